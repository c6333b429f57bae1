// The walk floor: what the simplest walk of a kd-tree image we could write
// costs on these rays, visiting the nodes the reference tracer visits, with
// nothing else to do. A tracer that visits those nodes is not faster than
// that, however cheap its triangle tests.
//
// The bare walk has the tracer's ray setup (frame, watertight setup, box
// clip) and its front-to-back order, but no triangle tests, no slack on the
// cell intervals and no counters; instead of the stop rules it ends each ray
// after as many leaves as the tracer's walk of that ray reached (fetched, or
// empty and passed), so it visits about the same nodes (the same ones but
// where the slack moved a decision), counting the nodes the tracer counts.
// It is a measurement, not a tracer: its decisions are not the hardware's.
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
  double ns_per_ray = 0;        // the bare walk, setup included
  double setup_ns_per_ray = 0;  // frame, ray setup and box clip alone
  double nodes_per_ray = 0;     // nodes the bare walk visits
};

namespace detail {

// Returns the nodes visited (0 if `walk` is false: the setup alone). Ray i
// ends after leaves[i] leaves.
inline uint64_t BareWalk(const ImageView& image, const std::vector<Ray>& rays, const std::vector<uint32_t>& leaves,
                         bool walk, float* sink) {
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
  for (size_t i = 0; i < rays.size(); ++i) {
    const RaySetup<fp::NativeF32Arith> r = SetupRay(a, ToFrameFtz(rays[i], frame).ray);
    const BoxClip<fp::NativeF32Arith> c = ClipToBox(a, r, h.bounds_min, h.bounds_max);
    keep += c.t0;
    if (!walk || c.miss) continue;
    float t0 = c.t0, t1 = c.t1;
    int sp = 0;
    uint32_t node = 0;
    uint32_t leaves_left = leaves[i];
    for (;;) {
      const img::Node n = nodes[node];
      // An empty leaf but the root is passed without a fetch (TraceRayIn).
      visited += !(n.IsLeaf() && n.Count() == 0 && node != 0);
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
      if (--leaves_left == 0 || sp == 0) break;
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

// The fastest of `repeat` runs (an fp32 image: raw nodes); leaves[i]: the
// leaves the tracer reached on ray i (RayCounters::leaves + empty_skipped).
inline WalkFloor MeasureWalkFloor(const ImageView& image, const std::vector<Ray>& rays,
                                  const std::vector<uint32_t>& leaves, int repeat) {
  WalkFloor f;
  if (image.raw_nodes() == nullptr || rays.empty() || leaves.size() != rays.size()) return f;
  fp::ScopedFtzDaz ftz;
  float sink = 0;
  double setup_s = 0, walk_s = 0;
  uint64_t visited = 0;
  for (int run = 0; run < repeat; ++run) {
    auto start = std::chrono::steady_clock::now();
    detail::BareWalk(image, rays, leaves, false, &sink);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    start = std::chrono::steady_clock::now();
    visited = detail::BareWalk(image, rays, leaves, true, &sink);
    const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    setup_s = run == 0 ? s : std::min(setup_s, s);
    walk_s = run == 0 ? w : std::min(walk_s, w);
  }
  asm volatile("" : : "m"(sink));
  const double n = static_cast<double>(rays.size());
  f.ns_per_ray = walk_s * 1e9 / n;
  f.setup_ns_per_ray = setup_s * 1e9 / n;
  f.nodes_per_ray = static_cast<double>(visited) / n;
  return f;
}

}  // namespace kdrt::bench
