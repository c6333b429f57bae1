#include "trace/tracer.h"

#include <chrono>

#include "common/error.h"
#include "fp/ftz.h"
#include "trace/ray_pool.h"
#include "trace/traversal.h"

namespace kdrt {

IsectMethod ParseIsectMethod(const std::string& name) {
  if (name == "watertight") return IsectMethod::kWatertight;
  if (name == "moller") return IsectMethod::kMoller;
  throw InputError("unknown intersection method '" + name + "' (expected watertight or moller)");
}

const char* IsectMethodName(IsectMethod m) { return m == IsectMethod::kWatertight ? "watertight" : "moller"; }

namespace {

int StackLimit(const TraceOptions& options) {
  return options.stack_depth > 0 ? options.stack_depth : kMaxTraversalStack;
}

// Runs fn(arith) with the arithmetic policy for the format: native float for
// fp32, native double for fp64 (the reference), the soft-float model for the
// rest (SoftArith refuses anything that is not a soft format).
template <class Fn>
auto WithArith(const fp::Format& format, Fn&& fn) {
  if (format.IsFp32()) {
    fp::ScopedFtzDaz ftz;
    return fn(fp::NativeF32Arith{});
  }
  if (format.IsFp64()) {
    fp::ScopedIeeeDefault ieee;
    return fn(fp::NativeF64Arith{});
  }
  return fn(fp::SoftArith(format));
}

}  // namespace

Hit TraceOne(const ImageView& image, const Ray& ray, const TraceOptions& options, RayCounters* counters,
             std::vector<uint32_t>* path) {
  return WithArith(options.format, [&](const auto& a) {
    return ToHit(a, TraceRay(a, image, ray, options.isect, options.query, counters, path, StackLimit(options)));
  });
}

std::vector<Hit> TraceRays(const ImageView& image, const std::vector<Ray>& rays, const TraceOptions& options,
                           TraceStats* stats, std::vector<RayCounters>* per_ray) {
  std::vector<Hit> hits(rays.size());
  std::vector<RayCounters> counters(rays.size());
  const auto start = std::chrono::steady_clock::now();
  RunRayThreads(rays.size(), options.threads, options.progress, [&](const NextChunk& next_chunk) {
    WithArith(options.format, [&](const auto& a) {
      size_t begin, end;
      while (next_chunk(&begin, &end)) {
        for (size_t i = begin; i < end; ++i) {
          hits[i] = ToHit(a, TraceRay(a, image, rays[i], options.isect, options.query, &counters[i], nullptr,
                                      StackLimit(options)));
        }
      }
      return 0;
    });
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (stats) {
    *stats = TraceStats{};
    stats->rays = rays.size();
    stats->seconds = seconds;
    for (size_t i = 0; i < rays.size(); ++i) {
      stats->totals += counters[i];
      if (hits[i].IsHit()) ++stats->hits;
    }
  }
  if (per_ray) *per_ray = std::move(counters);
  return hits;
}

}  // namespace kdrt
