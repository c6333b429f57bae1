#include "structures/structure_tracer.h"

#include <chrono>

#include "common/error.h"
#include "fp/ftz.h"
#include "trace/ray_pool.h"

namespace kdrt {
namespace {

template <class A>
Hit TraceWith(const A& a, const Structure& s, const Frame& frame, const Ray& ray, Query query,
              TraceScratch& scratch) {
  const FramedRay framed = ToFrame(ray, frame);
  const RaySetup<A> r = SetupRay(a, framed.ray);
  TraceResult<A> best;
  best.t_scale_log2 = framed.t_scale_log2;
  best.t = r.tmax;
  best.u = best.v = a.Zero();
  scratch.counters = AccelCounters{};
  scratch.mailbox.NextRay();
  s.Trace(a, r, query, best, scratch);
  return ToHit(a, best);
}

// fn(arith) under the format's rounding mode (as the kd-tree tracer).
template <class Fn>
auto WithNativeArith(const fp::Format& format, Fn&& fn) {
  if (format.IsFp32()) {
    fp::ScopedFtzDaz ftz;
    return fn(fp::NativeF32Arith{});
  }
  fp::ScopedIeeeDefault ieee;
  return fn(fp::NativeF64Arith{});
}

}  // namespace

AccelTotals ToAccelTotals(const TraceStats& ts) {
  AccelTotals t;
  t.rays = ts.rays;
  t.hits = ts.hits;
  t.seconds = ts.seconds;
  t.nodes = ts.totals.nodes;
  t.leaves = ts.totals.leaves;
  t.tri_tests = ts.totals.tri_tests;
  return t;
}

void CheckStructureTraceOptions(const TraceOptions& options) {
  if (!options.format.IsFp32() && !options.format.IsFp64()) {
    throw InputError("the software structures (grid, hgrid, octree, bvh) trace in fp32 or fp64 only, not " +
                     options.format.Name() + " (the reduced formats and the hardware read the kd-tree)");
  }
  if (options.isect != IsectMethod::kWatertight) {
    throw InputError("the software structures use the watertight test only (not --isect moller)");
  }
  if (TravFormat(options) != options.format) {
    throw InputError("the software structures trace in one format (no --trav-format); it is the kd-tree's option");
  }
}

Hit TraceStructureOne(const Structure& s, const Frame& frame, const Ray& ray, const TraceOptions& options,
                      TraceScratch& scratch) {
  CheckStructureTraceOptions(options);
  return WithNativeArith(options.format,
                         [&](const auto& a) { return TraceWith(a, s, frame, ray, options.query, scratch); });
}

std::vector<Hit> TraceStructureRays(const Structure& s, const Frame& frame, const std::vector<Ray>& rays,
                                    const TraceOptions& options, AccelTotals* totals,
                                    std::vector<AccelCounters>* per_ray) {
  CheckStructureTraceOptions(options);
  std::vector<Hit> hits(rays.size());
  std::vector<AccelCounters> counters(rays.size());
  const size_t triangles = s.triangle_count();
  const auto start = std::chrono::steady_clock::now();
  RunRayThreads(rays.size(), options.threads, options.progress, [&](const NextChunk& next_chunk) {
    TraceScratch scratch(triangles);
    WithNativeArith(options.format, [&](const auto& a) {
      size_t begin, end;
      while (next_chunk(&begin, &end)) {
        for (size_t i = begin; i < end; ++i) {
          hits[i] = TraceWith(a, s, frame, rays[i], options.query, scratch);
          counters[i] = scratch.counters;
        }
      }
      return 0;
    });
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (totals) {
    *totals = AccelTotals{};
    totals->rays = rays.size();
    totals->seconds = seconds;
    for (size_t i = 0; i < rays.size(); ++i) {
      totals->Add(counters[i]);
      if (hits[i].IsHit()) ++totals->hits;
    }
  }
  if (per_ray) *per_ray = std::move(counters);
  return hits;
}

}  // namespace kdrt
