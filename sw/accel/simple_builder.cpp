// Median and midpoint kd-trees: the cheap reference splitters. Both split the
// longest axis of the node cell; the median splitter at the median of the
// triangles' box centres (boxes clamped to the cell), the midpoint splitter in
// the middle of the cell. Classification as in the SAH builder: below iff the
// (clamped) box extends strictly below the plane, above iff strictly above; a
// triangle lying in the plane goes below.
#include <algorithm>
#include <vector>

#include "accel/build_util.h"

namespace kdrt::accel {
namespace {

class SimpleBuilder {
 public:
  SimpleBuilder(const BuildInput& input, bool median, int max_leaf_prims, TreeWriter* writer)
      : in_(input), median_(median), max_leaf_prims_(max_leaf_prims), writer_(writer) {}

  void Run() {
    ids_ = in_.ids;
    Build(0, ids_.size(), in_.bounds, 0);
  }

 private:
  static bool StrictlyInside(float s, const Box& cell, int axis) {
    return s > cell.lo[axis] && s < cell.hi[axis];
  }

  // Extends strictly below s, or lies in the plane s.
  static bool GoesBelow(const Box& b, int axis, float s) {
    return b.lo[axis] < s || (b.lo[axis] == s && b.hi[axis] == s);
  }

  static float Midpoint(const Box& cell, int axis) {
    return static_cast<float>(0.5 * (static_cast<double>(cell.lo[axis]) + cell.hi[axis]));
  }

  // Upper median of the clamped box centres; the midpoint when the median
  // sits on the cell boundary (e.g. most triangles flat on a cell face),
  // where it would cut off a zero-volume child.
  float MedianSplit(size_t begin, size_t end, const Box& cell, int axis) {
    centres_.clear();
    for (size_t i = begin; i < end; ++i) {
      const Box b = ClampToCell(in_.boxes[ids_[i]], cell);
      centres_.push_back(0.5 * (static_cast<double>(b.lo[axis]) + b.hi[axis]));
    }
    auto mid = centres_.begin() + centres_.size() / 2;
    std::nth_element(centres_.begin(), mid, centres_.end());
    const float s = static_cast<float>(*mid);
    return StrictlyInside(s, cell, axis) ? s : Midpoint(cell, axis);
  }

  void Build(size_t begin, size_t end, const Box& cell, int depth) {
    const size_t n = end - begin;
    if (n <= static_cast<size_t>(max_leaf_prims_) || depth >= in_.max_depth) {
      MakeLeaf(begin, end, n <= static_cast<size_t>(max_leaf_prims_) ? LeafCause::kFew : LeafCause::kDepth);
      return;
    }
    const int axis = LongestAxis(cell);
    const float s = median_ ? MedianSplit(begin, end, cell, axis) : Midpoint(cell, axis);
    if (!StrictlyInside(s, cell, axis)) {
      MakeLeaf(begin, end, LeafCause::kNoPlane);
      return;
    }
    // Children go on top of the id stack: below ids, then above ids.
    const size_t below_begin = ids_.size();
    for (size_t i = begin; i < end; ++i) {
      const uint32_t id = ids_[i];
      if (GoesBelow(ClampToCell(in_.boxes[id], cell), axis, s)) ids_.push_back(id);
    }
    const size_t above_begin = ids_.size();
    for (size_t i = begin; i < end; ++i) {
      const uint32_t id = ids_[i];
      if (ClampToCell(in_.boxes[id], cell).hi[axis] > s) ids_.push_back(id);
    }
    const size_t above_end = ids_.size();
    if (above_begin - below_begin == n && above_end - above_begin == n) {
      ids_.resize(below_begin);
      MakeLeaf(begin, end, LeafCause::kNoGain);
      return;
    }
    Box below_cell = cell;
    below_cell.hi[axis] = s;
    Box above_cell = cell;
    above_cell.lo[axis] = s;
    const uint32_t index = writer_->BeginInner();
    Build(below_begin, above_begin, below_cell, depth + 1);
    writer_->FinishInner(index, axis, s);
    Build(above_begin, above_end, above_cell, depth + 1);
    ids_.resize(below_begin);
  }

  void MakeLeaf(size_t begin, size_t end, LeafCause cause) {
    leaf_ids_.assign(ids_.begin() + begin, ids_.begin() + end);
    writer_->AddLeaf(leaf_ids_, cause);
  }

  const BuildInput& in_;
  const bool median_;
  const int max_leaf_prims_;
  TreeWriter* writer_;
  std::vector<uint32_t> ids_;  // stack of node triangle lists
  std::vector<double> centres_;
  std::vector<uint32_t> leaf_ids_;
};

}  // namespace

void BuildSimpleTree(const BuildInput& input, bool median, int max_leaf_prims,
                     TreeWriter* writer) {
  SimpleBuilder(input, median, max_leaf_prims, writer).Run();
}

}  // namespace kdrt::accel
