// Front-to-back stack traversal of the memory image's kd-tree (the recursive
// in-order rule of Kaplan/Arvo/Jansen, made iterative as in pbrt), templated
// on the arithmetic policy. Its operation order is the traversal unit's; see
// docs/dataflow.md.
//
// Closest hit is defined so that it does not depend on the order in which a
// pipelined unit returns the tests of one leaf:
//  - every test in a leaf uses the same t_max: the best hit t when the leaf
//    was entered (the ray's tmax before any hit);
//  - the best hit is the candidate with the smallest t, and among equal t the
//    smallest triangle id;
//  - after a leaf, the ray stops if it has a hit with t <= the cell's exit t
//    (an any-hit query, Query::kAny: if it has a hit at all);
//    a popped cell whose entry t lies beyond the best hit also ends the ray;
//  - a ray lying in a split plane (a zero direction component, the origin
//    on the plane: the split distance is 0 x inf = NaN) visits both children,
//    and neither stop rule applies while the far child it pushed is still on
//    the stack (see InPlane below).
#pragma once

#include <cstdint>
#include <type_traits>
#include <vector>

#include "common/ray.h"
#include "fp/format.h"
#include "trace/frame.h"
#include "trace/intersect.h"
#include "trace/leaf_x4.h"
#include "trace/memory_image.h"

namespace kdrt {

// A validated image is less than kMaxImageDepth deep, and a push happens at
// most once per level, so this stack cannot overflow.
inline constexpr int kMaxTraversalStack = kMaxImageDepth;

template <class A>
struct TraceResult {
  typename A::T t, u, v;  // t along the framed ray
  uint32_t prim = kNoPrim;
  int32_t t_scale_log2 = 0;  // world t = t * 2^t_scale_log2 (trace/frame.h)
};

// Cell intervals are conservative: every distance the traversal compares is
// computed with rounding (a sub, a mul and the reciprocal: within 3 ulps of
// the exact distance along the loaded ray), so each interval end is moved
// outwards by kTraversalSlackUlps encodings (fp::NudgeUp/NudgeDown, an exact
// integer step). Without it a ray aimed at a vertex lying on a split plane
// or on the scene box can skip every cell holding the vertex's triangles in
// a narrow format (seen in bf16). The slack widens cells, never the hit test:
// hits are still accepted only within [tmin, tmax].
inline constexpr uint32_t kTraversalSlackUlps = 4;

// The ray's [tmin, tmax] clipped to the scene box (the clip unit,
// rtl/rt_clip_unit.sv), widened by the slack. A slab whose distances are NaN
// (ray parallel to and in the slab's plane) does not narrow the interval.
template <class A>
struct BoxClip {
  typename A::T t0, t1;
  bool miss;
};

// The hot per-node helpers are forced inline: with the mixed-format
// instantiations beside them, GCC's unit growth limit stopped inlining them
// into the fp32 loop (7 % of its speed).
#if defined(__GNUC__)
#define KDRT_HOT_INLINE inline __attribute__((always_inline))
#else
#define KDRT_HOT_INLINE inline
#endif

template <class A>
KDRT_HOT_INLINE BoxClip<A> ClipToBox(const A& a, const RaySetup<A>& r, const float bounds_min[3],
                                     const float bounds_max[3]) {
  using T = typename A::T;
  BoxClip<A> c{r.tmin, r.tmax, false};
  for (int i = 0; i < 3; ++i) {
    const bool neg = a.IsNeg(r.inv_d[i]);
    const T near_plane = a.Load(neg ? bounds_max[i] : bounds_min[i]);
    const T far_plane = a.Load(neg ? bounds_min[i] : bounds_max[i]);
    const T tn = a.Mul(a.Sub(near_plane, r.o[i]), r.inv_d[i]);
    const T tf = a.Mul(a.Sub(far_plane, r.o[i]), r.inv_d[i]);
    if (a.Lt(c.t0, tn)) c.t0 = tn;
    if (a.Lt(tf, c.t1)) c.t1 = tf;
  }
  c.t0 = a.NudgeDown(c.t0, kTraversalSlackUlps);
  c.t1 = a.NudgeUp(c.t1, kTraversalSlackUlps);
  c.miss = a.Lt(c.t1, c.t0);
  return c;
}

// One inner node (the traversal unit, rtl/rt_trav_unit.sv).
enum class TraversalAction { kFirst, kSecond, kPush };

template <class A>
struct TraversalStep {
  typename A::T t_split;  // (split - o) * inv_d
  typename A::T t_lo;     // t_split nudged down: where the far child's interval starts
  typename A::T t_hi;     // t_split nudged up: where the near child's interval ends
  bool below_first;
  TraversalAction action;  // kPush: push (second, t_lo, t1), go first with t1 = t_hi
};

// The step's action from its split distance and the (nudged) ends of its
// two children against the cell's interval [t0, t1].
template <class A>
KDRT_HOT_INLINE TraversalAction DecideAction(const A& a, const TraversalStep<A>& s, typename A::T t0,
                                             typename A::T t1) {
  if (a.Lt(t1, s.t_lo) || a.Le(s.t_split, a.Zero())) return TraversalAction::kFirst;
  if (a.Lt(s.t_hi, t0)) return TraversalAction::kSecond;
  return TraversalAction::kPush;
}

template <class A>
KDRT_HOT_INLINE TraversalStep<A> StepInnerNode(const A& a, float split_fp32, typename A::T o, typename A::T d,
                                               typename A::T inv_d, typename A::T t0, typename A::T t1) {
  TraversalStep<A> s;
  const typename A::T split = a.Load(split_fp32);
  s.t_split = a.Mul(a.Sub(split, o), inv_d);
  s.t_lo = a.NudgeDown(s.t_split, kTraversalSlackUlps);
  s.t_hi = a.NudgeUp(s.t_split, kTraversalSlackUlps);
  s.below_first = a.Lt(o, split) || (a.Eq(o, split) && a.Le(d, a.Zero()));
  s.action = DecideAction(a, s, t0, t1);
  return s;
}

// A split distance that is NaN: the ray lies in the split plane. A triangle
// touching the plane from one side only is listed in that side's child
// alone, so such a ray must see both children, and a hit in the near child
// says nothing about the far one: the usual stop rules assume the children's
// intervals are ordered along the ray, and these are not. The near child
// gets a NaN exit (the nudge keeps NaN) and the far child a NaN entry, and
// the far child's stack entry marks the ray: while one is on the stack, the
// ray stops only when its stack is empty (rtl/rt_leaf_exit.sv counts them).
template <class A>
bool InPlane(const A& a, typename A::T t_entry) {
  return !a.Eq(t_entry, t_entry);
}

// Converts a datapath result to the fp32 hit record (exact widening), t in
// the caller's units (an exact power-of-two scale, trace/frame.h).
template <class A>
Hit ToHit(const A& a, const TraceResult<A>& r) {
  Hit h;
  if (r.prim == kNoPrim) return h;
  if constexpr (std::is_same_v<A, fp::NativeF32Arith>) {
    h.t = DistanceToWorldFtz(r.t, r.t_scale_log2);  // A's contract: FTZ is held
  } else {
    h.t = DistanceToWorld(a.Store(r.t), r.t_scale_log2);
  }
  h.u = a.Store(r.u);
  h.v = a.Store(r.v);
  h.prim = r.prim;
  return h;
}

// The traversal may run in a wider format than the triangle test (a
// separate traversal datapath, TraceOptions::trav_format). It then works on
// the test's own ray, widened exactly (At must hold every value of Ai), so
// its conservative cells are those of the ray the test sees and the slack
// argument above holds in At's ulps; hit distances are compared with cell
// ends after the same exact widening.
// The triangle test decides as if each vertex were moved by about an ulp of
// |vertex - origin| in the test's format (the rounding of vertex - origin
// and of the shear), so a cell must also reach that far beyond where the
// traversal's own arithmetic puts it. In one format the traversal's slack
// covers it (kTraversalSlackUlps); a wider traversal rounds every interval
// end outwards to the test's format and adds kTestSlackUlps encodings
// (docs/precision.md, "A traversal wider than the test").
inline constexpr uint32_t kTestSlackUlps = 1;

// A test-format value in the traversal format (exact: At holds Ai).
template <class At, class Ai>
typename At::T Widen(const At& at, const Ai& ai, typename Ai::T x) {
  return at.Load(ai.Store(x));
}

// The traversal's ray in a wider format: the test's origin, direction
// (after its flushed-shear rule) and interval widened to At, with At's own
// reciprocal direction (rtl/rt_ray_setup.sv's out_inv_o). Only those: the
// traversal traces exactly the test's ray, so no rule of At's own setup
// (axes, shears) applies.
template <class At, class Ai>
RaySetup<At> TraversalRay(const At& at, const Ai& ai, const RaySetup<Ai>& r) {
  RaySetup<At> t{};
  for (int i = 0; i < 3; ++i) {
    t.o[i] = Widen(at, ai, r.o[i]);
    t.d[i] = Widen(at, ai, r.d[i]);
    t.inv_d[i] = at.Div(at.One(), t.d[i]);
  }
  t.tmin = Widen(at, ai, r.tmin);
  t.tmax = Widen(at, ai, r.tmax);
  return t;
}

// x moved outwards (up or down) by at least kTestSlackUlps encodings of the
// test's format: rounded to it towards the outside (to nearest, then one
// encoding further if that went inwards), then nudged. Positive values only
// move, as the nudges do (a positive x below the format's smallest normal
// rounds up to +0, as the format's own arithmetic flushes it). The result is
// a value of the test's format: cell intervals and the stack need no more
// bits than the test's format.
template <class At, class Ai>
typename At::T WidenForTest(const At& at, const Ai& ai, typename At::T x, bool up) {
  typename Ai::T r = ai.Load(at.Store(x));
  const typename At::T back = Widen(at, ai, r);
  if (up && at.Lt(back, x)) r = ai.NudgeUp(r, 1);
  if (!up && at.Lt(x, back)) r = ai.NudgeDown(r, 1);
  return Widen(at, ai, up ? ai.NudgeUp(r, kTestSlackUlps) : ai.NudgeDown(r, kTestSlackUlps));
}

// The box clip of a traversal wider than the test (rtl/rt_clip_unit.sv with
// TravE, TravM): the box rounded to the test's format like the splits, the
// clip in At, its ends moved outwards into the test's format.
template <class At, class Ai>
BoxClip<At> ClipToBoxMixed(const At& at, const Ai& ai, const RaySetup<At>& r, const float bounds_min[3],
                           const float bounds_max[3]) {
  float bmin[3], bmax[3];
  for (int i = 0; i < 3; ++i) {
    bmin[i] = ai.Store(ai.Load(bounds_min[i]));
    bmax[i] = ai.Store(ai.Load(bounds_max[i]));
  }
  BoxClip<At> c = ClipToBox(at, r, bmin, bmax);
  c.t0 = WidenForTest(at, ai, c.t0, false);
  c.t1 = WidenForTest(at, ai, c.t1, true);
  c.miss = at.Lt(c.t1, c.t0);
  return c;
}

// The traversal step of a traversal wider than the test (rtl/rt_trav_unit.sv
// with TravE, TravM): o, d, t0 and t1 are test-format values (widened), inv_d
// is At's; the split is rounded to the test's format (as the vertices are:
// rounding both the same monotone way keeps every triangle on the side of the
// plane the builder put it), the step runs in At, and the children's ends are
// moved outwards into the test's format.
template <class At, class Ai>
KDRT_HOT_INLINE TraversalStep<At> StepInnerNodeMixed(const At& at, const Ai& ai, float split_fp32,
                                                     typename At::T o, typename At::T d, typename At::T inv_d,
                                                     typename At::T t0, typename At::T t1) {
  TraversalStep<At> s = StepInnerNode(at, ai.Store(ai.Load(split_fp32)), o, d, inv_d, t0, t1);
  s.t_lo = WidenForTest(at, ai, s.t_lo, false);
  s.t_hi = WidenForTest(at, ai, s.t_hi, true);
  s.action = DecideAction(at, s, t0, t1);
  return s;
}

// `path`, when given, receives the index of every node fetched, in order.
// `stack_limit` below the tree's depth models the core's StackDepth: a push
// onto that many entries ends the ray with the hit it has so far, as
// rt_core does (its thread goes to DONE with the overflow bit, rt_thread_fsm),
// and counts an overflow. `at` is the traversal's arithmetic, `ai` the
// triangle test's: the same object unless Mixed (a separate traversal
// format; a template parameter so that the one-format path pays nothing).
template <bool Mixed, class At, class Ai>
TraceResult<Ai> TraceRayIn(const At& at, const Ai& ai, const ImageView& image, const Ray& ray, IsectMethod isect,
                           Query query, RayCounters* counters = nullptr, std::vector<uint32_t>* path = nullptr,
                           int stack_limit = kMaxTraversalStack) {
  using T = typename At::T;
  // Native fp32 holds FTZ (NativeF32Arith's contract): its frame mapping
  // may run natively, with the same bits.
  FramedRay framed;
  if constexpr (!Mixed && std::is_same_v<Ai, fp::NativeF32Arith>) {
    framed = ToFrameFtz(ray, image.frame());
  } else {
    framed = ToFrame(ray, image.frame());
  }
  const RaySetup<Ai> r = SetupRay(ai, framed.ray);
  TraceResult<Ai> best;
  best.t_scale_log2 = framed.t_scale_log2;
  best.t = r.tmax;
  best.u = best.v = ai.Zero();

  const img::Header& h = image.header();
  RaySetup<At> mixed_ray;  // Mixed: the traversal's own ray
  const RaySetup<At>* trav_ray = nullptr;
  BoxClip<At> clip;
  if constexpr (Mixed) {
    mixed_ray = TraversalRay(at, ai, r);
    trav_ray = &mixed_ray;
    clip = ClipToBoxMixed(at, ai, mixed_ray, h.bounds_min, h.bounds_max);
  } else {
    trav_ray = &r;
    clip = ClipToBox(at, r, h.bounds_min, h.bounds_max);
  }
  const RaySetup<At>& rt = *trav_ray;
  if (clip.miss) return best;

  struct Entry {
    uint32_t node;
    T t0, t1;
  };
  const uint32_t* lists = image.lists();
  // A leaf's candidate: the closest hit so far if its t is smaller, or equal
  // with a smaller triangle id (so the order of a leaf's tests does not matter).
  const auto offer = [&ai, &best](typename Ai::T t, typename Ai::T u, typename Ai::T v, uint32_t id) {
    if (ai.Lt(t, best.t) || (ai.Eq(t, best.t) && id < best.prim)) {
      best.t = t;
      best.u = u;
      best.v = v;
      best.prim = id;
    }
  };
  // Native fp32 on an fp32 image tests a leaf of two or more triangles four
  // at a time, bit for bit the scalar tests (trace/leaf_x4.h); a single
  // triangle takes the scalar test (1-4 % faster than the four-wide one's
  // gather on balls, tetra, gears and rings).
  bool four_wide = false;
  if constexpr (!Mixed && std::is_same_v<Ai, fp::NativeF32Arith>) {
    four_wide = KDRT_HAVE_LEAF_X4 && isect == IsectMethod::kWatertight && image.raw_triangles() != nullptr;
  }
  // An fp32 image's nodes are read in place: ImageView::node and ::next
  // test the layout at every node.
  const img::Node* raw_nodes = image.raw_nodes();
  const img::ImageLayout& layout = image.layout();
  // The walk, compiled twice for native fp32: the common case (an fp32
  // image, no path recorded) without the per-node tests of either. Its
  // state is its own (not captured): GCC kept captured locals in memory,
  // which put a store and a load on every step's chain.
  const auto walk = [&](auto raw_no_path) -> TraceResult<Ai> {
    constexpr bool kRawNoPath = decltype(raw_no_path)::value;
    T t0 = clip.t0, t1 = clip.t1;
    Entry stack[kMaxTraversalStack];
    int sp = 0;
    int in_plane = 0;  // stack entries with a NaN entry t (InPlane)
    // Counted in a local, added to *counters once, on whichever return
    // (the returns before the walk have counted nothing).
    RayCounters walked;
    const auto finish = [counters, &walked, &best]() {
      if (counters) *counters += walked;
      return best;
    };
    uint32_t node = 0;
    for (;;) {
      const img::Node n = kRawNoPath || raw_nodes ? raw_nodes[node] : image.node(node);
      // An empty leaf other than the root is marked in its parent: the
      // hardware goes to the leaf's exit without fetching it, so it counts
      // neither as a node nor as a leaf (it stays on the path).
      const bool fetched = !(n.IsLeaf() && n.Count() == 0 && node != 0);
      walked.nodes += fetched;
      walked.empty_skipped += !fetched;
      if constexpr (!kRawNoPath) {
        if (path) path->push_back(node);
      }
      if (!n.IsLeaf()) {
        const int axis = n.Axis();
        TraversalStep<At> step;
        if constexpr (Mixed) {
          step = StepInnerNodeMixed(at, ai, n.Split(), rt.o[axis], rt.d[axis], rt.inv_d[axis], t0, t1);
        } else {
          step = StepInnerNode(at, n.Split(), rt.o[axis], rt.d[axis], rt.inv_d[axis], t0, t1);
        }
        const uint32_t below = kRawNoPath || raw_nodes ? node + 1 : layout.NextNode(node);
        const uint32_t first = step.below_first ? below : n.AboveChild();
        const uint32_t second = step.below_first ? n.AboveChild() : below;
        if (step.action == TraversalAction::kFirst) {
          node = first;
        } else if (step.action == TraversalAction::kSecond) {
          node = second;
        } else {
          if (sp >= stack_limit) {
            ++walked.overflows;
            return finish();
          }
          stack[sp++] = Entry{second, step.t_lo, t1};
          if (InPlane(at, step.t_lo)) ++in_plane;
          node = first;
          t1 = step.t_hi;
        }
        continue;
      }
      walked.leaves += fetched;
      const uint32_t count = n.Count();
      const uint32_t* ids = lists + n.FirstEntry();
      const typename Ai::T leaf_tmax = best.t;
      walked.tri_tests += count;
      if (four_wide && count > 1) {
#if KDRT_HAVE_LEAF_X4
        if constexpr (!Mixed && std::is_same_v<Ai, fp::NativeF32Arith>) {
          for (uint32_t k = 0; k < count; k += 4) {
            float ct[4], cu[4], cv[4];
            const uint32_t group = count - k < 4 ? count - k : 4;
            for (unsigned m = IntersectWatertightX4(r, image.raw_triangles(), ids + k, group, leaf_tmax, ct, cu, cv);
                 m != 0; m &= m - 1) {
              const int lane = __builtin_ctz(m);
              offer(ct[lane], cu[lane], cv[lane], ids[k + lane]);
            }
          }
        }
#endif
      } else {
        for (uint32_t k = 0; k < count; ++k) {
          const uint32_t id = ids[k];
          const Candidate<Ai> c = isect == IsectMethod::kWatertight
                                      ? IntersectWatertight(ai, r, image.triangle(id), leaf_tmax)
                                      : IntersectMoller(ai, r, image.triangle(id), leaf_tmax);
          if (c.hit) offer(c.t, c.u, c.v, id);
        }
      }
      const bool may_stop = best.prim != kNoPrim && in_plane == 0;
      if (best.prim != kNoPrim && query == Query::kAny) return finish();
      T best_t;
      if constexpr (Mixed) {
        best_t = Widen(at, ai, best.t);
      } else {
        best_t = best.t;
      }
      if (may_stop && at.Le(best_t, t1)) return finish();
      if (sp == 0) return finish();
      const Entry& e = stack[--sp];
      if (may_stop && at.Lt(best_t, e.t0)) return finish();
      if (InPlane(at, e.t0)) --in_plane;
      node = e.node;
      t0 = e.t0;
      t1 = e.t1;
    }
  };
  if constexpr (!Mixed && std::is_same_v<Ai, fp::NativeF32Arith>) {
    if (raw_nodes != nullptr && path == nullptr) return walk(std::true_type{});
  }
  return walk(std::false_type{});
}

// Traversal and test in one format (the RTL core's datapath).
template <class A>
TraceResult<A> TraceRay(const A& a, const ImageView& image, const Ray& ray, IsectMethod isect, Query query,
                        RayCounters* counters = nullptr, std::vector<uint32_t>* path = nullptr,
                        int stack_limit = kMaxTraversalStack) {
  return TraceRayIn<false>(a, a, image, ray, isect, query, counters, path, stack_limit);
}

}  // namespace kdrt
