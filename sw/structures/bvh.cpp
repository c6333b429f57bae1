// The lecture's hierarchical bounding volumes, built top-down with the
// surface area heuristic: a binned SAH BVH (Wald 2007, "On fast construction
// of SAH-based bounding volume hierarchies"; the rules of pbrt-v3's BVHAccel
// with SplitMethod::SAH), one reference per triangle, so no mailbox.
//
// Build: the triangles' boxes are copied into one array that is partitioned
// in place; each node bins its centroids into options.bvh_bins bins along
// every axis with a centroid extent, sweeps the bins for the cheapest split
// and becomes a leaf when that split is not cheaper than testing all its
// triangles (cost kTraversalCost + (N_l A_l + N_r A_r) / A against N).
//
// Traversal: a stack, the near child first (by the split axis and the sign
// of the ray's direction), a conservative slab test against [tmin, best t].
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "common/error.h"
#include "structures/bvh_tree.h"
#include "structures/structure.h"

namespace kdrt {
namespace {

using accel::Box;

// Cost of visiting a node relative to one triangle test (pbrt's 1/8).
constexpr double kTraversalCost = 0.125;
// Traversal stack entries: at most one push per level, and no tree is deeper
// than kBvhMaxSahDepth + 23 (bvh_tree.h; at most 2^30 triangles).
constexpr int kBvhStackSize = kBvhMaxSahDepth + 32;
constexpr size_t kBvhMaxTriangles = size_t{1} << 30;

// ---------------------------------------------------------------------------
// Build

struct PrimRef {
  float lo[3];
  float hi[3];
  uint32_t id;
};

// Twice the centroid: exact in double for any float box.
inline double Centroid2(const PrimRef& p, int axis) {
  return static_cast<double>(p.lo[axis]) + static_cast<double>(p.hi[axis]);
}

struct CentroidBounds {
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity()};
  double Extent(int axis) const { return hi[axis] - lo[axis]; }
};

Box EmptyBox() {
  Box b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = std::numeric_limits<float>::infinity();
    b.hi[a] = -std::numeric_limits<float>::infinity();
  }
  return b;
}

inline void Grow(Box& b, const float lo[3], const float hi[3]) {
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = std::min(b.lo[a], lo[a]);
    b.hi[a] = std::max(b.hi[a], hi[a]);
  }
}

// A range's box and centroid bounds, grown one triangle at a time.
struct RangeInfo {
  Box box = EmptyBox();
  CentroidBounds cb;
  void Add(const PrimRef& p) {
    Grow(box, p.lo, p.hi);
    for (int a = 0; a < 3; ++a) {
      const double c = Centroid2(p, a);
      cb.lo[a] = std::min(cb.lo[a], c);
      cb.hi[a] = std::max(cb.hi[a], c);
    }
  }
};

// The node boxes are read without fp::NativeF32Arith::Load (which flushes
// subnormals), so they hold no subnormals: those are rounded outwards to
// zero or to the smallest normal, which only grows the box. Decided on the
// bits, so the caller's FTZ/DAZ mode cannot change it.
bool IsSubnormal(float x) {
  uint32_t u;
  std::memcpy(&u, &x, sizeof u);
  return (u & 0x7F800000u) == 0 && (u & 0x007FFFFFu) != 0;
}
float RoundDownToNormal(float x) {
  if (!IsSubnormal(x)) return x;
  return std::signbit(x) ? -std::numeric_limits<float>::min() : 0.0f;
}
float RoundUpToNormal(float x) {
  if (!IsSubnormal(x)) return x;
  return std::signbit(x) ? -0.0f : std::numeric_limits<float>::min();
}

struct Bin {
  Box box;
  uint32_t count;
};

struct Split {
  int bins = 0;  // bins per axis used for the node
  int axis = -1;
  int bin = 0;   // triangles in bins < bin go to the first child
  double cost = std::numeric_limits<double>::infinity();  // N_l A_l + N_r A_r
};

// Maps centroids to bins along each axis of a node, the same way in the
// binning pass and in the partition (the child boxes do not depend on it
// matching, but the SAH counts do).
class Binner {
 public:
  Binner(const CentroidBounds& cb, int bins) : bins_(bins) {
    for (int a = 0; a < 3; ++a) {
      lo_[a] = cb.lo[a];
      const double extent = cb.Extent(a);
      scale_[a] = extent > 0 ? bins / extent : 0.0;
    }
  }
  bool Usable(int axis) const { return scale_[axis] > 0; }
  int operator()(const PrimRef& p, int axis) const {
    const int b = static_cast<int>((Centroid2(p, axis) - lo_[axis]) * scale_[axis]);
    return std::min(b, bins_ - 1);
  }

 private:
  int bins_;
  double lo_[3];
  double scale_[3];
};

class BvhBuilder {
 public:
  BvhBuilder(const StructureInput& input, int bins) : bins_(bins), bin_store_(3 * bins), right_area_(bins),
                                                      right_count_(bins) {
    prims_.reserve(input.ids.size());
    for (uint32_t id : input.ids) {
      const Box& b = input.boxes[id];
      prims_.push_back(PrimRef{{b.lo[0], b.lo[1], b.lo[2]}, {b.hi[0], b.hi[1], b.hi[2]}, id});
    }
  }

  void Build(BvhTree* tree, StructureStats* stats) {
    tree_ = tree;
    if (!prims_.empty()) {
      RangeInfo root;
      for (const PrimRef& p : prims_) root.Add(p);
      root_area_ = accel::SurfaceArea(root.box);
      BuildNode(0, static_cast<uint32_t>(prims_.size()), root, 0);
    }
    tree->ids.resize(prims_.size());
    for (size_t i = 0; i < prims_.size(); ++i) tree->ids[i] = prims_[i].id;
    stats->nodes = tree->nodes.size();
    stats->leaves = leaves_;
    stats->references = prims_.size();
    stats->max_depth = max_depth_;
    stats->max_leaf_prims = max_leaf_prims_;
    stats->memory_bytes = tree->nodes.size() * sizeof(BvhNode) + tree->ids.size() * sizeof(uint32_t);
    stats->extra["bins"] = bins_;
    stats->extra["avg_leaf_prims"] = leaves_ ? static_cast<double>(prims_.size()) / leaves_ : 0.0;
    stats->extra["sah_cost"] = sah_cost_;
  }

 private:
  // Emits the subtree of prims_[begin, end) in depth-first order.
  void BuildNode(uint32_t begin, uint32_t end, const RangeInfo& info, uint32_t depth) {
    const uint32_t index = static_cast<uint32_t>(tree_->nodes.size());
    tree_->nodes.push_back(MakeNode(info.box));
    max_depth_ = std::max(max_depth_, depth);
    const uint32_t n = end - begin;
    const double area = accel::SurfaceArea(info.box);
    const double rel_area = root_area_ > 0 ? area / root_area_ : 1.0;

    RangeInfo left, right;
    uint32_t mid = 0;
    int axis = 0;
    if (n == 1) {
      return MakeLeaf(index, begin, n, rel_area);
    }
    const bool separable = info.cb.Extent(0) > 0 || info.cb.Extent(1) > 0 || info.cb.Extent(2) > 0;
    const Split split = depth < kBvhMaxSahDepth && separable ? FindSahSplit(begin, end, info) : Split{};
    if (split.axis >= 0) {
      const double split_cost = kTraversalCost + (area > 0 ? split.cost / area : n);
      if (n <= kBvhMaxLeafPrims && split_cost >= n) return MakeLeaf(index, begin, n, rel_area);
      axis = split.axis;
      const Binner binner(info.cb, split.bins);
      mid = Partition(begin, end, [&](const PrimRef& p) { return binner(p, split.axis) < split.bin; }, &left,
                      &right);
    } else {
      // Coincident centroids (no split separates them) or too deep.
      if (n <= kBvhMaxLeafPrims) return MakeLeaf(index, begin, n, rel_area);
      axis = LargestAxis(info.cb);
      mid = MedianSplit(begin, end, axis, &left, &right);
    }
    sah_cost_ += kTraversalCost * rel_area;
    tree_->nodes[index].axis = static_cast<uint8_t>(axis);
    BuildNode(begin, mid, left, depth + 1);
    tree_->nodes[index].offset = static_cast<uint32_t>(tree_->nodes.size());
    BuildNode(mid, end, right, depth + 1);
  }

  static BvhNode MakeNode(const Box& b) {
    BvhNode node{};
    for (int a = 0; a < 3; ++a) {
      node.box[a] = RoundDownToNormal(b.lo[a]);
      node.box[3 + a] = RoundUpToNormal(b.hi[a]);
    }
    return node;
  }

  void MakeLeaf(uint32_t index, uint32_t begin, uint32_t n, double rel_area) {
    BvhNode& node = tree_->nodes[index];
    node.offset = begin;
    node.count = static_cast<uint16_t>(n);
    ++leaves_;
    max_leaf_prims_ = std::max(max_leaf_prims_, n);
    sah_cost_ += n * rel_area;
  }

  static int LargestAxis(const CentroidBounds& cb) {
    int axis = 0;
    for (int a = 1; a < 3; ++a) {
      if (cb.Extent(a) > cb.Extent(axis)) axis = a;
    }
    return axis;
  }

  // The cheapest split over all axes and bin boundaries (first one on ties).
  // Only called when some axis has a centroid extent, and then that axis has
  // its first and last bins occupied, so the result always splits.
  Split FindSahSplit(uint32_t begin, uint32_t end, const RangeInfo& info) {
    // A small node needs no more bins than a few per triangle; clearing and
    // sweeping all of them would dominate the build near the leaves.
    const int bins = std::min<int>(bins_, std::max<uint32_t>(4, 4 * (end - begin)));
    const Binner binner(info.cb, bins);
    std::fill(bin_store_.begin(), bin_store_.begin() + 3 * bins, Bin{EmptyBox(), 0});
    const bool use[3] = {binner.Usable(0), binner.Usable(1), binner.Usable(2)};
    for (uint32_t i = begin; i < end; ++i) {
      const PrimRef& p = prims_[i];
      for (int a = 0; a < 3; ++a) {
        if (!use[a]) continue;
        Bin& b = bin_store_[a * bins + binner(p, a)];
        ++b.count;
        Grow(b.box, p.lo, p.hi);
      }
    }
    Split best;
    best.bins = bins;
    for (int a = 0; a < 3; ++a) {
      if (use[a]) SweepAxis(a, bins, &best);
    }
    return best;
  }

  void SweepAxis(int axis, int n, Split* best) {
    const Bin* bins = &bin_store_[axis * n];
    Box acc = EmptyBox();
    uint32_t count = 0;
    for (int j = n - 1; j >= 1; --j) {
      Grow(acc, bins[j].box.lo, bins[j].box.hi);
      count += bins[j].count;
      right_count_[j] = count;
      right_area_[j] = count ? accel::SurfaceArea(acc) : 0.0;
    }
    acc = EmptyBox();
    count = 0;
    for (int j = 0; j + 1 < n; ++j) {
      Grow(acc, bins[j].box.lo, bins[j].box.hi);
      count += bins[j].count;
      if (count == 0 || right_count_[j + 1] == 0) continue;
      const double cost = count * accel::SurfaceArea(acc) + right_count_[j + 1] * right_area_[j + 1];
      if (cost < best->cost) *best = Split{n, axis, j + 1, cost};
    }
  }

  // In-place partition of prims_[begin, end) into the triangles for which
  // goes_first holds and the rest; returns the boundary and the two ranges'
  // boxes and centroid bounds.
  template <class Pred>
  uint32_t Partition(uint32_t begin, uint32_t end, const Pred& goes_first, RangeInfo* first, RangeInfo* second) {
    uint32_t i = begin, j = end;
    for (;;) {
      while (i < j && goes_first(prims_[i])) first->Add(prims_[i++]);
      while (i < j && !goes_first(prims_[j - 1])) second->Add(prims_[--j]);
      if (i >= j) break;
      std::swap(prims_[i], prims_[j - 1]);
      first->Add(prims_[i++]);
      second->Add(prims_[--j]);
    }
    return i;
  }

  // Splits at the median centroid along `axis` (ties by id, so the order is
  // defined); both halves non-empty.
  uint32_t MedianSplit(uint32_t begin, uint32_t end, int axis, RangeInfo* first, RangeInfo* second) {
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(prims_.begin() + begin, prims_.begin() + mid, prims_.begin() + end,
                     [axis](const PrimRef& x, const PrimRef& y) {
                       const double cx = Centroid2(x, axis), cy = Centroid2(y, axis);
                       return cx < cy || (cx == cy && x.id < y.id);
                     });
    for (uint32_t i = begin; i < mid; ++i) first->Add(prims_[i]);
    for (uint32_t i = mid; i < end; ++i) second->Add(prims_[i]);
    return mid;
  }

  const int bins_;
  std::vector<PrimRef> prims_;
  std::vector<Bin> bin_store_;  // bins_ per axis, reused by every node
  std::vector<double> right_area_;
  std::vector<uint32_t> right_count_;
  BvhTree* tree_ = nullptr;
  double root_area_ = 0;
  double sah_cost_ = 0;
  uint64_t leaves_ = 0;
  uint32_t max_depth_ = 0;
  uint32_t max_leaf_prims_ = 0;
};

// ---------------------------------------------------------------------------
// Traversal

// Node box planes are normal floats or zeros (MakeNode), which
// NativeF32Arith::Load returns unchanged: skip its bit masking.
inline float LoadPlane(const fp::NativeF32Arith&, float x) { return x; }
template <class A>
typename A::T LoadPlane(const A& a, float x) {
  return a.Load(x);
}

// Per-ray constants of the slab test: which of a node's planes is entered
// first on each axis.
struct SlabOrder {
  int near[3], far[3];
  bool neg[3];
};

template <class A>
SlabOrder MakeSlabOrder(const A& a, const RaySetup<A>& r) {
  SlabOrder s;
  for (int i = 0; i < 3; ++i) {
    s.neg[i] = a.IsNeg(r.inv_d[i]);
    s.near[i] = s.neg[i] ? 3 + i : i;
    s.far[i] = s.neg[i] ? i : 3 + i;
  }
  return s;
}

// Pruning a node by the best hit needs more slack than the slab test's own:
// the watertight test's t is not within a few ulps of the distance to the
// triangle's box. Its error is a few ulps of the vertices' distances along
// the ray (up to the frame's reach 2^kFrameReachLog2, trace/frame.h),
// however small t is: in the gears scene a ray starting just above two
// overlapping coplanar triangles gets t 9 and 13 ulps short of their
// plane's distance, so with 4 ulps of slack the box of the closer one was
// skipped once the other had hit. So the range a node must meet is
// [tmin, best t] widened by this margin (kBoxMarginUlps encodings of
// 2^kFrameReachLog2 in A's format: about 5e-4 in fp32, a small fraction of
// a triangle in the frame) and by kBestSlackUlps encodings of each end (the
// relative error of a t without cancellation). Wider only costs the
// occasional extra node just behind a hit (about 1 % more nodes on gears).
constexpr uint32_t kBoxMarginUlps = 256;
constexpr uint32_t kBestSlackUlps = 16;

template <class A>
typename A::T BoxMargin(const A& a) {
  const typename A::T reach = a.Load(static_cast<float>(1 << kFrameReachLog2));
  return a.Sub(a.NudgeUp(reach, kBoxMarginUlps), reach);
}

// The ray's range a node box must meet: [lo, hi] from [tmin, best t].
template <class A>
struct RayRange {
  typename A::T lo, hi;
};

template <class A>
inline typename A::T WidenUpBy(const A& a, typename A::T x, uint32_t ulps) {
  return a.IsNeg(x) ? a.Neg(a.NudgeDown(a.Neg(x), ulps)) : a.NudgeUp(x, ulps);
}
template <class A>
inline typename A::T WidenDownBy(const A& a, typename A::T x, uint32_t ulps) {
  return a.IsNeg(x) ? a.Neg(a.NudgeUp(a.Neg(x), ulps)) : a.NudgeDown(x, ulps);
}

template <class A>
inline typename A::T RangeEnd(const A& a, typename A::T best_t, typename A::T margin) {
  return WidenUpBy(a, a.Add(best_t, margin), kBestSlackUlps);
}

// t0 - slack <= t1 + slack, both ends moved kTraversalSlackUlps encodings
// outwards whatever their sign, as ClipToBox widens a cell.
template <class A>
inline bool WidenedLe(const A& a, typename A::T t0, typename A::T t1) {
  return a.Le(WidenDownBy(a, t0, kTraversalSlackUlps), WidenUpBy(a, t1, kTraversalSlackUlps));
}
// The same on native floats without branches (10 % of the trace time): on
// the sign-magnitude key of the encoding (+0 and -0 both 0) a step of one is
// one encoding. It differs from the nudges only next to zero, where it
// steps on through the subnormals and across zero instead of jumping to
// zero; the slab distances' rounding errors there are below one encoding.
inline int64_t OrderedKey(float x) {
  uint32_t u;
  std::memcpy(&u, &x, sizeof u);
  const int64_t mag = u & 0x7FFFFFFFu;
  return (u >> 31) ? -mag : mag;
}
inline int64_t OrderedKey(double x) {
  uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  const int64_t mag = static_cast<int64_t>(u & 0x7FFFFFFFFFFFFFFFull);
  return (u >> 63) ? -mag : mag;
}
inline bool WidenedLe(const fp::NativeF32Arith&, float t0, float t1) {
  return OrderedKey(t0) <= OrderedKey(t1) + 2 * static_cast<int64_t>(kTraversalSlackUlps);
}
inline bool WidenedLe(const fp::NativeF64Arith&, double t0, double t1) {
  return OrderedKey(t0) <= OrderedKey(t1) + 2 * static_cast<int64_t>(kTraversalSlackUlps);
}

// True if the ray may meet a triangle of the node within `range`: the slab
// interval clipped to it, widened like ClipToBox (trace/traversal.h), is not
// empty. A slab whose distances are NaN (the ray parallel to it and in one
// of its planes) does not narrow the interval.
template <class A>
inline bool EntersBox(const A& a, const RaySetup<A>& r, const SlabOrder& s, const BvhNode& node,
                      const RayRange<A>& range) {
  using T = typename A::T;
  T t0 = range.lo, t1 = range.hi;
  for (int i = 0; i < 3; ++i) {
    const T tn = a.Mul(a.Sub(LoadPlane(a, node.box[s.near[i]]), r.o[i]), r.inv_d[i]);
    const T tf = a.Mul(a.Sub(LoadPlane(a, node.box[s.far[i]]), r.o[i]), r.inv_d[i]);
    if (a.Lt(t0, tn)) t0 = tn;
    if (a.Lt(tf, t1)) t1 = tf;
  }
  // A ray parallel to a slab and outside it gets t0 = +inf or t1 = -inf, a
  // miss even for tmax = inf: the direction's largest component (in [1, 2)
  // in the frame) always makes t1 finite.
  return WidenedLe(a, t0, t1);
}

class Bvh final : public StructureBase<Bvh> {
 public:
  Bvh(const StructureInput& input, BvhTree tree, StructureStats stats)
      : StructureBase<Bvh>(input), tree_(std::move(tree)) {
    stats_ = std::move(stats);
  }
  AccelKind kind() const override { return AccelKind::kBvh; }
  bool uses_mailbox() const override { return false; }
  const BvhTree& tree() const { return tree_; }

  // Counters: `nodes` counts the nodes whose box test the ray passed (inner
  // nodes and leaves; a box test that fails is not counted), `leaves` the
  // leaves among them (every leaf holds triangles).
  template <class A>
  void TraceT(const A& a, const RaySetup<A>& r, Query query, TraceResult<A>& best, TraceScratch& scratch) const {
    if (tree_.nodes.empty()) return;
    const BvhNode* nodes = tree_.nodes.data();
    const uint32_t* ids = tree_.ids.data();
    const img::TriangleRecord* triangles = input_->triangles.data();
    const SlabOrder slabs = MakeSlabOrder(a, r);
    const typename A::T margin = BoxMargin(a);
    RayRange<A> range{WidenDownBy(a, a.Sub(r.tmin, margin), kBestSlackUlps), RangeEnd(a, best.t, margin)};
    AccelCounters c;
    uint32_t stack[kBvhStackSize];
    int sp = 0;
    uint32_t index = 0;
    for (;;) {
      const BvhNode& node = nodes[index];
      if (EntersBox(a, r, slabs, node, range)) {
        ++c.nodes;
        if (!node.IsLeaf()) {
          // Near child first: the first child holds the lower centroids.
          const bool second_first = slabs.neg[node.axis];
          stack[sp++] = second_first ? index + 1 : node.offset;
          index = second_first ? node.offset : index + 1;
          continue;
        }
        ++c.leaves;
        for (uint32_t k = 0; k < node.count; ++k) {
          const uint32_t id = ids[node.offset + k];
          TestTriangle(a, r, triangles[id], id, best, c);
          if (query == Query::kAny && best.prim != kNoPrim) {
            scratch.counters += c;
            return;
          }
        }
        range.hi = RangeEnd(a, best.t, margin);
      }
      if (sp == 0) break;
      index = stack[--sp];
    }
    scratch.counters += c;
  }

 private:
  BvhTree tree_;
};

}  // namespace

std::unique_ptr<Structure> BuildBvh(const StructureInput& input, const StructureOptions& options) {
  CheckStructureOptions(options);
  if (input.ids.size() > kBvhMaxTriangles) throw InputError("bvh: more than 2^30 triangles");
  return Structure::Timed([&] {
    BvhTree tree;
    StructureStats stats;
    BvhBuilder(input, options.bvh_bins).Build(&tree, &stats);
    return std::make_unique<Bvh>(input, std::move(tree), std::move(stats));
  });
}

const BvhTree* BvhTreeOf(const Structure& s) {
  const Bvh* bvh = dynamic_cast<const Bvh*>(&s);
  return bvh ? &bvh->tree() : nullptr;
}

}  // namespace kdrt
