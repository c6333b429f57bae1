// Tracing in reduced-precision formats differs from fp32 only in ways that
// rounding explains: where both hit the same triangle, t agrees to a few
// units of the format's precision; where the triangle (or hit/miss) changes,
// one of the two hits lies within rounding distance of its triangle's edge
// (the loaded ray moved by a few ulps of its coordinates: a silhouette or a
// shared edge). Prints the counts per preset (the figures in the README).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "trace_test_util.h"

namespace kdrt {
namespace {

// Distance from p to the nearest edge of triangle t (p assumed in its plane).
double DistanceToEdges(const Triangle& t, const glm::dvec3& p) {
  const glm::dvec3 v[3] = {t.v0, t.v1, t.v2};
  double best = INFINITY;
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3 a = v[i], b = v[(i + 1) % 3];
    const glm::dvec3 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double s = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, glm::length(p - (a + s * ab)));
  }
  return best;
}

struct FormatCase {
  const char* generator;
  const char* format;
};

class FormatDifferences : public ::testing::TestWithParam<FormatCase> {};

TEST_P(FormatDifferences, AreExplainedByRounding) {
  const FormatCase& fc = GetParam();
  testing::Prepared p(GenerateScene(fc.generator, 3000));
  const ImageView image = p.view();
  const std::vector<Ray> rays = testing::CameraRays(p.scene, 96);
  TraceOptions ref_options, options;
  options.format = fp::ParseFormat(fc.format);
  const std::vector<Hit> ref = TraceRays(image, rays, ref_options);
  const std::vector<Hit> got = TraceRays(image, rays, options);
  const double eps = std::ldexp(1.0, -options.format.m);  // one ulp at 1

  // A hit is "at an edge" if it lies within rounding distance of one: the
  // loaded ray is off by ~eps of its coordinates, scaled by the hit distance.
  auto at_edge = [&](const Ray& r, const Hit& h) {
    if (!h.IsHit()) return false;
    const glm::dvec3 o = r.o, d = glm::dvec3(r.d);
    const glm::dvec3 point = o + static_cast<double>(h.t) * d;
    const double scale = std::max(glm::length(o), glm::length(point)) + glm::length(point - o);
    return DistanceToEdges(p.scene.triangles[h.prim], point) <= 64 * eps * scale;
  };
  size_t same = 0, same_close = 0, changed = 0, explained = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    if (got[i].IsHit() == ref[i].IsHit() && got[i].prim == ref[i].prim) {
      if (!ref[i].IsHit()) continue;
      ++same;
      same_close += std::fabs(got[i].t - ref[i].t) <= 16 * eps * ref[i].t;
      continue;
    }
    ++changed;
    const bool close_t = got[i].IsHit() && ref[i].IsHit() && std::fabs(got[i].t - ref[i].t) <= 64 * eps * ref[i].t;
    if (close_t || at_edge(rays[i], ref[i]) || at_edge(rays[i], got[i])) ++explained;
  }
  std::printf("[ formats  ] %s %s: %zu of %zu pixels changed triangle or hit/miss (%zu explained); "
              "%zu of %zu same-triangle hits within 16 ulps in t\n",
              fc.generator, fc.format, changed, rays.size(), explained, same_close, same);
  EXPECT_EQ(explained, changed);
  EXPECT_GE(same_close, same - same / 1000);
}

INSTANTIATE_TEST_SUITE_P(
    Presets, FormatDifferences,
    ::testing::Values(FormatCase{"room", "fp24"}, FormatCase{"room", "bf16"}, FormatCase{"room", "fp16"},
                      FormatCase{"balls", "fp24"}, FormatCase{"balls", "bf16"}, FormatCase{"balls", "fp16"},
                      FormatCase{"tetra", "fp16"}, FormatCase{"rings", "fp16"}, FormatCase{"tree", "fp16"},
                      FormatCase{"tree", "bf16"}),
    [](const auto& info) { return std::string(info.param.generator) + "_" + info.param.format; });

}  // namespace
}  // namespace kdrt
