// The floor under any scalar walk of a kd-tree image: what the simplest walk
// we could write costs per ray (its setup) and per node, on this tree and
// these rays, with nothing else to do. kdrt_bench multiplies it by the nodes
// the reference tracer really visits per ray: a tracer that visits those
// nodes cannot be faster than that, however cheap its triangle tests.
//
// The bare walk has no triangle tests, no slack on the cell intervals, no
// stop rule (it crosses every cell the ray crosses: more nodes than a real
// trace, each as cheap as a step can be) and no counters; the ray setup is the
// tracer's own (frame, watertight setup, box clip). It is a measurement, not
// a tracer: its decisions are not the hardware's.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "fp/ftz.h"
#include "trace/memory_image.h"
#include "trace/traversal.h"

namespace kdrt::bench {

struct WalkFloor {
  double setup_ns_per_ray = 0;  // frame, ray setup and box clip alone
  double ns_per_node = 0;       // the bare walk's time beyond its setup, per node
  double nodes_per_ray = 0;     // nodes the bare walk visits
};

namespace detail {

// Returns the nodes visited (0 if `walk` is false: the setup alone).
inline uint64_t BareWalk(const ImageView& image, const std::vector<Ray>& rays, bool walk, float* sink) {
  const fp::NativeF32Arith a;
  const img::Node* nodes = image.raw_nodes();
  const img::Header& h = image.header();
  const Frame frame = image.frame();
  uint64_t visited = 0;
  float keep = 0;
  struct Entry {
    uint32_t node;
    float t0, t1;
  };
  Entry stack[kMaxTraversalStack];
  for (const Ray& ray : rays) {
    const RaySetup<fp::NativeF32Arith> r = SetupRay(a, ToFrameFtz(ray, frame).ray);
    const BoxClip<fp::NativeF32Arith> c = ClipToBox(a, r, h.bounds_min, h.bounds_max);
    keep += c.t0;
    if (!walk || c.miss) continue;
    float t0 = c.t0, t1 = c.t1;
    int sp = 0;
    uint32_t node = 0;
    for (;;) {
      const img::Node n = nodes[node];
      ++visited;
      if (!n.IsLeaf()) {
        const int axis = n.Axis();
        const float split = n.Split();
        const float t_split = (split - r.o[axis]) * r.inv_d[axis];
        const bool below_first = r.o[axis] < split || (r.o[axis] == split && r.d[axis] <= 0.0f);
        const uint32_t first = below_first ? node + 1 : n.AboveChild();
        const uint32_t second = below_first ? n.AboveChild() : node + 1;
        if (t_split > t1 || t_split <= 0.0f) {
          node = first;
        } else if (t_split < t0) {
          node = second;
        } else if (sp < kMaxTraversalStack) {
          stack[sp++] = Entry{second, t_split, t1};
          node = first;
          t1 = t_split;
        } else {
          break;
        }
        continue;
      }
      if (sp == 0) break;
      --sp;
      node = stack[sp].node;
      t0 = stack[sp].t0;
      t1 = stack[sp].t1;
    }
  }
  *sink += keep;
  return visited;
}

}  // namespace detail

// The fastest of `repeat` runs of each (an fp32 image: raw nodes).
inline WalkFloor MeasureWalkFloor(const ImageView& image, const std::vector<Ray>& rays, int repeat) {
  WalkFloor f;
  if (image.raw_nodes() == nullptr || rays.empty()) return f;
  fp::ScopedFtzDaz ftz;
  float sink = 0;
  double setup_s = 0, walk_s = 0;
  uint64_t visited = 0;
  for (int run = 0; run < repeat; ++run) {
    auto start = std::chrono::steady_clock::now();
    detail::BareWalk(image, rays, false, &sink);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    start = std::chrono::steady_clock::now();
    visited = detail::BareWalk(image, rays, true, &sink);
    const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    setup_s = run == 0 ? s : std::min(setup_s, s);
    walk_s = run == 0 ? w : std::min(walk_s, w);
  }
  asm volatile("" : : "m"(sink));
  const double n = static_cast<double>(rays.size());
  f.setup_ns_per_ray = setup_s * 1e9 / n;
  f.nodes_per_ray = static_cast<double>(visited) / n;
  f.ns_per_node = visited ? std::max(0.0, walk_s - setup_s) * 1e9 / static_cast<double>(visited) : 0.0;
  return f;
}

}  // namespace kdrt::bench
