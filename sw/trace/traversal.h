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
#include <vector>

#include "common/ray.h"
#include "trace/frame.h"
#include "trace/intersect.h"
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

template <class A>
BoxClip<A> ClipToBox(const A& a, const RaySetup<A>& r, const float bounds_min[3], const float bounds_max[3]) {
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

template <class A>
TraversalStep<A> StepInnerNode(const A& a, float split_fp32, typename A::T o, typename A::T d,
                               typename A::T inv_d, typename A::T t0, typename A::T t1) {
  TraversalStep<A> s;
  const typename A::T split = a.Load(split_fp32);
  s.t_split = a.Mul(a.Sub(split, o), inv_d);
  s.t_lo = a.NudgeDown(s.t_split, kTraversalSlackUlps);
  s.t_hi = a.NudgeUp(s.t_split, kTraversalSlackUlps);
  s.below_first = a.Lt(o, split) || (a.Eq(o, split) && a.Le(d, a.Zero()));
  if (a.Lt(t1, s.t_lo) || a.Le(s.t_split, a.Zero())) {
    s.action = TraversalAction::kFirst;
  } else if (a.Lt(s.t_hi, t0)) {
    s.action = TraversalAction::kSecond;
  } else {
    s.action = TraversalAction::kPush;
  }
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
  h.t = DistanceToWorld(a.Store(r.t), r.t_scale_log2);
  h.u = a.Store(r.u);
  h.v = a.Store(r.v);
  h.prim = r.prim;
  return h;
}

// `path`, when given, receives the index of every node fetched, in order.
// `stack_limit` below the tree's depth models the core's StackDepth: a push
// onto that many entries ends the ray with the hit it has so far, as
// rt_core does (its thread goes to DONE with the overflow bit, rt_thread_fsm),
// and counts an overflow.
template <class A>
TraceResult<A> TraceRay(const A& a, const ImageView& image, const Ray& ray, IsectMethod isect, Query query,
                        RayCounters* counters = nullptr, std::vector<uint32_t>* path = nullptr,
                        int stack_limit = kMaxTraversalStack) {
  using T = typename A::T;
  const FramedRay framed = ToFrame(ray, image.frame());
  const RaySetup<A> r = SetupRay(a, framed.ray);
  TraceResult<A> best;
  best.t_scale_log2 = framed.t_scale_log2;
  best.t = r.tmax;
  best.u = best.v = a.Zero();

  const img::Header& h = image.header();
  const BoxClip<A> clip = ClipToBox(a, r, h.bounds_min, h.bounds_max);
  if (clip.miss) return best;
  T t0 = clip.t0, t1 = clip.t1;

  struct Entry {
    uint32_t node;
    T t0, t1;
  };
  Entry stack[kMaxTraversalStack];
  int sp = 0;
  int in_plane = 0;  // stack entries with a NaN entry t (InPlane)
  const uint32_t* lists = image.lists();
  uint32_t node = 0;
  for (;;) {
    const img::Node n = image.node(node);
    if (counters) ++counters->nodes;
    if (path) path->push_back(node);
    if (!n.IsLeaf()) {
      const TraversalStep<A> step =
          StepInnerNode(a, n.Split(), r.o[n.Axis()], r.d[n.Axis()], r.inv_d[n.Axis()], t0, t1);
      const uint32_t below = image.next(node);
      const uint32_t first = step.below_first ? below : n.AboveChild();
      const uint32_t second = step.below_first ? n.AboveChild() : below;
      if (step.action == TraversalAction::kFirst) {
        node = first;
      } else if (step.action == TraversalAction::kSecond) {
        node = second;
      } else {
        if (sp >= stack_limit) {
          if (counters) ++counters->overflows;
          return best;
        }
        stack[sp++] = Entry{second, step.t_lo, t1};
        if (InPlane(a, step.t_lo)) ++in_plane;
        node = first;
        t1 = step.t_hi;
      }
      continue;
    }
    if (counters) ++counters->leaves;
    const uint32_t count = n.Count();
    if (count > 0) {
      const T leaf_tmax = best.t;
      for (uint32_t k = 0; k < count; ++k) {
        const uint32_t id = lists[n.FirstEntry() + k];
        if (counters) ++counters->tri_tests;
        const Candidate<A> c = isect == IsectMethod::kWatertight
                                   ? IntersectWatertight(a, r, image.triangle(id), leaf_tmax)
                                   : IntersectMoller(a, r, image.triangle(id), leaf_tmax);
        if (!c.hit) continue;
        if (a.Lt(c.t, best.t) || (a.Eq(c.t, best.t) && id < best.prim)) {
          best.t = c.t;
          best.u = c.u;
          best.v = c.v;
          best.prim = id;
        }
      }
    }
    const bool may_stop = best.prim != kNoPrim && in_plane == 0;
    if (best.prim != kNoPrim && query == Query::kAny) return best;
    if (may_stop && a.Le(best.t, t1)) return best;
    if (sp == 0) return best;
    const Entry& e = stack[--sp];
    if (may_stop && a.Lt(best.t, e.t0)) return best;
    if (InPlane(a, e.t0)) --in_plane;
    node = e.node;
    t0 = e.t0;
    t1 = e.t1;
  }
}

}  // namespace kdrt
