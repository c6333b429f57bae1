// Helpers the structure tests share: hand-made scenes, rays that start and
// end inside the scene, and the brute-force answer every structure must give.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "fp/ftz.h"
#include "tests/trace/trace_test_util.h"

namespace kdrt::testing {

// A scene of the given triangles, one white material.
inline Scene FromTriangles(std::vector<Triangle> triangles) {
  Scene s;
  s.triangles = std::move(triangles);
  s.material.assign(s.triangles.size(), 0);
  s.colors = {glm::vec3(1.0f)};
  s.finishes = {Finish{}};
  return s;
}

// Random rays from points inside the box of the scene's vertices, with tmax
// from 0 to about the box's diagonal: they start inside cells and end inside
// cells.
inline std::vector<Ray> InsideRays(const Scene& scene, size_t n, uint32_t seed) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const Triangle& t : scene.triangles) {
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
  }
  const float diag = glm::length(hi - lo);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::normal_distribution<float> gauss;
  std::vector<Ray> rays(n);
  for (Ray& r : rays) {
    r.o = lo + (hi - lo) * glm::vec3(u01(rng), u01(rng), u01(rng));
    r.d = glm::vec3(gauss(rng), gauss(rng), gauss(rng));
    r.tmin = 0.0f;
    r.tmax = u01(rng) * diag / std::max(glm::length(r.d), 1e-6f);
  }
  return rays;
}

// Every triangle tested (fp32 or fp64): the exact (t, id) minimum.
inline std::vector<Hit> BruteForceHits(const ImageView& image, const std::vector<Ray>& rays,
                                       const fp::Format& format) {
  std::vector<Hit> hits;
  hits.reserve(rays.size());
  if (format.IsFp64()) {
    fp::ScopedIeeeDefault ieee;
    for (const Ray& r : rays) hits.push_back(BruteForce(fp::NativeF64Arith{}, image, r));
  } else {
    fp::ScopedFtzDaz ftz;
    for (const Ray& r : rays) hits.push_back(BruteForce(fp::NativeF32Arith{}, image, r));
  }
  return hits;
}
inline std::vector<Hit> BruteForceHits(const ImageView& image, const std::vector<Ray>& rays, const char* format) {
  return BruteForceHits(image, rays, fp::ParseFormat(format));
}

}  // namespace kdrt::testing
