#include "trace/tracer.h"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <type_traits>

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

// Runs fn(traversal arith, test arith). With a separate traversal format
// the test runs on the soft-float model (fp32 too: bit-identical to native,
// and native fp32 needs FTZ where a native fp64 traversal needs IEEE).
template <class Fn>
auto WithTraceArith(const TraceOptions& options, Fn&& fn) {
  const fp::Format trav = TravFormat(options);
  if (trav == options.format) {
    return WithArith(options.format, [&](const auto& a) { return fn(a, a, std::false_type{}); });
  }
  CheckTravFormat(options);
  const fp::SoftArith test(options.format);
  if (trav.IsFp64()) {
    fp::ScopedIeeeDefault ieee;
    return fn(fp::NativeF64Arith{}, test, std::true_type{});
  }
  if (trav.IsFp32()) {
    fp::ScopedFtzDaz ftz;
    return fn(fp::NativeF32Arith{}, test, std::true_type{});
  }
  return fn(fp::SoftArith(trav), test, std::true_type{});
}

}  // namespace

fp::Format TravFormat(const TraceOptions& options) { return options.trav_format.value_or(options.format); }

void CheckTravFormat(const fp::Format& format, const fp::Format& trav) {
  if (trav == format) return;
  if (trav.e < format.e || trav.m < format.m || format.IsFp64()) {
    throw InputError("traversal format " + trav.Name() + " does not hold every value of " + format.Name() +
                     ": it needs at least the test format's exponent and mantissa bits (the traversal works on "
                     "the test's ray, widened exactly)");
  }
}

void CheckTravFormat(const TraceOptions& options) { CheckTravFormat(options.format, TravFormat(options)); }

void CheckImageFormat(const fp::Format& format, const fp::Format& image) {
  if (image == format) return;
  if (image.IsFp64() || image.e > format.e || image.m > format.m) {
    throw InputError("image format " + image.Name() + " is wider than the datapath's " + format.Name() +
                     ": an image narrower than the format (at most its exponent and mantissa bits) is loaded "
                     "exactly; a wider one is not (kdrt render --image-format fp32 rounds it on every load)");
  }
}

Hit TraceOne(const ImageView& image, const Ray& ray, const TraceOptions& options, RayCounters* counters,
             std::vector<uint32_t>* path) {
  return WithTraceArith(options, [&](const auto& at, const auto& ai, auto mixed) {
    return ToHit(ai, TraceRayIn<decltype(mixed)::value>(at, ai, image, ray, options.isect, options.query, counters,
                                                          path, StackLimit(options)));
  });
}

std::vector<Hit> TraceRays(const ImageView& image, const std::vector<Ray>& rays, const TraceOptions& options,
                           TraceStats* stats, std::vector<RayCounters>* per_ray) {
  CheckTravFormat(options);  // here, not in the ray threads
  std::vector<Hit> hits(rays.size());
  std::vector<RayCounters> counters(rays.size());
  const PacketPlan plan = PlanPackets(image, options);
  std::mutex counts_mutex;
  PacketCounts packet_counts;
  const auto start = std::chrono::steady_clock::now();
  const int row = options.row_width;
  if (plan.width > 0 && row > 0 && rays.size() % row == 0) {
    // Tiles: a packet's rays gathered from neighbouring rows, its results
    // put back in each ray's slot.
    const int tw = plan.width == 4 ? 2 : 4, th = plan.width / tw;
    const size_t rows = rays.size() / row;
    const size_t tiles_x = (row + tw - 1) / tw, tiles_y = (rows + th - 1) / th;
    RunRayThreads(tiles_x * tiles_y, options.threads, options.progress, [&](const NextChunk& next_chunk) {
      fp::ScopedFtzDaz ftz;
      PacketCounts alone;
      Ray tile_rays[16];
      Hit tile_hits[16];
      RayCounters tile_counters[16];
      size_t index[16];
      size_t begin, end;
      while (next_chunk(&begin, &end)) {
        for (size_t t = begin; t < end; ++t) {
          const size_t x0 = t % tiles_x * tw, y0 = t / tiles_x * th;
          int n = 0;
          for (size_t y = y0; y < y0 + th && y < rows; ++y) {
            for (size_t x = x0; x < x0 + tw && x < static_cast<size_t>(row); ++x) {
              index[n] = y * row + x;
              tile_rays[n] = rays[index[n]];
              tile_counters[n] = RayCounters{};
              ++n;
            }
          }
          TracePacket(plan, image, tile_rays, n, options, tile_hits, tile_counters, &alone);
          for (int k = 0; k < n; ++k) {
            hits[index[k]] = tile_hits[k];
            counters[index[k]] = tile_counters[k];
          }
        }
      }
      const std::lock_guard<std::mutex> lock(counts_mutex);
      packet_counts += alone;
    });
  } else if (plan.width > 0) {
    // Packets of consecutive rays (a caller's camera rays run along a row
    // or a tile); the pool's chunks are multiples of every width.
    RunRayThreads(rays.size(), options.threads, options.progress, [&](const NextChunk& next_chunk) {
      fp::ScopedFtzDaz ftz;
      PacketCounts alone;
      size_t begin, end;
      while (next_chunk(&begin, &end)) {
        for (size_t i = begin; i < end; i += plan.width) {
          const int n = static_cast<int>(std::min<size_t>(plan.width, end - i));
          TracePacket(plan, image, &rays[i], n, options, &hits[i], &counters[i], &alone);
        }
      }
      const std::lock_guard<std::mutex> lock(counts_mutex);
      packet_counts += alone;
    });
  } else {
    RunRayThreads(rays.size(), options.threads, options.progress, [&](const NextChunk& next_chunk) {
      WithTraceArith(options, [&](const auto& at, const auto& ai, auto mixed) {
        size_t begin, end;
        while (next_chunk(&begin, &end)) {
          for (size_t i = begin; i < end; ++i) {
            hits[i] = ToHit(ai, TraceRayIn<decltype(mixed)::value>(at, ai, image, rays[i], options.isect,
                                                                   options.query, &counters[i], nullptr,
                                                                   StackLimit(options)));
          }
        }
        return 0;
      });
    });
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (stats) {
    *stats = TraceStats{};
    stats->rays = rays.size();
    stats->seconds = seconds;
    stats->packets = plan;
    stats->packet_counts = packet_counts;
    for (size_t i = 0; i < rays.size(); ++i) {
      stats->totals += counters[i];
      if (hits[i].IsHit()) ++stats->hits;
    }
  }
  if (per_ray) *per_ray = std::move(counters);
  return hits;
}

}  // namespace kdrt
