// The octree backend (octree_tree.h).
//
// Build: top down and depth first, by the rules in octree_tree.h. The
// references of the cells on the current path live in one work array; a
// cell that splits appends its children's lists to it, builds them and
// truncates the array again, so no node owns a heap allocation. A triangle
// goes to every child its triangle (not its box) overlaps, the child widened
// by the binning margin.
//
// Trace: an inner node is crossed as the three levels of a kd-tree over its
// mid planes (x, then y, then z) would be, with the kd-tree's rule per plane
// (StepInnerNode in trace/traversal.h): the same slack-widened intervals, so
// a ray grazing a plane, an edge or the centre visits every child near it.
// The up to eight children come out front to back and go on an explicit
// stack. After a leaf the ray stops if its best hit lies within the leaf's
// (widened) exit, taken from the leaf's box (CellExit).
#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "structures/octree_tree.h"
#include "structures/tri_box.h"

namespace kdrt {
namespace octree {
namespace {

// Builds into the given arrays; see the file comment.
class Builder {
 public:
  Builder(const StructureInput& in, int max_prims, int depth_limit, double margin, std::vector<Node>* nodes,
          std::vector<uint32_t>* refs)
      : in_(in), max_prims_(max_prims), depth_limit_(depth_limit), margin_(margin), nodes_(*nodes), refs_(*refs) {}

  void Run(const Cell& root) {
    work_.assign(in_.ids.begin(), in_.ids.end());
    refs_.reserve(in_.ids.size() * 2);
    nodes_.assign(1, Node::Leaf(0, 0));
    BuildNode(0, root, 0, work_.size(), 0, kDuplicationBudget * double(work_.size()));
  }

  uint32_t max_depth() const { return max_depth_; }
  uint64_t leaves() const { return leaves_; }
  uint32_t max_leaf_prims() const { return max_leaf_prims_; }
  uint64_t oversized_leaves() const { return oversized_; }

 private:
  void BuildNode(uint32_t index, const Cell& cell, size_t begin, size_t end, int depth, double budget) {
    const size_t n = end - begin;
    float mid[3];
    if (n <= static_cast<size_t>(max_prims_) || depth >= depth_limit_ || !CellCentre(cell, mid)) {
      return MakeLeaf(index, begin, end, depth);
    }
    uint32_t count[8] = {};
    masks_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const uint32_t m = ChildMask(work_[begin + i], cell, mid);
      masks_[i] = static_cast<uint8_t>(m);
      for (int c = 0; c < 8; ++c) count[c] += (m >> c) & 1u;
    }
    size_t sum = 0;
    uint32_t nonempty = 0;
    for (int c = 0; c < 8; ++c) {
      sum += count[c];
      if (count[c] > 0) nonempty |= 1u << c;
    }
    if (!SplitPays(n, sum) || double(sum) > budget) return MakeLeaf(index, begin, end, depth);

    // The children's lists, appended to the work array in child order.
    const size_t base = work_.size();
    size_t start[8], fill[8];
    for (int c = 0, at = 0; c < 8; at += count[c], ++c) start[c] = fill[c] = base + at;
    work_.resize(base + sum);
    for (size_t i = 0; i < n; ++i) {
      const uint32_t id = work_[begin + i];
      for (uint32_t m = masks_[i]; m != 0; m &= m - 1) work_[fill[__builtin_ctz(m)]++] = id;
    }
    const uint32_t first = static_cast<uint32_t>(nodes_.size());
    if (first > kLeafFlag - 8) throw InputError("octree: more than 2^31 nodes");
    nodes_.resize(first + __builtin_popcount(nonempty));
    nodes_[index] = Node::Inner(first, nonempty);
    for (int c = 0, slot = 0; c < 8; ++c) {
      if (count[c] == 0) continue;
      BuildNode(first + slot++, ChildCell(cell, mid, c), start[c], start[c] + count[c], depth + 1,
                budget * double(count[c]) / double(sum));
    }
    work_.resize(base);
  }

  void MakeLeaf(uint32_t index, size_t begin, size_t end, int depth) {
    const uint32_t n = static_cast<uint32_t>(end - begin);
    max_depth_ = std::max(max_depth_, static_cast<uint32_t>(depth));
    if (refs_.size() + n > kLeafFlag) throw InputError("octree: more than 2^31 triangle references");
    nodes_[index] = Node::Leaf(static_cast<uint32_t>(refs_.size()), n);
    if (n == 0) return;  // only an empty scene's root
    refs_.insert(refs_.end(), work_.begin() + begin, work_.begin() + end);
    ++leaves_;
    max_leaf_prims_ = std::max(max_leaf_prims_, n);
    if (n > static_cast<uint32_t>(max_prims_)) ++oversized_;
  }

  // Bit c set: the triangle overlaps child c (widened). The triangle
  // overlaps the widened cell, so when its box reaches into one child only
  // it overlaps that child and needs no test.
  uint32_t ChildMask(uint32_t id, const Cell& cell, const float mid[3]) const {
    const accel::Box& b = in_.boxes[id];
    uint32_t sides[3];  // bit 0: reaches the lower half, bit 1: the upper half
    bool single = true;
    for (int k = 0; k < 3; ++k) {
      if (mid[k] == cell.hi[k]) {  // axis not split: all in the lower half
        sides[k] = 1u;
        continue;
      }
      sides[k] = (double(b.lo[k]) <= double(mid[k]) + margin_ ? 1u : 0u) |
                 (double(b.hi[k]) >= double(mid[k]) - margin_ ? 2u : 0u);
      single = single && sides[k] != 3u;
    }
    if (single) return 1u << ((sides[0] >> 1) | (sides[1] & 2u) | ((sides[2] & 2u) << 1));
    const TriangleBoxTest sat(in_.triangles[id]);
    uint32_t mask = 0, candidates = 0;
    for (int c = 0; c < 8; ++c) {
      double lo[3], hi[3];
      bool candidate = true;
      for (int k = 0; k < 3; ++k) {
        const bool upper = (c >> k) & 1;
        candidate = candidate && (sides[k] & (upper ? 2u : 1u));
        lo[k] = double(upper ? mid[k] : cell.lo[k]) - margin_;
        hi[k] = double(upper ? cell.hi[k] : mid[k]) + margin_;
      }
      if (!candidate) continue;
      candidates |= 1u << c;
      if (sat.Overlaps(lo, hi)) mask |= 1u << c;
    }
    // The widened children cover the widened cell, so only rounding at a
    // touching contact could leave none; never lose a triangle to that.
    return mask != 0 ? mask : candidates;
  }

  const StructureInput& in_;
  const int max_prims_;
  const int depth_limit_;
  const double margin_;
  std::vector<Node>& nodes_;
  std::vector<uint32_t>& refs_;
  std::vector<uint32_t> work_;  // reference lists of the cells on the current path and their children
  std::vector<uint8_t> masks_;  // per reference of the cell being split
  uint32_t max_depth_ = 0;
  uint64_t leaves_ = 0;
  uint32_t max_leaf_prims_ = 0;
  uint64_t oversized_ = 0;
};

// A ray's interval in a cell, [t0, t1], widened.
template <class A>
struct Span {
  typename A::T t0, t1;
  uint32_t node;
  Cell cell;
};

// One mid plane as StepInnerNode sees it, computed once per node.
template <class A>
struct PlaneCut {
  typename A::T t_split, t_lo, t_hi;
  uint32_t first_bit;  // the child bit of the side the ray starts on
  bool behind;         // at or behind the origin: the ray stays on its first side
};

// Forced inline (as CrossedChildren): GCC keeps it out of line otherwise,
// which costs about 6 % of the trace time (balls, 100k triangles).
template <class A>
inline __attribute__((always_inline)) PlaneCut<A> CutPlane(const A& a, const RaySetup<A>& r, float mid, int axis) {
  using T = typename A::T;
  PlaneCut<A> c;
  const T split = a.Load(mid);
  c.t_split = a.Mul(a.Sub(split, r.o[axis]), r.inv_d[axis]);
  c.t_lo = a.NudgeDown(c.t_split, kTraversalSlackUlps);
  c.t_hi = a.NudgeUp(c.t_split, kTraversalSlackUlps);
  const bool below_first = a.Lt(r.o[axis], split) || (a.Eq(r.o[axis], split) && a.Le(r.d[axis], a.Zero()));
  c.first_bit = below_first ? 0u : 1u << axis;
  c.behind = a.Le(c.t_split, a.Zero());
  return c;
}

template <class A>
struct ChildSpan {
  typename A::T t0, t1;
  uint32_t child;  // 0..7
  bool valid;
};

// One kd step (StepInnerNode's three cases) on a span, written without
// branches: out[0] is the span's part on the plane's first side, out[1] on
// its second side, each valid when that case visits it.
template <class A>
inline void SplitSpan(const A& a, const PlaneCut<A>& cut, uint32_t axis_bit, const ChildSpan<A>& in,
                      ChildSpan<A> out[2]) {
  const bool first_only = cut.behind || a.Lt(in.t1, cut.t_lo);
  const bool second_only = !first_only && a.Lt(cut.t_hi, in.t0);
  const bool both = !first_only && !second_only;
  out[0].t0 = in.t0;
  out[0].t1 = both ? cut.t_hi : in.t1;
  out[0].child = in.child | cut.first_bit;
  out[0].valid = in.valid && !second_only;
  out[1].t0 = both ? cut.t_lo : in.t0;
  out[1].t1 = in.t1;
  out[1].child = in.child | (cut.first_bit ^ axis_bit);
  out[1].valid = in.valid && !first_only;
}

// The children of a cell the ray's span crosses, as the three kd levels
// over its mid planes (x, then y, then z) would visit them: out[0..7] front
// to back, the valid ones in the returned mask (bit i: out[i]). The fixed
// binary expansion keeps the data-dependent branches out.
template <class A>
inline __attribute__((always_inline)) uint32_t CrossedChildren(const A& a, const RaySetup<A>& r, const float mid[3],
                                                               const Span<A>& span, ChildSpan<A> out[8]) {
  ChildSpan<A> l0{span.t0, span.t1, 0, true};
  ChildSpan<A> l1[2], l2[4];
  SplitSpan(a, CutPlane(a, r, mid[0], 0), 1u, l0, l1);
  const PlaneCut<A> cut_y = CutPlane(a, r, mid[1], 1);
  for (int i = 0; i < 2; ++i) SplitSpan(a, cut_y, 2u, l1[i], l2 + 2 * i);
  const PlaneCut<A> cut_z = CutPlane(a, r, mid[2], 2);
  for (int i = 0; i < 4; ++i) SplitSpan(a, cut_z, 4u, l2[i], out + 2 * i);
  uint32_t valid = 0;
  for (int i = 0; i < 8; ++i) valid |= static_cast<uint32_t>(out[i].valid) << i;
  return valid;
}

// Where the ray leaves the cell (not widened), for the stop rule: its
// nearest far plane, as ClipToBox computes it (a NaN distance, the ray lying
// in that face, does not narrow). Taken from the box rather than from the
// span, whose end may be NaN or infinite for a ray lying in a mid plane of
// an ancestor.
template <class A>
typename A::T CellExit(const A& a, const RaySetup<A>& r, const Cell& cell) {
  using T = typename A::T;
  T exit = r.tmax;
  for (int k = 0; k < 3; ++k) {
    const T far_plane = a.Load(a.IsNeg(r.inv_d[k]) ? cell.lo[k] : cell.hi[k]);
    const T t = a.Mul(a.Sub(far_plane, r.o[k]), r.inv_d[k]);
    if (a.Lt(t, exit)) exit = t;
  }
  return exit;
}

}  // namespace

bool TriangleOverlapsBox(const img::TriangleRecord& tri, const double lo[3], const double hi[3]) {
  return TriangleBoxTest(tri).Overlaps(lo, hi);
}

double BinningMargin(const accel::Box& bounds) {
  double reach = 0;
  for (int k = 0; k < 3; ++k) {
    reach = std::max({reach, std::fabs(double(bounds.lo[k])), std::fabs(double(bounds.hi[k]))});
  }
  return std::ldexp(reach, -20);
}

// The kd-tree's rule (8 + 1.3 log2 N kd levels) at three kd levels per
// octree level, plus one. Measured on balls and tree at 100k and 1M (with the
// duplication budget): deeper limits change neither the tests nor the nodes
// per ray, only the build time and the chains of cells at shared vertices.
int DefaultMaxDepth(size_t triangles) {
  if (triangles == 0) return 0;
  const double d = std::round((8.0 + 1.3 * std::log2(static_cast<double>(triangles))) / 3.0) + 1.0;
  return static_cast<int>(std::min<double>(d, kMaxDepth));
}

// A random line meeting a box meets each of its octants with probability
// 1/4 (Cauchy: a convex body's share of the random lines meeting a larger
// one is the ratio of their surface areas), so a ray crossing the cell
// would test child_sum / 4 triangles instead of n. Break-even rather than a
// required gain: early termination makes a split worth more than that.
bool SplitPays(size_t n, size_t child_sum) { return child_sum < 4 * n; }

}  // namespace octree

using octree::Node;

Octree::Octree(const StructureInput& input, const StructureOptions& options)
    : StructureBase(input), max_prims_(options.octree_max_prims) {
  depth_limit_ = options.octree_max_depth >= 0 ? options.octree_max_depth : octree::DefaultMaxDepth(input.ids.size());
  margin_ = octree::BinningMargin(input.bounds);
  for (int k = 0; k < 3; ++k) {
    root_.lo[k] = fp::NativeF32Arith::Load(input.bounds.lo[k]);
    root_.hi[k] = fp::NativeF32Arith::Load(input.bounds.hi[k]);
  }
  octree::Builder builder(input, max_prims_, depth_limit_, margin_, &nodes_, &refs_);
  builder.Run(root_);
  nodes_.shrink_to_fit();
  refs_.shrink_to_fit();

  stats_.nodes = nodes_.size();
  stats_.leaves = builder.leaves();
  stats_.references = refs_.size();
  stats_.memory_bytes = nodes_.size() * sizeof(Node) + refs_.size() * sizeof(uint32_t);
  stats_.max_depth = builder.max_depth();
  stats_.max_leaf_prims = builder.max_leaf_prims();
  stats_.extra = {{"max_prims", max_prims_},
                  {"depth_limit", depth_limit_},
                  {"duplication_budget", octree::kDuplicationBudget},
                  {"oversized_leaves", builder.oversized_leaves()}};
}

AccelKind Octree::kind() const { return AccelKind::kOctree; }

template <class A>
void Octree::TraceT(const A& a, const RaySetup<A>& r, Query query, TraceResult<A>& best,
                    TraceScratch& scratch) const {
  using Span = octree::Span<A>;
  using ChildSpan = octree::ChildSpan<A>;
  const BoxClip<A> clip = ClipToBox(a, r, input_->bounds.lo, input_->bounds.hi);  // as the kd-tree clips
  if (clip.miss) return;
  // A node pushes at most eight children and pops one of them at once; only
  // its own children lie above its entry on the stack.
  constexpr int kStack = 7 * (octree::kMaxDepth + 1) + 1;
  Span stack[kStack];
  int sp = 0;
  Span cur{clip.t0, clip.t1, 0, root_};
  AccelCounters& counters = scratch.counters;
  const Node* nodes = nodes_.data();
  const auto beyond_best = [&](typename A::T t0) { return best.prim != kNoPrim && a.Lt(best.t, t0); };
  for (;;) {
    const Node n = nodes[cur.node];
    ++counters.nodes;
    if (!n.IsLeaf()) {
      float mid[3];
      octree::CellCentre(cur.cell, mid);
      ChildSpan kids[8];
      uint32_t valid = octree::CrossedChildren(a, r, mid, cur, kids);
      // Pushed last to first so they pop front to back; empty children and
      // those starting beyond the best hit are never entered.
      while (valid != 0) {
        const int i = 31 - __builtin_clz(valid);
        valid &= ~(1u << i);
        const ChildSpan& c = kids[i];
        if (!n.HasChild(c.child) || beyond_best(c.t0)) continue;
        stack[sp++] = Span{c.t0, c.t1, n.Child(c.child), octree::ChildCell(cur.cell, mid, c.child)};
      }
    } else if (n.Count() > 0) {
      ++counters.leaves;
      const uint32_t* ids = refs_.data() + n.FirstRef();
      for (uint32_t i = 0; i < n.Count(); ++i) {
        TestMailboxed(a, r, input_->triangles[ids[i]], ids[i], best, scratch);
      }
      if (DoneAfterCell(a, best, query, octree::CellExit(a, r, cur.cell))) return;
    }
    do {
      if (sp == 0) return;
      cur = stack[--sp];
    } while (beyond_best(cur.t0));
  }
}

template void Octree::TraceT(const fp::NativeF32Arith&, const RaySetup<fp::NativeF32Arith>&, Query,
                             TraceResult<fp::NativeF32Arith>&, TraceScratch&) const;
template void Octree::TraceT(const fp::NativeF64Arith&, const RaySetup<fp::NativeF64Arith>&, Query,
                             TraceResult<fp::NativeF64Arith>&, TraceScratch&) const;

std::unique_ptr<Structure> BuildOctree(const StructureInput& input, const StructureOptions& options) {
  CheckStructureOptions(options);
  return Structure::Timed([&] { return std::make_unique<Octree>(input, options); });
}

}  // namespace kdrt
