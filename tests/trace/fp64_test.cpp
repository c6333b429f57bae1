// The double-precision truth (`--format fp64`, NativeF64Arith): the same
// traversal and test as every format, in native double. It must agree with
// fp32 where fp32 is accurate, be watertight (watertight_test.cpp) and give
// the same bits on every run and thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "fp/ftz.h"
#include "trace_test_util.h"

namespace kdrt {
namespace {

using testing::CameraRays;
using testing::Prepared;

// Distance in fp32 encodings between two positive finite floats.
int64_t UlpDistance(float a, float b) {
  return std::llabs(static_cast<int64_t>(fp::BitsOf(a)) - static_cast<int64_t>(fp::BitsOf(b)));
}

// Where the ray meets the triangle's plane, in long double.
long double PlaneT(const img::TriangleRecord& t, const Ray& r) {
  long double u[3], v[3], w[3], n[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = static_cast<long double>(t.v1[i]) - t.v0[i];
    v[i] = static_cast<long double>(t.v2[i]) - t.v0[i];
    w[i] = static_cast<long double>(t.v0[i]) - r.o[i];
  }
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  return (n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) / (n[0] * r.d[0] + n[1] * r.d[1] + n[2] * r.d[2]);
}

std::vector<Hit> Trace(const ImageView& image, const std::vector<Ray>& rays, fp::Format f, int threads) {
  TraceOptions o;
  o.format = f;
  o.threads = threads;
  return TraceRays(image, rays, o);
}

TEST(Fp64, PolicyBasics) {
  fp::ScopedIeeeDefault ieee;
  const fp::NativeF64Arith a;
  EXPECT_EQ(a.Load(0.1f), static_cast<double>(0.1f));
  const float sub = 1e-40f;  // subnormal fp32: exact, not flushed
  EXPECT_EQ(a.Load(sub), static_cast<double>(sub));
  EXPECT_NE(a.Load(sub), 0.0);
  EXPECT_EQ(a.Store(1.0 + 1e-12), 1.0f);  // rounded once to the fp32 record
  EXPECT_EQ(a.NudgeUp(1.0, 4), 1.0 + 4 * 0x1p-52);
  EXPECT_EQ(a.NudgeDown(1.0, 4), 1.0 - 4 * 0x1p-53);
  EXPECT_EQ(a.NudgeDown(0x1p-1022, 1), 0.0);  // leaves the normal range
  EXPECT_EQ(a.NudgeUp(1.7976931348623157e308, 4), a.Inf());
  EXPECT_EQ(a.NudgeUp(-1.0, 4), -1.0);
  EXPECT_EQ(a.NudgeUp(a.Inf(), 4), a.Inf());
  EXPECT_TRUE(std::signbit(a.Min(-0.0, 0.0)));
  EXPECT_FALSE(std::signbit(a.Max(-0.0, 0.0)));
  EXPECT_TRUE(std::isnan(a.Min(std::nan(""), 1.0)));
}

// On the generators, fp64 and fp32 agree on hit or miss and on the triangle
// for almost every ray, and on t within a few fp32 ulps. They may differ only
// where fp32's rounding decides: a ray through an edge or vertex shared by
// two triangles (a tie at the same t, so t still agrees), or a grazing ray
// whose fp32 t and u, v carry more rounding (a few in 10,000 rays).
TEST(Fp64, AgreesWithFp32OnTheGenerators) {
  for (const char* name : {"room", "balls", "rings", "tetra", "tree"}) {
    Prepared p(GenerateScene(name, 3000));
    const std::vector<Ray> rays = CameraRays(p.scene, 96);
    const std::vector<Hit> h32 = Trace(p.view(), rays, fp::kFp32, 2);
    const std::vector<Hit> h64 = Trace(p.view(), rays, fp::kFp64, 2);
    size_t hit_miss = 0, other_prim = 0, hits = 0, beyond_4_ulps = 0;
    int64_t max_ulps = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      if (h32[i].IsHit() != h64[i].IsHit()) {
        ++hit_miss;
        continue;
      }
      if (!h32[i].IsHit()) continue;
      ++hits;
      EXPECT_NEAR(h32[i].t, h64[i].t, 1e-5 * h64[i].t) << name << " ray " << i;
      if (h32[i].prim != h64[i].prim) {
        ++other_prim;
        continue;
      }
      const int64_t ulps = UlpDistance(h32[i].t, h64[i].t);
      max_ulps = std::max(max_ulps, ulps);
      if (ulps > 4) {
        // fp64 is the closer one: against the plane of the triangle in long double.
        ++beyond_4_ulps;
        // In the image's frame, where both traced the same (framed) ray.
        const FramedRay framed = ToFrame(rays[i], p.view().frame());
        const long double exact =
            std::ldexp(PlaneT(p.view().triangle(h64[i].prim), framed.ray), framed.t_scale_log2);
        EXPECT_LT(std::fabs(h64[i].t - exact), std::fabs(h32[i].t - exact)) << name << " ray " << i;
      }
      EXPECT_NEAR(h32[i].u, h64[i].u, 1e-3) << name << " ray " << i;
      EXPECT_NEAR(h32[i].v, h64[i].v, 1e-3) << name << " ray " << i;
    }
    EXPECT_GT(hits, rays.size() / 10) << name;
    EXPECT_LE(hit_miss, rays.size() / 2000) << name;    // at most 4 of 9,216
    EXPECT_LE(other_prim, rays.size() / 500) << name;   // at most 18
    EXPECT_LE(beyond_4_ulps, rays.size() / 500) << name;  // grazing rays
    EXPECT_LE(max_ulps, 64) << name;
    std::printf("%-6s %zu hits; differ: %zu hit/miss, %zu triangle; t: max %lld fp32 ulps, %zu rays beyond 4\n", name,
                hits, hit_miss, other_prim, static_cast<long long>(max_ulps), beyond_4_ulps);
  }
}

TEST(Fp64, DeterministicAcrossRunsAndThreads) {
  Prepared p(GenerateScene("tree", 3000));
  const std::vector<Ray> rays = CameraRays(p.scene, 64);
  const std::vector<Hit> a = Trace(p.view(), rays, fp::kFp64, 1);
  const std::vector<Hit> b = Trace(p.view(), rays, fp::kFp64, 2);
  const std::vector<Hit> c = Trace(p.view(), rays, fp::kFp64, 2);
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(std::memcmp(&a[i], &b[i], sizeof(Hit)), 0) << i;
    EXPECT_EQ(std::memcmp(&b[i], &c[i], sizeof(Hit)), 0) << i;
  }
  // TraceOne is the same path.
  for (size_t i = 0; i < rays.size(); i += 97) {
    TraceOptions o;
    o.format = fp::kFp64;
    const Hit one = TraceOne(p.view(), rays[i], o);
    EXPECT_EQ(std::memcmp(&one, &a[i], sizeof(Hit)), 0) << i;
  }
}

// The caller's FTZ/DAZ does not leak into the reference: the tracer sets
// IEEE defaults for fp64 itself.
TEST(Fp64, IndependentOfTheCallersFtzDaz) {
  Prepared p(GenerateScene("balls", 1000));
  const std::vector<Ray> rays = CameraRays(p.scene, 32);
  const std::vector<Hit> plain = Trace(p.view(), rays, fp::kFp64, 1);
  fp::ScopedFtzDaz ftz;
  const std::vector<Hit> under_ftz = Trace(p.view(), rays, fp::kFp64, 1);
  for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(std::memcmp(&plain[i], &under_ftz[i], sizeof(Hit)), 0) << i;
}

}  // namespace
}  // namespace kdrt
