// SAH kd-tree construction in O(N log N) after Wald & Havran 2006: every
// triangle contributes start/end (or one planar) events per axis, sorted once
// at the root; a node finds its best plane by sweeping its three sorted event
// lists, and the children's lists come from a linear split of the parent's
// plus a small sorted list for the triangles that straddle the plane, merged
// in linear time.
//
// Classification is the paper's (and pbrt's): a triangle is in the below
// child iff its box in the node extends strictly below the plane (lo < s),
// in the above child iff it extends strictly above (hi > s); one lying in
// the plane (lo == hi == s) goes to the side the planar rule picks. A
// triangle touching the plane from one side is therefore only on that side;
// the traversal's slack (trace/traversal.h) makes a ray crossing the plane
// near such a point visit both children. The sweep counts the same way:
//   N_below(s) = #{lo < s} (+ planar at s if they go below)
//   N_above(s) = #{hi > s} (+ planar at s if they go above)
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <thread>
#include <utility>
#include <vector>

#include "accel/build_util.h"

namespace kdrt::accel {
namespace {

// An event is one uint64: order-preserving position bits in the high half,
// then triangle id and type, so sorting the integers sorts by position.
enum EventType : uint32_t { kEnd = 0, kPlanar = 1, kStart = 2 };

inline uint32_t OrderedBits(float f) {
  if (f == 0.0f) f = 0.0f;  // -0 and +0 are one plane
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

inline float FromOrderedBits(uint32_t o) {
  const uint32_t u = (o & 0x80000000u) ? (o & 0x7fffffffu) : ~o;
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

inline uint64_t MakeEvent(float pos, uint32_t tri, EventType type) {
  return (static_cast<uint64_t>(OrderedBits(pos)) << 32) | (tri << 2) | type;
}
inline uint32_t EventPos(uint64_t e) { return static_cast<uint32_t>(e >> 32); }
inline uint32_t EventTri(uint64_t e) { return static_cast<uint32_t>(e) >> 2; }
// OrderedBits never yields this (-0 is mapped to +0).
constexpr uint32_t kNegativeZeroBits = 0x7fffffffu;

inline EventType EventKind(uint64_t e) { return static_cast<EventType>(e & 3u); }
// Per EventType: an end counts in the low half, a start in the high half.
constexpr uint64_t kEndStartCount[4] = {1, 0, uint64_t{1} << 32, 0};
static_assert(kEnd == 0 && kPlanar == 1 && kStart == 2, "kEndStartCount is indexed by EventType");

// std::allocator that leaves a resize's new elements uninitialised: the
// event lists are resized before they are written, and zeroing them first
// cost a pass over the memory.
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  using std::allocator<T>::allocator;
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
using EventList = std::vector<uint64_t, DefaultInitAllocator<uint64_t>>;

// LSD radix sort of the root event lists, 16 bits per pass (a few times
// faster than std::sort on millions of keys); `tmp` is scratch.
void RadixSort(EventList* keys, EventList* tmp) {
  constexpr int kBits = 16;
  constexpr size_t kBuckets = size_t{1} << kBits;
  EventList& a = *keys;
  EventList& b = *tmp;
  b.resize(a.size());
  std::vector<size_t> count(kBuckets);
  for (int shift = 0; shift < 64; shift += kBits) {
    std::fill(count.begin(), count.end(), 0);
    for (uint64_t k : a) ++count[(k >> shift) & (kBuckets - 1)];
    if (count[(a.empty() ? 0 : (a[0] >> shift)) & (kBuckets - 1)] == a.size()) continue;
    size_t sum = 0;
    for (size_t& c : count) {
      const size_t here = c;
      c = sum;
      sum += here;
    }
    for (uint64_t k : a) b[count[(k >> shift) & (kBuckets - 1)]++] = k;
    a.swap(b);
  }
  b.clear();
}

constexpr int kMaxBadRefines = 3;  // pbrt-v3's limit

// A subtree the automatic clipping starts may hold this many references per
// triangle of its root at most (docs/kdtree.md, "Clipping where the boxes
// fail"): without a budget the fanned slivers of gen:gears, clipped, refine
// to the depth limit with 270 references per triangle at 200k; at 2 the
// clipped trees of gen:hoops test 1.4x as many triangles per ray as at 4, at
// 8 gears' references grow 1.4x for 0.7x the tests.
constexpr double kClipBudget = 4.0;

enum Side : uint8_t { kBoth = 0, kBelowOnly = 1, kAboveOnly = 2 };

// A node's triangles: per axis, a range of the axis' event arena.
struct NodeEvents {
  size_t begin[3];
  size_t end[3];
  uint32_t count;  // triangles
  Box cell;
  // Its events come from the triangles clipped to its cell, and its
  // children's will (perfect splits in this subtree).
  bool clipped = false;
  // References its subtree may hold (automatic clipping; infinite elsewhere).
  double budget = std::numeric_limits<double>::infinity();
};

struct Split {
  int axis = -1;
  uint32_t pos_bits = 0;
  bool planar_below = true;
  double cost = 0;
  uint32_t n_below = 0;  // as counted by the sweep (exact before clipping)
  uint32_t n_above = 0;
};

// A subtree left for a worker by the parallel build: its three sorted
// event lists (copied out of the arena), its cell and where the recursion
// stood.
struct DeferredSubtree {
  EventList events[3];
  uint32_t count = 0;
  Box cell{};
  int depth = 0;
  int bad_refines = 0;
  bool clipped = false;
  double budget = 0;
  uint32_t top_index = 0;  // its placeholder among the top nodes
  std::vector<img::Node> nodes;  // built by the worker, indices relative
  std::vector<uint32_t> lists;
  LeafCauses causes;             // of its leaves
};

class SahBuilder {
 public:
  SahBuilder(const BuildInput& input, const BuildOptions& options, TreeWriter* writer)
      : in_(input),
        tris_(*input.triangles),
        traversal_cost_(options.traversal_cost),
        isect_cost_(options.isect_cost),
        empty_bonus_(options.empty_bonus),
        max_leaf_prims_(options.max_leaf_prims),
        perfect_(options.perfect_splits),
        auto_clip_(options.auto_clip),
        good_split_below_(1.0 - static_cast<double>(options.min_split_gain)),
        writer_(writer),
        side_(tris_.size(), kBoth) {}

  void Run() {
    NodeEvents root;
    root.cell = in_.bounds;
    root.count = static_cast<uint32_t>(in_.ids.size());
    root.clipped = perfect_;
    for (int a = 0; a < 3; ++a) {
      arena_[a].reserve(in_.ids.size() * 4 + 16);
      for (uint32_t id : in_.ids) AppendEvents(id, in_.boxes[id], a, &arena_[a]);
      RadixSort(&arena_[a], &new_below_[0]);
      root.begin[a] = 0;
      root.end[a] = arena_[a].size();
    }
    Build(root, 0, 0);
  }

  // The parallel build's top: nodes at `depth` with at least `min_count`
  // triangles are not built but copied into `out`, a placeholder node
  // standing in the tree for each.
  void DeferAt(int depth, uint32_t min_count, std::vector<DeferredSubtree>* out) {
    defer_depth_ = depth;
    defer_min_count_ = min_count;
    deferred_ = out;
  }

  // Builds a deferred subtree, its events moved into this builder's arena.
  void RunSubtree(DeferredSubtree& d) {
    NodeEvents node;
    node.cell = d.cell;
    node.count = d.count;
    node.clipped = d.clipped;
    node.budget = d.budget;
    for (int a = 0; a < 3; ++a) {
      arena_[a] = std::move(d.events[a]);
      node.begin[a] = 0;
      node.end[a] = arena_[a].size();
    }
    Build(node, d.depth, d.bad_refines);
  }

 private:
  bool IsFlat(uint32_t tri, int axis) const { return (in_.flat[tri] >> axis) & 1u; }

  // A triangle lying in a plane x_axis = c gets one planar event at c (its
  // exact vertex coordinate, which a clipped box would have widened);
  // otherwise start and end at its box bounds. A clipped box that is flat
  // (the triangle only touches a face of the cell) is planar too, so that
  // start == end can never be classified as both below-only and above-only.
  void AppendEvents(uint32_t tri, const Box& box, int axis, EventList* out) const {
    if (IsFlat(tri, axis)) {
      const glm::vec3& v = tris_[tri].v0;
      out->push_back(MakeEvent(v[axis], tri, kPlanar));
    } else if (box.lo[axis] == box.hi[axis]) {
      out->push_back(MakeEvent(box.lo[axis], tri, kPlanar));
    } else {
      out->push_back(MakeEvent(box.lo[axis], tri, kStart));
      out->push_back(MakeEvent(box.hi[axis], tri, kEnd));
    }
  }

  // Termination as in pbrt-v3: a split that does not beat the leaf cost
  // is still taken up to kMaxBadRefines times on a path (the greedy cost
  // cannot see that splitting further often pays off), unless it is hopeless
  // (more than 4x the leaf cost in a node of fewer than 16 triangles).
  // With a minimum gain G, a split must cost less than (1 - G) x the leaf
  // not to count as bad: where every split leaves most triangles on both
  // sides (long overlapping slivers), the greedy cost accepts gains of a
  // fraction of a test, level after level, and duplicates every sliver.
  void Build(const NodeEvents& node, int depth, int bad_refines) {
    if (deferred_ && depth == defer_depth_ && node.count >= defer_min_count_) {
      Defer(node, depth, bad_refines);
      return;
    }
    const double leaf_cost = static_cast<double>(isect_cost_) * node.count;
    if (node.count <= static_cast<uint32_t>(max_leaf_prims_)) {
      MakeLeaf(node, LeafCause::kFew);
      return;
    }
    if (depth >= in_.max_depth) {
      MakeLeaf(node, LeafCause::kDepth);
      return;
    }
    const Split split = FindSplit(node);
    const bool good = split.axis >= 0 && split.cost < leaf_cost * good_split_below_;
    if (!good && auto_clip_ && !node.clipped && node.count > kLargeLeafPrims) {
      // The triangles' boxes (clamped to the cell) give no good plane: long
      // slivers crossing the cell diagonally fill it on every axis. Their
      // parts inside the cell may (docs/kdtree.md, "Clipping where the
      // boxes fail"): the node is decided again on the clipped boxes, and
      // its subtree is built with perfect splits, within a budget of
      // references (kClipBudget).
      const size_t start[3] = {arena_[0].size(), arena_[1].size(), arena_[2].size()};
      Build(ClipToCell(node), depth, bad_refines);
      for (int a = 0; a < 3; ++a) arena_[a].resize(start[a]);
      return;
    }
    if (split.axis < 0) {
      MakeLeaf(node, LeafCause::kNoPlane);
      return;
    }
    if (!good) ++bad_refines;
    if (bad_refines >= kMaxBadRefines) {
      MakeLeaf(node, LeafCause::kNoGain);
      return;
    }
    if (split.cost > 4.0 * leaf_cost && node.count < 16) {
      MakeLeaf(node, LeafCause::kHopeless);
      return;
    }
    if (static_cast<double>(split.n_below) + split.n_above > node.budget) {
      MakeLeaf(node, LeafCause::kBudget);
      return;
    }
    const size_t child_start[3] = {arena_[0].size(), arena_[1].size(), arena_[2].size()};
    NodeEvents below, above;
    if (split.n_below == 0 || split.n_above == 0) {
      // Cutting off empty space: every triangle lies on the full side (at
      // most touching the plane), its box there is its box in the node, so
      // the full child keeps the node's event lists as they are.
      EmptySplit(node, split, &below, &above);
    } else {
      SplitEvents(node, split, &below, &above);
    }
    const uint32_t index = writer_->BeginInner();
    Build(below, depth + 1, bad_refines);
    writer_->FinishInner(index, split.axis, FromOrderedBits(split.pos_bits));
    Build(above, depth + 1, bad_refines);
    for (int a = 0; a < 3; ++a) arena_[a].resize(child_start[a]);
  }

  void Defer(const NodeEvents& node, int depth, int bad_refines) {
    DeferredSubtree d;
    for (int a = 0; a < 3; ++a) {
      d.events[a].assign(arena_[a].begin() + node.begin[a], arena_[a].begin() + node.end[a]);
    }
    d.count = node.count;
    d.cell = node.cell;
    d.depth = depth;
    d.bad_refines = bad_refines;
    d.clipped = node.clipped;
    d.budget = node.budget;
    d.top_index = writer_->node_count();
    writer_->AppendNode(img::Node{0, 0});  // the placeholder
    deferred_->push_back(std::move(d));
  }

  // The node's triangles clipped to its cell: new event lists for all
  // three axes at the ends of the arenas (a triangle whose clip is empty
  // is left out).
  NodeEvents ClipToCell(const NodeEvents& node) {
    clip_ids_.clear();
    const uint64_t* ev = arena_[0].data();
    for (size_t i = node.begin[0]; i < node.end[0]; ++i) {
      if (EventKind(ev[i]) != kEnd) clip_ids_.push_back(EventTri(ev[i]));
    }
    for (int a = 0; a < 3; ++a) new_below_[a].clear();
    NodeEvents out;
    out.cell = node.cell;
    out.clipped = true;
    out.count = 0;
    for (uint32_t tri : clip_ids_) {
      Box box;
      if (!ClippedTriangleBox(tris_[tri], node.cell, &box)) continue;
      ++out.count;
      for (int a = 0; a < 3; ++a) AppendEvents(tri, box, a, &new_below_[a]);
    }
    for (int a = 0; a < 3; ++a) {
      std::sort(new_below_[a].begin(), new_below_[a].end());
      out.begin[a] = arena_[a].size();
      arena_[a].insert(arena_[a].end(), new_below_[a].begin(), new_below_[a].end());
      out.end[a] = arena_[a].size();
    }
    out.budget = kClipBudget * out.count;
    return out;
  }

  void MakeLeaf(const NodeEvents& node, LeafCause cause) {
    leaf_ids_.clear();
    const uint64_t* ev = arena_[0].data();
    for (size_t i = node.begin[0]; i < node.end[0]; ++i) {
      if (EventKind(ev[i]) != kEnd) leaf_ids_.push_back(EventTri(ev[i]));
    }
    writer_->AddLeaf(leaf_ids_, cause);
  }

  // Candidate planes per axis: the event positions strictly inside the cell,
  // with the triangles lying in the plane (if any) once below and once above.
  // Between two event positions the counts are constant and the cost is
  // linear, so its minimum over the gap is at one of its ends; the event
  // position at that end has the same count on one side and no more on the
  // other (triangles ending or starting there drop out), and differs only by
  // the one float of area, so inner gaps need no candidates of their own.
  // The exception is flat geometry lying on a face of the cell (a floor):
  // the plane that separates it from the empty space beside it can only be
  // the float next to the face, so the first and the last gap are evaluated
  // when planar triangles lie on the face.
  Split FindSplit(const NodeEvents& node) const {
    Split best;
    const Box& cell = node.cell;
    const double sa = SurfaceArea(cell);
    if (!(sa > 0)) return best;
    const double inv_sa = 1.0 / sa;
    const uint32_t n = node.count;
    const double isect = isect_cost_;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(cell.lo[axis] < cell.hi[axis])) continue;
      const int a1 = (axis + 1) % 3;
      const int a2 = (axis + 2) % 3;
      const double d1 = static_cast<double>(cell.hi[a1]) - cell.lo[a1];
      const double d2 = static_cast<double>(cell.hi[a2]) - cell.lo[a2];
      const double lo = cell.lo[axis];
      const double hi = cell.hi[axis];
      const double face = 2.0 * d1 * d2 * inv_sa;     // area ratio of a zero-width child
      const double per_unit = 2.0 * (d1 + d2) * inv_sa;  // its growth per unit width
      auto consider = [&](uint32_t s_bits, uint32_t n_below, uint32_t n_above,
                          bool planar_below) {
        const double s = FromOrderedBits(s_bits);
        const double p_below = face + (s - lo) * per_unit;
        const double p_above = face + (hi - s) * per_unit;
        const double bonus = (n_below == 0 || n_above == 0) ? empty_bonus_ : 0.0;
        const double cost =
            traversal_cost_ + isect * (1.0 - bonus) * (p_below * n_below + p_above * n_above);
        if (best.axis < 0 || cost < best.cost) {
          best.axis = axis;
          best.pos_bits = s_bits;
          best.planar_below = planar_below;
          best.cost = cost;
          best.n_below = n_below;
          best.n_above = n_above;
        }
      };
      const uint64_t* ev = arena_[axis].data();
      uint32_t starts_before = 0;  // starts and planars strictly below the plane
      uint32_t ends_before = 0;    // ends and planars strictly below the plane
      const uint32_t lo_bits = OrderedBits(cell.lo[axis]);
      const uint32_t hi_bits = OrderedBits(cell.hi[axis]);
      // Both ends of the gap between positions a and b (ordered bits), with
      // the gap's counts.
      auto consider_gap = [&](uint32_t a, uint32_t b, uint32_t n_below, uint32_t n_above) {
        uint32_t s1 = a + 1, s2 = b - 1;
        if (s1 == kNegativeZeroBits) ++s1;  // -0 is not a separate plane
        if (s2 == kNegativeZeroBits) --s2;
        if (!(a < s1 && s1 <= s2 && s2 < b)) return;
        consider(s1, n_below, n_above, true);
        if (s2 != s1) consider(s2, n_below, n_above, true);
      };
      uint32_t prev = lo_bits;
      size_t i = node.begin[axis];
      const size_t end = node.end[axis];
      while (i < end) {
        const uint32_t pos = EventPos(ev[i]);
        // Ends and starts counted in the two halves of one register (a count
        // array on the stack put a store and a reload on every event); the
        // planars are the rest of the position's events.
        const size_t first = i;
        uint64_t ends_starts = 0;
        for (; i < end && EventPos(ev[i]) == pos; ++i) ends_starts += kEndStartCount[EventKind(ev[i])];
        const uint32_t n_end = static_cast<uint32_t>(ends_starts);
        const uint32_t n_start = static_cast<uint32_t>(ends_starts >> 32);
        const uint32_t n_planar = static_cast<uint32_t>(i - first) - n_end - n_start;
        if (pos > lo_bits && pos < hi_bits) {
          const uint32_t below = starts_before;
          const uint32_t above = n - ends_before - n_end - n_planar;
          consider(pos, below + n_planar, above, true);
          if (n_planar > 0) consider(pos, below, above + n_planar, false);
        } else if (pos == hi_bits && n_planar > 0) {
          consider_gap(prev, pos, starts_before, n - ends_before);
        }
        starts_before += n_start + n_planar;
        ends_before += n_end + n_planar;
        if (pos == lo_bits && n_planar > 0) {
          consider_gap(pos, i < end ? EventPos(ev[i]) : hi_bits, starts_before, n - ends_before);
        }
        prev = pos;
      }
    }
    return best;
  }

  void EmptySplit(const NodeEvents& node, const Split& split, NodeEvents* below,
                  NodeEvents* above) const {
    const int k = split.axis;
    const float s = FromOrderedBits(split.pos_bits);
    *below = node;
    *above = node;
    below->cell.hi[k] = s;
    above->cell.lo[k] = s;
    NodeEvents* empty = split.n_below == 0 ? below : above;
    empty->count = 0;
    for (int a = 0; a < 3; ++a) empty->end[a] = empty->begin[a];
  }

  void SplitEvents(const NodeEvents& node, const Split& split, NodeEvents* below,
                   NodeEvents* above) {
    const int k = split.axis;
    const uint32_t s = split.pos_bits;
    const float s_float = FromOrderedBits(s);

    // Classify from the split axis' events, in one pass: a triangle has a
    // planar event there, or a start and then (at a larger position) an end.
    // Its start says whether it lies above the plane, its end whether below;
    // at its planar or end event its side is known. (The straddlers come out
    // in the order of their ends; they are sorted or their events are,
    // below.)
    const uint64_t* ev = arena_[k].data();
    uint32_t n_below = 0, n_above = 0;
    straddlers_.clear();
    for (size_t i = node.begin[k]; i < node.end[k]; ++i) {
      const uint64_t e = ev[i];
      const uint32_t pos = EventPos(e);
      const uint32_t tri = EventTri(e);
      switch (EventKind(e)) {
        case kStart:
          side_[tri] = pos >= s ? kAboveOnly : kBoth;
          break;
        case kEnd:
          if (pos <= s) {
            side_[tri] = kBelowOnly;
            ++n_below;
          } else if (side_[tri] == kAboveOnly) {
            ++n_above;
          } else {
            straddlers_.push_back(tri);
          }
          break;
        case kPlanar:
          if (pos < s || (pos == s && split.planar_below)) {
            side_[tri] = kBelowOnly;
            ++n_below;
          } else {
            side_[tri] = kAboveOnly;
            ++n_above;
          }
          break;
      }
    }

    below->cell = node.cell;
    below->cell.hi[k] = s_float;
    above->cell = node.cell;
    above->cell.lo[k] = s_float;

    // Events of the straddling triangles, recomputed for each child cell:
    // their boxes re-clipped with perfect splits. Without clipping a child's
    // box of a triangle is its box clamped to the child's cell, which differs
    // from the node's on the split axis alone, at the plane (SplitAxisEvents,
    // FilterEvents).
    for (int a = 0; a < 3; ++a) {
      new_below_[a].clear();
      new_above_[a].clear();
    }
    const bool clip = node.clipped;
    below->clipped = clip;
    above->clipped = clip;
    for (uint32_t tri : straddlers_) {
      if (!clip) {
        ++n_below;
        ++n_above;
        continue;
      }
      Box box;
      if (ClippedTriangleBox(tris_[tri], below->cell, &box)) {
        ++n_below;
        for (int a = 0; a < 3; ++a) AppendEvents(tri, box, a, &new_below_[a]);
      }
      if (ClippedTriangleBox(tris_[tri], above->cell, &box)) {
        ++n_above;
        for (int a = 0; a < 3; ++a) AppendEvents(tri, box, a, &new_above_[a]);
      }
    }
    below->count = n_below;
    above->count = n_above;
    // A clipped subtree's budget is shared in proportion to the children's
    // references, so along any path the duplication it allows multiplies
    // to at most the budget's factor.
    below->budget = above->budget = node.budget;
    if (std::isfinite(node.budget)) {
      const double per_ref = node.budget / (static_cast<double>(n_below) + n_above);
      below->budget = per_ref * n_below;
      above->budget = per_ref * n_above;
    }

    for (int a = 0; a < 3; ++a) {
      if (!clip) {
        if (a == k) {
          SplitAxisEvents(node, k, s, below, above);
        } else {
          FilterEvents(node, a, below, above);
        }
        continue;
      }
      std::sort(new_below_[a].begin(), new_below_[a].end());
      std::sort(new_above_[a].begin(), new_above_[a].end());
      // The one-sided triangles keep their events; a stable partition keeps
      // both halves sorted.
      kept_below_.clear();
      kept_above_.clear();
      const uint64_t* src = arena_[a].data();
      for (size_t i = node.begin[a]; i < node.end[a]; ++i) {
        const uint8_t side = side_[EventTri(src[i])];
        if (side == kBelowOnly) {
          kept_below_.push_back(src[i]);
        } else if (side == kAboveOnly) {
          kept_above_.push_back(src[i]);
        }
      }
      EventList& arena = arena_[a];
      const size_t start = arena.size();
      const size_t n_b = kept_below_.size() + new_below_[a].size();
      const size_t n_a = kept_above_.size() + new_above_[a].size();
      arena.resize(start + n_b + n_a);
      std::merge(kept_below_.begin(), kept_below_.end(), new_below_[a].begin(),
                 new_below_[a].end(), arena.begin() + start);
      std::merge(kept_above_.begin(), kept_above_.end(), new_above_[a].begin(),
                 new_above_[a].end(), arena.begin() + start + n_b);
      below->begin[a] = start;
      below->end[a] = start + n_b;
      above->begin[a] = start + n_b;
      above->end[a] = start + n_b + n_a;
    }
  }

  // Appends the children's lists on axis `a` to its arena: the node's
  // events, in their order, to the below list where bit 0 of where(e) is
  // set and to the above list where bit 1 is, with `room` free slots at the
  // end of the below list and at the front of the above list; sets the
  // children's ranges on `a` and returns where the two lists start.
  template <class Where>
  std::pair<uint64_t*, uint64_t*> PartitionEvents(const NodeEvents& node, int a, size_t room, Where where,
                                                  NodeEvents* below, NodeEvents* above) {
    // One pass over the node's events: the below list is written in place,
    // the above list past the most the below list can take, then moved down
    // next to it (a sequential copy costs less than a counting pass, whose
    // lookups of side_ are random). The sides come from one lookup as a
    // mask: no branch on them (they are random along the axis).
    EventList& arena = arena_[a];
    const size_t first = node.begin[a], stop = node.end[a];
    const size_t len = stop - first;
    const size_t start = arena.size();
    arena.resize(start + 2 * (len + room));
    uint64_t* const out_b = arena.data() + start;
    uint64_t* const scratch_a = out_b + len + 2 * room;
    uint64_t* wb = out_b;
    uint64_t* wa = scratch_a;
    const uint64_t* const src = arena.data();
    for (size_t i = first; i < stop; ++i) {
      const uint64_t e = src[i];
      const unsigned m = where(e);
      *wb = e;
      wb += m & 1u;
      *wa = e;
      wa += m >> 1;
    }
    const size_t n_b = static_cast<size_t>(wb - out_b) + room;
    const size_t n_a_events = static_cast<size_t>(wa - scratch_a);
    uint64_t* const out_a = out_b + n_b;
    std::memmove(out_a + room, scratch_a, n_a_events * sizeof(uint64_t));
    const size_t n_a = n_a_events + room;
    arena.resize(start + n_b + n_a);
    below->begin[a] = start;
    below->end[a] = start + n_b;
    above->begin[a] = start + n_b;
    above->end[a] = start + n_b + n_a;
    return {out_b, out_a};
  }

  // The children's lists on an axis where their events are the node's (no
  // clipping, not the split axis): the node's list filtered, the straddlers
  // in both, so both stay sorted with no sort or merge (the same lists the
  // sort and merge give: events are distinct keys). A third of building
  // strips and tree was sorting and merging these.
  void FilterEvents(const NodeEvents& node, int a, NodeEvents* below, NodeEvents* above) {
    // Per Side: both children, below only, above only.
    static constexpr uint8_t kMask[3] = {3, 1, 2};
    const uint8_t* side = side_.data();
    PartitionEvents(
        node, a, 0, [side](uint64_t e) { return unsigned{kMask[side[EventTri(e)]]}; }, below, above);
  }

  // The children's lists on the split axis without clipping. A straddling
  // triangle (start below the plane, end above it) keeps its start in the
  // below child and its end in the above child, and its box clamped to each
  // child ends (below) or starts (above) at the plane: those new events sit
  // at the plane, among the events there in triangle order. So the lists are
  // the node's filtered, with the new events merged in at the tail (below)
  // and the head (above), in place: only the straddlers' ids are sorted.
  void SplitAxisEvents(const NodeEvents& node, int k, uint32_t plane_bits, NodeEvents* below,
                       NodeEvents* above) {
    std::sort(straddlers_.begin(), straddlers_.end());  // no longer needed in their end order
    const size_t n_s = straddlers_.size();
    // Per Side and EventType: a one-sided triangle's events go to its side,
    // a straddler's start below and its end above (a straddler has no
    // planar event).
    static constexpr uint8_t kMask[3][4] = {{2, 0, 1, 0}, {1, 1, 1, 0}, {2, 2, 2, 0}};
    const uint8_t* side = side_.data();
    const auto [out_b, out_a] = PartitionEvents(
        node, k, n_s, [side](uint64_t e) { return unsigned{kMask[side[EventTri(e)]][EventKind(e)]}; }, below,
        above);
    const size_t n_b = below->end[k] - below->begin[k], n_a = above->end[k] - above->begin[k];
    const uint64_t plane = uint64_t{plane_bits} << 32;
    // Below: merged from the back; the write position never passes the read one.
    size_t r = n_b - n_s, w = n_b;
    for (size_t j = n_s; j > 0;) {
      const uint64_t e = plane | (uint64_t{straddlers_[j - 1]} << 2) | kEnd;
      if (r > 0 && out_b[r - 1] > e) {
        out_b[--w] = out_b[--r];
      } else {
        out_b[--w] = e;
        --j;
      }
    }
    // Above: merged from the front, likewise.
    r = n_s;
    w = 0;
    for (size_t j = 0; j < n_s;) {
      const uint64_t e = plane | (uint64_t{straddlers_[j]} << 2) | kStart;
      if (r < n_a && out_a[r] < e) {
        out_a[w++] = out_a[r++];
      } else {
        out_a[w++] = e;
        ++j;
      }
    }
  }

  const BuildInput& in_;
  const std::vector<Triangle>& tris_;
  const float traversal_cost_;
  const float isect_cost_;
  const float empty_bonus_;
  const int max_leaf_prims_;
  const bool perfect_;    // every node clipped, from the root
  const bool auto_clip_;  // nodes clipped where their boxes give no good split
  const double good_split_below_;  // x the leaf cost: a split not below it is a bad refinement
  TreeWriter* writer_;

  EventList arena_[3];         // stack of event lists, one per axis
  std::vector<uint8_t> side_;  // per triangle id, valid while splitting a node
  // Scratch reused by every node, so the hot loops do not allocate.
  std::vector<uint32_t> straddlers_;
  EventList new_below_[3], new_above_[3];
  EventList kept_below_, kept_above_;
  std::vector<uint32_t> leaf_ids_;
  std::vector<uint32_t> clip_ids_;

  int defer_depth_ = -1;
  uint32_t defer_min_count_ = 0;
  std::vector<DeferredSubtree>* deferred_ = nullptr;
};

// Below this many triangles a subtree is built where it stands: copying its
// events out costs about what building it does.
constexpr uint32_t kMinDeferredTriangles = 2048;

// Appends the top of the tree and its built subtrees to `writer` in the
// serial build's order (depth first, each subtree where its placeholder
// stands, leaf lists in leaf order), moving child and list indices.
void Assemble(const std::vector<img::Node>& top, const std::vector<uint32_t>& top_lists,
              const std::vector<DeferredSubtree>& subtrees, TreeWriter* writer) {
  // Where each top node lands: a placeholder takes its subtree's size.
  std::vector<uint64_t> final_index(top.size() + 1);
  std::vector<int> subtree_at(top.size(), -1);
  for (size_t k = 0; k < subtrees.size(); ++k) subtree_at[subtrees[k].top_index] = static_cast<int>(k);
  final_index[0] = writer->node_count();
  for (size_t i = 0; i < top.size(); ++i) {
    final_index[i + 1] = final_index[i] + (subtree_at[i] >= 0 ? subtrees[subtree_at[i]].nodes.size() : 1);
  }
  if (final_index[top.size()] > img::kMaxChildIndex + uint64_t{1}) {
    writer->Fail("kd-tree has more than 2^28 nodes, too many for the memory image");
  }
  for (size_t i = 0; i < top.size(); ++i) {
    if (subtree_at[i] >= 0) {
      const DeferredSubtree& d = subtrees[subtree_at[i]];
      const uint32_t node_base = static_cast<uint32_t>(final_index[i]);
      const uint32_t list_base = static_cast<uint32_t>(writer->list_count());
      for (const img::Node& n : d.nodes) {
        if (n.IsLeaf()) {
          writer->AppendNode(n.Count() == 0 ? n : img::Node{n.word0 + list_base, n.word1});
        } else {
          writer->AppendNode(img::Node{n.word0, ((n.AboveChild() + node_base) << 2) | (n.word1 & 3u)});
        }
      }
      writer->AppendList(d.lists.data(), d.lists.size());
      continue;
    }
    const img::Node& n = top[i];
    if (n.IsLeaf()) {
      const uint32_t list_base = static_cast<uint32_t>(writer->list_count());
      if (n.Count() > 0) writer->AppendList(top_lists.data() + n.FirstEntry(), n.Count());
      writer->AppendNode(n.Count() == 0 ? n : img::Node{list_base, n.word1});
    } else {
      const uint32_t above = static_cast<uint32_t>(final_index[n.AboveChild()]);
      writer->AppendNode(img::Node{n.word0, (above << 2) | (n.word1 & 3u)});
    }
  }
}

}  // namespace

void BuildSahTree(const BuildInput& input, const BuildOptions& options, TreeWriter* writer) {
  int threads = options.threads;
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (threads == 1 || input.ids.size() < 2 * kMinDeferredTriangles) {
    SahBuilder(input, options, writer).Run();
    return;
  }
  // The top levels serially, down to a depth with about 4 subtrees per
  // thread; then the subtrees on the threads; then the pieces put together
  // in the serial order. Every node is decided exactly as the serial build
  // decides it (the same events, depth and bad-refine count), so the tree
  // is the same.
  int depth = 0;
  while ((1 << depth) < 4 * threads && depth < 16) ++depth;
  std::vector<img::Node> top;
  std::vector<uint32_t> top_lists;
  std::vector<DeferredSubtree> subtrees;
  {
    TreeWriter top_writer(&top, &top_lists, writer->source());
    SahBuilder builder(input, options, &top_writer);
    builder.DeferAt(depth, kMinDeferredTriangles, &subtrees);
    builder.Run();
    writer->MergeCauses(top_writer.causes());
  }
  // Largest first, so the threads finish together.
  std::vector<size_t> order(subtrees.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return subtrees[a].count > subtrees[b].count; });
  std::atomic<size_t> next{0};
  std::vector<std::exception_ptr> errors(subtrees.size());
  auto worker = [&]() {
    for (size_t k; (k = next.fetch_add(1)) < order.size();) {
      DeferredSubtree& d = subtrees[order[k]];
      try {
        TreeWriter sub_writer(&d.nodes, &d.lists, writer->source());
        SahBuilder(input, options, &sub_writer).RunSubtree(d);
        d.causes = sub_writer.causes();
      } catch (...) {
        errors[order[k]] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);  // the first subtree's in tree order, as the serial build would
  }
  for (const DeferredSubtree& d : subtrees) writer->MergeCauses(d.causes);
  Assemble(top, top_lists, subtrees, writer);
}

}  // namespace kdrt::accel
