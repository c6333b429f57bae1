// Pieces shared by the kd-tree builders: float boxes, the prepared triangle
// input, and the writer that emits nodes and leaf lists in the memory-image
// encoding while enforcing its index limits.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "accel/kdtree.h"
#include "common/image_format.h"
#include "scene/scene.h"

namespace kdrt::accel {

struct Box {
  float lo[3];
  float hi[3];
};

inline double SurfaceArea(const Box& b) {
  const double dx = static_cast<double>(b.hi[0]) - b.lo[0];
  const double dy = static_cast<double>(b.hi[1]) - b.lo[1];
  const double dz = static_cast<double>(b.hi[2]) - b.lo[2];
  return 2.0 * (dx * dy + dy * dz + dz * dx);
}

inline int LongestAxis(const Box& b) {
  int axis = 0;
  for (int a = 1; a < 3; ++a) {
    if (b.hi[a] - b.lo[a] > b.hi[axis] - b.lo[axis]) axis = a;
  }
  return axis;
}

// Intersection of a box with a cell; callers only use it on boxes that touch
// the cell, so the result is never inverted.
inline Box ClampToCell(const Box& b, const Box& cell) {
  Box r;
  for (int a = 0; a < 3; ++a) {
    r.lo[a] = std::min(std::max(b.lo[a], cell.lo[a]), cell.hi[a]);
    r.hi[a] = std::max(std::min(b.hi[a], cell.hi[a]), cell.lo[a]);
  }
  return r;
}

// What the builders see of the scene: the non-degenerate triangles and their
// bounding boxes.
struct BuildInput {
  const std::vector<Triangle>* triangles = nullptr;
  std::vector<uint32_t> ids;   // non-degenerate triangle ids, ascending
  std::vector<Box> boxes;      // per scene triangle id (meaningful for `ids` only)
  std::vector<uint8_t> flat;   // per id: bit a set when all vertices share coordinate a
  Box bounds{};                // box of the non-degenerate triangles = root cell
  int max_depth = 0;           // resolved (never -1)
  std::string source;          // scene name for error messages
};

// Appends nodes depth-first. The caller reserves an inner node, builds the
// below subtree (which lands at index + 1), then finishes the inner node
// (the above child is the next node written) and builds the above subtree.
class TreeWriter {
 public:
  TreeWriter(std::vector<img::Node>* nodes, std::vector<uint32_t>* lists, std::string source)
      : nodes_(nodes), lists_(lists), source_(std::move(source)) {}

  uint32_t BeginInner() {
    const uint32_t index = NextIndex();
    nodes_->push_back(img::Node{0, 0});
    return index;
  }

  void FinishInner(uint32_t index, int axis, float split) {
    (*nodes_)[index] = img::Node::Inner(axis, split, NextIndex());
  }

  // Sorts `ids` ascending (the leaf-list contract) and appends the leaf,
  // counting it under `cause`.
  void AddLeaf(std::vector<uint32_t>& ids, LeafCause cause) {
    NextIndex();
    causes_.Add(cause, ids.size());
    if (ids.empty()) {
      nodes_->push_back(img::Node::Leaf(0, 0));
      return;
    }
    std::sort(ids.begin(), ids.end());
    if (ids.size() > img::kMaxIndex) Fail(kListTooLong);
    const uint32_t first = static_cast<uint32_t>(lists_->size());
    AppendList(ids.data(), ids.size());
    nodes_->push_back(img::Node::Leaf(first, static_cast<uint32_t>(ids.size())));
  }

  [[noreturn]] void Fail(const std::string& what) const;

  // For assembling a tree built in parts (the parallel SAH build): a node
  // or a leaf list as it is, with the same limits as above.
  void AppendNode(const img::Node& n) {
    NextIndex();
    nodes_->push_back(n);
  }
  void AppendList(const uint32_t* ids, size_t count) {
    if (lists_->size() + count > UINT32_MAX) Fail(kListTooLong);
    lists_->insert(lists_->end(), ids, ids + count);
  }
  uint32_t node_count() const { return static_cast<uint32_t>(nodes_->size()); }
  size_t list_count() const { return lists_->size(); }
  const std::string& source() const { return source_; }
  const LeafCauses& causes() const { return causes_; }
  // For the parts of a parallel build: their leaves, counted elsewhere.
  void MergeCauses(const LeafCauses& c) { causes_.Merge(c); }

 private:
  static constexpr const char* kListTooLong = "a leaf list does not fit the 30-bit count or the 32-bit list index";

  uint32_t NextIndex() const {
    if (nodes_->size() > img::kMaxChildIndex) {
      Fail("kd-tree has more than 2^28 nodes, too many for the memory image");
    }
    return static_cast<uint32_t>(nodes_->size());
  }

  std::vector<img::Node>* nodes_;
  std::vector<uint32_t>* lists_;
  std::string source_;
  LeafCauses causes_;
};

// Box of the triangle clipped to `cell` (Sutherland-Hodgman in double,
// rounded outward to float, clamped to the triangle's box and to the cell).
// Returns false when the triangle does not touch the cell. Conservative:
// every point of the triangle inside the closed cell lies inside the
// returned box.
bool ClippedTriangleBox(const Triangle& t, const Box& cell, Box* out);

// The builders. Each appends exactly one subtree (the whole tree) to writer.
// The SAH build reads options' costs, leaf size, perfect splits, automatic
// clipping and minimum split gain (the depth limit is input.max_depth) and runs on
// options.threads threads (0: all cores); the tree is the serial build's,
// node for node.
void BuildSahTree(const BuildInput& input, const BuildOptions& options, TreeWriter* writer);
void BuildSimpleTree(const BuildInput& input, bool median, int max_leaf_prims,
                     TreeWriter* writer);

}  // namespace kdrt::accel
