// The criteria behind AnalyzePrecision (trace/precision.h), one function per
// family; docs/precision.md defines each. Internal to sw/trace.
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "common/ray.h"
#include "trace/memory_image.h"
#include "trace/precision.h"

namespace kdrt::precision {

// The largest mantissa width checked: every fp32 value of the image is exact
// with 23 bits, so nothing can need more.
inline constexpr int kMaxMantissaBits = 23;

// vertex_collapse, degenerate_triangles, split_order.
void AddMantissaCriteria(const ImageView& image, int threads, std::vector<PrecisionCriterion>* out);

// hit_degenerate; `hits` are the rays' fp64 hits; `threads` as ParallelFor's.
void AddRayMantissaCriteria(const ImageView& image, const std::vector<Ray>& rays, const std::vector<Hit>& hits,
                            int threads, std::vector<PrecisionCriterion>* out);

// coordinate_overflow, triangle_underflow, triangle_overflow.
void AddImageExponentCriteria(const ImageView& image, std::vector<PrecisionCriterion>* out);

// ray_overflow, ray_underflow, hit_overflow, hit_underflow; `hits` are the
// rays' fp64 hits.
void AddRayExponentCriteria(const ImageView& image, const std::vector<Ray>& rays, const std::vector<Hit>& hits,
                            std::vector<PrecisionCriterion>* out);

// Runs fn(i) for i in [0, n) on up to `threads` threads (0: all cores); fn
// must only write state of its own i.
template <class Fn>
void ParallelFor(size_t n, int threads, Fn fn) {
  int t = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  t = std::max(1, std::min<int>(t, static_cast<int>(n / 4096 + 1)));
  constexpr size_t kChunk = 1024;
  std::atomic<size_t> next{0};
  auto worker = [&]() {
    for (;;) {
      const size_t begin = next.fetch_add(kChunk);
      if (begin >= n) return;
      for (size_t i = begin, end = std::min(n, begin + kChunk); i < end; ++i) fn(i);
    }
  };
  std::vector<std::thread> pool;
  for (int k = 1; k < t; ++k) pool.emplace_back(worker);
  worker();
  for (std::thread& th : pool) th.join();
}

}  // namespace kdrt::precision
