// The octree backend (octree.cpp), declared here so its tests can walk the
// tree: the lecture's "oct-tree" spatial hierarchy over the kd-tree's scene
// box, every cell split at its centre on all three axes, built by the
// lecture's insert rule (a cell with more than max_prims triangles splits
// while shallower than the depth limit) and traced front to back.
#pragma once

#include <cstdint>
#include <vector>

#include "structures/structure.h"

namespace kdrt {
namespace octree {

constexpr uint32_t kLeafFlag = 0x80000000u;
constexpr int kMaxDepth = 32;  // CheckStructureOptions' bound on octree_max_depth

// 8 bytes. Only non-empty children are stored: an inner node holds the mask
// of its non-empty children (bit c: child c, whose bit k is set when it lies
// above the centre on axis k) and the index of the first of them; they
// follow each other in child order. A leaf holds kLeafFlag | count and the
// index of its first reference. The planes are not stored: the traversal
// carries each cell's box and recomputes the centre (CellCentre).
struct Node {
  uint32_t first;
  uint32_t meta;

  bool IsLeaf() const { return (meta & kLeafFlag) != 0; }
  uint32_t Count() const { return meta & ~kLeafFlag; }
  uint32_t FirstRef() const { return first; }
  uint32_t ChildMask() const { return meta & 0xFFu; }
  bool HasChild(int c) const { return (meta >> c) & 1u; }
  uint32_t Child(int c) const {  // HasChild(c) must hold
    return first + static_cast<uint32_t>(__builtin_popcount(meta & ((1u << c) - 1u)));
  }
  static Node Leaf(uint32_t first_ref, uint32_t count) { return Node{first_ref, kLeafFlag | count}; }
  static Node Inner(uint32_t first_child, uint32_t mask) { return Node{first_child, mask}; }
};

// A cell's box in the frame. Its planes are fp32 values (never subnormal),
// and the traversal computes its distances from exactly the values the build
// binned against.
struct Cell {
  float lo[3], hi[3];
};

// The cell's split point: each axis' centre, (lo + hi) / 2 rounded once to
// fp32 (exact halving of the rounded sum), a subnormal flushed to zero so
// the build (IEEE mode) and the fp32 trace (FTZ/DAZ) compute the same
// planes. An axis too narrow to split (its centre rounds onto a bound, a
// flat scene's thin axis) gets mid = hi, so the lower children span all of
// it and the upper ones are empty. False if no axis can be split.
inline bool CellCentre(const Cell& cell, float mid[3]) {
  bool any = false;
  for (int k = 0; k < 3; ++k) {
    const float m = fp::NativeF32Arith::Load((cell.lo[k] + cell.hi[k]) * 0.5f);
    const bool split = cell.lo[k] < m && m < cell.hi[k];
    mid[k] = split ? m : cell.hi[k];
    any = any || split;
  }
  return any;
}

inline Cell ChildCell(const Cell& cell, const float mid[3], int child) {
  Cell c;
  for (int k = 0; k < 3; ++k) {
    const bool upper = (child >> k) & 1;
    c.lo[k] = upper ? mid[k] : cell.lo[k];
    c.hi[k] = upper ? cell.hi[k] : mid[k];
  }
  return c;
}

// Akenine-Moller's separating-axis test in double: true if the triangle and
// the closed box [lo, hi] share a point (touching counts).
bool TriangleOverlapsBox(const img::TriangleRecord& tri, const double lo[3], const double hi[3]);

// How far the binning widens every cell on each side, in frame units: a few
// dozen fp32 ulps of the scene's coordinates, above the distance by which a
// ray the watertight test reports as hitting a triangle (rounding) can pass
// beside it.
double BinningMargin(const accel::Box& bounds);

// The depth limit when octree_max_depth is -1: round((8 + 1.3 log2 N) / 3)
// + 1, capped at kMaxDepth (the kd-tree's rule counted in octree levels).
int DefaultMaxDepth(size_t triangles);

// The build's guards against blow-up, besides the depth limit. A cell of n
// triangles whose children would hold child_sum references in all splits
// only if
//  - the split pays (SplitPays): a random ray crossing the cell would test
//    fewer triangles (every child getting (nearly) all triangles fails);
//  - child_sum fits the cell's duplication budget. The root's budget is
//    kDuplicationBudget references per triangle; a split hands each child
//    the share of its parent's budget that its list has of child_sum. So the
//    total stays below kDuplicationBudget x N, and geometry that no split
//    separates (long slivers, fans around a shared vertex, thin cylinders:
//    each level doubling the references) stops after a few levels, while
//    splits that separate triangles (child_sum near n) cost nearly nothing.
bool SplitPays(size_t n, size_t child_sum);
constexpr double kDuplicationBudget = 32.0;

}  // namespace octree

class Octree : public StructureBase<Octree> {
 public:
  Octree(const StructureInput& input, const StructureOptions& options);
  AccelKind kind() const override;  // out of line: the vtable lives in octree.cpp
  bool uses_mailbox() const override { return true; }

  template <class A>
  void TraceT(const A& a, const RaySetup<A>& r, Query query, TraceResult<A>& best, TraceScratch& scratch) const;

  // For tests: node 0 is the root, whose cell is root_cell() (the scene box,
  // subnormal bounds flushed to zero).
  const std::vector<octree::Node>& nodes() const { return nodes_; }
  const std::vector<uint32_t>& refs() const { return refs_; }
  const octree::Cell& root_cell() const { return root_; }
  int max_prims() const { return max_prims_; }
  int depth_limit() const { return depth_limit_; }
  double margin() const { return margin_; }

 private:
  std::vector<octree::Node> nodes_;
  std::vector<uint32_t> refs_;  // leaf lists, ascending ids within each
  octree::Cell root_;
  int max_prims_;
  int depth_limit_;
  double margin_;
};

}  // namespace kdrt
