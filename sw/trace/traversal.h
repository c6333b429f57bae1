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
//  - after a leaf, the ray stops if it has a hit with t <= the cell's exit t;
//    a popped cell whose entry t lies beyond the best hit also ends the ray.
#pragma once

#include <cstdint>
#include <vector>

#include "common/ray.h"
#include "trace/intersect.h"
#include "trace/memory_image.h"

namespace kdrt {

// A validated image is less than kMaxImageDepth deep, and a push happens at
// most once per level, so the stack cannot overflow.
inline constexpr int kMaxTraversalStack = kMaxImageDepth;

template <class A>
struct TraceResult {
  typename A::T t, u, v;
  uint32_t prim = kNoPrim;
};

// Converts a datapath result to the fp32 hit record (exact widening).
template <class A>
Hit ToHit(const A& a, const TraceResult<A>& r) {
  Hit h;
  if (r.prim == kNoPrim) return h;
  h.t = a.Store(r.t);
  h.u = a.Store(r.u);
  h.v = a.Store(r.v);
  h.prim = r.prim;
  return h;
}

// `path`, when given, receives the index of every node fetched, in order.
template <class A>
TraceResult<A> TraceRay(const A& a, const ImageView& image, const Ray& ray, IsectMethod isect,
                        RayCounters* counters = nullptr, std::vector<uint32_t>* path = nullptr) {
  using T = typename A::T;
  const RaySetup<A> r = SetupRay(a, ray);
  TraceResult<A> best;
  best.t = r.tmax;
  best.u = best.v = a.Zero();

  // Clip [tmin, tmax] to the scene box. A slab whose distances are NaN (ray
  // parallel to and in the slab's plane) does not narrow the interval.
  const img::Header& h = image.header();
  T t0 = r.tmin, t1 = r.tmax;
  for (int i = 0; i < 3; ++i) {
    const T near_plane = a.IsNeg(r.inv_d[i]) ? a.Load(h.bounds_max[i]) : a.Load(h.bounds_min[i]);
    const T far_plane = a.IsNeg(r.inv_d[i]) ? a.Load(h.bounds_min[i]) : a.Load(h.bounds_max[i]);
    const T tn = a.Mul(a.Sub(near_plane, r.o[i]), r.inv_d[i]);
    const T tf = a.Mul(a.Sub(far_plane, r.o[i]), r.inv_d[i]);
    if (a.Lt(t0, tn)) t0 = tn;
    if (a.Lt(tf, t1)) t1 = tf;
  }
  if (a.Lt(t1, t0)) return best;

  struct Entry {
    uint32_t node;
    T t0, t1;
  };
  Entry stack[kMaxTraversalStack];
  int sp = 0;
  const img::Node* nodes = image.nodes();
  const uint32_t* lists = image.lists();
  const img::TriangleRecord* tris = image.triangles();
  uint32_t node = 0;
  for (;;) {
    const img::Node n = nodes[node];
    if (counters) ++counters->nodes;
    if (path) path->push_back(node);
    if (!n.IsLeaf()) {
      const int axis = n.Axis();
      const T split = a.Load(n.Split());
      const T t_split = a.Mul(a.Sub(split, r.o[axis]), r.inv_d[axis]);
      const bool below_first =
          a.Lt(r.o[axis], split) || (a.Eq(r.o[axis], split) && a.Le(r.d[axis], a.Zero()));
      const uint32_t first = below_first ? node + 1 : n.AboveChild();
      const uint32_t second = below_first ? n.AboveChild() : node + 1;
      if (a.Lt(t1, t_split) || a.Le(t_split, a.Zero())) {
        node = first;
      } else if (a.Lt(t_split, t0)) {
        node = second;
      } else {
        stack[sp++] = Entry{second, t_split, t1};
        node = first;
        t1 = t_split;
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
                                   ? IntersectWatertight(a, r, tris[id], leaf_tmax)
                                   : IntersectMoller(a, r, tris[id], leaf_tmax);
        if (!c.hit) continue;
        if (a.Lt(c.t, best.t) || (a.Eq(c.t, best.t) && id < best.prim)) {
          best.t = c.t;
          best.u = c.u;
          best.v = c.v;
          best.prim = id;
        }
      }
    }
    if (best.prim != kNoPrim && a.Le(best.t, t1)) return best;
    if (sp == 0) return best;
    const Entry& e = stack[--sp];
    if (best.prim != kNoPrim && a.Lt(best.t, e.t0)) return best;
    node = e.node;
    t0 = e.t0;
    t1 = e.t1;
  }
}

}  // namespace kdrt
