// The precision requirement derived from the scene (trace/precision.h,
// docs/precision.md): its building blocks, its monotonicity, and that it
// tells the formats that fail on the extremes from those that work.
#include <gtest/gtest.h>

#include <cfloat>

#include "trace/precision.h"
#include "trace/watertight.h"
#include "trace_test_util.h"

namespace kdrt {
namespace {

using testing::CameraRays;
using testing::MovedSphere;
using testing::Prepared;

size_t CountMisses(const ImageView& image, const std::vector<Ray>& rays, fp::Format f) {
  TraceOptions o;
  o.format = f;
  o.threads = 2;
  size_t misses = 0;
  for (const Hit& h : TraceRays(image, rays, o)) misses += !h.IsHit();
  return misses;
}

const PrecisionCriterion& Criterion(const PrecisionRequirement& req, const std::string& name) {
  for (const PrecisionCriterion& c : req.criteria) {
    if (c.name == name) return c;
  }
  throw std::runtime_error("no criterion " + name);
}

TEST(Precision, RoundMantissa) {
  EXPECT_EQ(RoundMantissa(1.0f + 0x1p-23f, 23), 1.0f + 0x1p-23f);
  EXPECT_EQ(RoundMantissa(1.0f + 0x1p-23f, 22), 1.0f);                  // tie to even (down)
  EXPECT_EQ(RoundMantissa(1.0f + 3 * 0x1p-23f, 22), 1.0f + 0x1p-21f);  // tie to even (up)
  EXPECT_EQ(RoundMantissa(1.3f, 1), 1.5f);
  EXPECT_EQ(RoundMantissa(-1.3f, 1), -1.5f);
  EXPECT_EQ(RoundMantissa(1.9f, 1), 2.0f);  // carry into the exponent
  EXPECT_EQ(RoundMantissa(0x1.ep100f, 1), 0x1p101f);
  EXPECT_EQ(RoundMantissa(0.0f, 4), 0.0f);
  EXPECT_EQ(RoundMantissa(INFINITY, 4), INFINITY);
}

TEST(Precision, CollinearIsExact) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 2, 3}, c[3] = {2, 4, 6};
  EXPECT_TRUE(Collinear(a, b, c));
  EXPECT_TRUE(Collinear(a, a, c));  // coincident vertices
  const double d[3] = {2, 4, 6 + 0x1p-50};
  EXPECT_FALSE(Collinear(a, b, d));
  // a*d and b*c round to the same double but differ by 2^-60: not collinear.
  const double a_ = 1 + 0x1p-30, b_ = 1 + 0x1p-29;
  const double o[3] = {0, 0, 0}, q[3] = {a_, b_, 0}, r[3] = {1, a_, 0};
  ASSERT_EQ(a_ * a_, b_ * 1.0);  // the naive cross product says 0
  EXPECT_FALSE(Collinear(o, q, r));
}

// Every count shrinks as bits are added, and the minimum is where all counts
// reach zero: a format with at least the minimal bits gets no shortfall, one
// with fewer exponent or mantissa bits does.
void ExpectMonotone(const PrecisionRequirement& req) {
  for (const PrecisionCriterion& c : req.criteria) {
    for (int b = 1; b < 24; ++b) EXPECT_LE(c.Failing(b), c.Failing(b - 1)) << c.name;
    EXPECT_EQ(c.Failing(c.MinBits()), 0u) << c.name;
    if (c.MinBits() > 0) {
      EXPECT_GT(c.Failing(c.MinBits() - 1), 0u) << c.name;
    }
  }
  for (int e = 2; e <= 8; ++e) {
    for (int m = 1; m <= 23; ++m) {
      const bool meets = e >= req.min_exponent_bits && m >= req.min_mantissa_bits;
      EXPECT_EQ(req.Shortfall(fp::Format{e, m}).empty(), meets) << "e" << e << "m" << m;
    }
  }
  EXPECT_EQ(req.Shortfall(fp::kFp64), "");
}

TEST(Precision, UnitSphereNeedsFewBitsAndFp16Works) {
  const testing::MeshAndRays m = MovedSphere(0, 1);
  Prepared p(m.scene);
  const PrecisionRequirement req = AnalyzePrecision(p.view(), m.rays, 2);
  std::printf("unit sphere: %s\n", req.MinimalFormat().c_str());
  EXPECT_LE(req.min_exponent_bits, 5);
  EXPECT_LE(req.min_mantissa_bits, 7);
  EXPECT_EQ(req.rays, m.rays.size());
  EXPECT_EQ(req.hit_tests, m.rays.size());
  for (const fp::Format& f : fp::Presets()) {
    EXPECT_EQ(req.Shortfall(f), "") << f.Name();
    EXPECT_EQ(CountMisses(p.view(), m.rays, f), 0u) << f.Name();
  }
  ExpectMonotone(req);
}

// The unit sphere beside a triangle 1e5 away: in the image's frame the
// sphere is ~3e-4 of the reach, below fp16's, bf16's and fp24's rounding
// step there, so its vertices collapse (most rays miss); fp32 holds it.
TEST(Precision, SphereInAStadiumNeedsMoreThanFp16AndBf16) {
  const testing::MeshAndRays m = testing::SphereInStadium(1e5);
  Prepared p(m.scene);
  const PrecisionRequirement req = AnalyzePrecision(p.view(), m.rays, 2);
  std::printf("sphere in a stadium of 1e5: %s\n", req.MinimalFormat().c_str());
  EXPECT_GT(req.min_mantissa_bits, fp::kFp24.m);
  EXPECT_EQ(req.Shortfall(fp::kFp32), "");
  const std::string fp16 = req.Shortfall(fp::kFp16);
  EXPECT_EQ(fp16.rfind("fp16 cannot represent this scene: ", 0), 0u) << fp16;
  EXPECT_NE(fp16.find("vertices collapse onto another vertex"), std::string::npos) << fp16;
  EXPECT_NE(req.Shortfall(fp::kBf16).find("vertices collapse"), std::string::npos);
  // What the requirement says is what the tracer does.
  EXPECT_GT(CountMisses(p.view(), m.rays, fp::kFp16), m.rays.size() / 2);
  EXPECT_EQ(CountMisses(p.view(), m.rays, fp::kFp32), 0u);
  ExpectMonotone(req);
}

// A datapath reading a narrower image (--image-format): the storage criteria
// (what happens to stored vertices and splits) are checked against the
// image's format, the rest against the datapath's. fp32 arithmetic cannot
// give back vertices that collapsed in a bf16 image, and the tracer shows
// it; an fp16 image of the unit sphere is enough for fp32 arithmetic.
TEST(Precision, ANarrowerImageIsCheckedByItsStorageCriteria) {
  std::vector<std::string> storage;
  const testing::MeshAndRays stadium = testing::SphereInStadium(1e5);
  Prepared p(stadium.scene);
  const PrecisionRequirement req = AnalyzePrecision(p.view(), stadium.rays, 2);
  for (const PrecisionCriterion& c : req.criteria) {
    if (c.storage) storage.push_back(c.name);
  }
  EXPECT_EQ(storage, (std::vector<std::string>{"coordinate_overflow", "coordinate_flush", "vertex_collapse",
                                               "degenerate_triangles", "split_order"}));
  EXPECT_GT(req.min_image_mantissa_bits, fp::kBf16.m);
  EXPECT_LE(req.min_image_mantissa_bits, req.min_mantissa_bits);
  EXPECT_EQ(req.Shortfall(fp::kFp32, fp::kFp32), "");
  const std::string bf16 = req.Shortfall(fp::kFp32, fp::kBf16);
  EXPECT_EQ(bf16.rfind("fp32 with its image in bf16 cannot represent this scene: ", 0), 0u) << bf16;
  EXPECT_NE(bf16.find("vertices collapse onto another vertex"), std::string::npos) << bf16;
  EXPECT_NE(bf16.find("minimal image format e"), std::string::npos) << bf16;
  const std::vector<uint8_t> packed = RepackImage(p.view(), LayoutFor(fp::kBf16));
  EXPECT_GT(CountMisses(ImageView(packed), stadium.rays, fp::kFp32), stadium.rays.size() / 2);

  const testing::MeshAndRays sphere = MovedSphere(0, 1);
  Prepared q(sphere.scene);
  const PrecisionRequirement unit = AnalyzePrecision(q.view(), sphere.rays, 2);
  EXPECT_EQ(unit.Shortfall(fp::kFp32, fp::kFp16), "");
  const std::vector<uint8_t> fp16 = RepackImage(q.view(), LayoutFor(fp::kFp16));
  EXPECT_EQ(CountMisses(ImageView(fp16), sphere.rays, fp::kFp32), 0u);
}

// Offsets and scales that broke the world-space datapath (1e5 away: fp16,
// bf16 and fp24 missed; scaled by 1e-15 or 1e15: the watertight test's
// products under- or overflowed) are harmless in the image's frame: every
// preset meets the requirement and misses nothing.
TEST(Precision, OffsetAndScaleAreHarmlessInTheFrame) {
  for (const auto& [offset, scale] : {std::pair{1e5, 1.0}, std::pair{0.0, 1e-15}, std::pair{0.0, 1e15}}) {
    const testing::MeshAndRays m = MovedSphere(offset, scale);
    Prepared p(m.scene);
    const PrecisionRequirement req = AnalyzePrecision(p.view(), m.rays, 2);
    std::printf("sphere offset %g scale %g: %s\n", offset, scale, req.MinimalFormat().c_str());
    for (const fp::Format& f : fp::Presets()) {
      EXPECT_EQ(req.Shortfall(f), "") << f.Name() << " offset " << offset << " scale " << scale;
      EXPECT_EQ(CountMisses(p.view(), m.rays, f), 0u) << f.Name() << " offset " << offset << " scale " << scale;
    }
    ExpectMonotone(req);
  }
  // Camera rays (unit directions, t ~ 1e15) on the huge sphere: no infinite t.
  const testing::MeshAndRays huge = MovedSphere(0, 1e15);
  Prepared p(huge.scene);
  const std::vector<Ray> rays = CameraRays(p.scene, 32);
  EXPECT_EQ(AnalyzePrecision(p.view(), rays, 2).Shortfall(fp::kFp32), "");
  TraceOptions o;
  o.threads = 2;
  size_t hits = 0;
  for (const Hit& h : TraceRays(p.view(), rays, o)) {
    hits += h.IsHit();
    EXPECT_TRUE(!h.IsHit() || std::isfinite(h.t));
  }
  EXPECT_GT(hits, 0u);
}

// No warning for fp32 on the generators, and the requirement is monotone.
TEST(Precision, Fp32RepresentsTheGenerators) {
  for (const char* name : {"room", "balls", "rings", "tetra", "tree"}) {
    Prepared p(GenerateScene(name, 10000));
    const PrecisionRequirement req = AnalyzePrecision(p.view(), CameraRays(p.scene, 64), 2);
    std::printf("%-6s minimal format %s\n", name, req.MinimalFormat().c_str());
    EXPECT_EQ(req.Shortfall(fp::kFp32), "") << name;
    EXPECT_GT(req.hit_tests, 0u) << name;
    ExpectMonotone(req);
  }
}

// A finely tessellated closed sphere seen from 100 radii: relative to the
// ray origin (magnitude ~100 radii) a 6-bit significand keeps none of a
// triangle's extent (~0.08 radii), so the test sees degenerate triangles and
// rays fall through the mesh. hit_degenerate says so; fp32 keeps them all.
TEST(Precision, FarRaysOnSmallTrianglesNeedMantissaBits) {
  Scene s = ClosedSphereMesh(40, 80);
  std::vector<Ray> rays;
  for (size_t i = 0; i < s.triangles.size(); i += 7) {
    const glm::vec3 target = s.triangles[i].v0;
    const glm::vec3 o = 100.0f * target;
    rays.push_back(Ray{o, target - o, 0.0f, INFINITY});
  }
  Prepared p(s);
  const PrecisionRequirement req = AnalyzePrecision(p.view(), rays, 2);
  std::printf("sphere from 100 radii: %s\n", req.MinimalFormat().c_str());
  const PrecisionCriterion& c = Criterion(req, "hit_degenerate");
  EXPECT_EQ(c.checked, rays.size());
  EXPECT_EQ(c.Failing(fp::kFp32.m), 0u);
  const fp::Format e6m5{6, 5};
  EXPECT_GT(c.Failing(e6m5.m), rays.size() / 10);
  EXPECT_NE(req.Shortfall(e6m5).find("lose their area relative to the ray origin"), std::string::npos)
      << req.Shortfall(e6m5);
  EXPECT_GT(CountMisses(p.view(), rays, e6m5), 0u);
  EXPECT_EQ(CountMisses(p.view(), rays, fp::kFp32), 0u);
  ExpectMonotone(req);
}

// Without rays only the image criteria run.
TEST(Precision, ImageAloneWithoutRays) {
  Prepared p(GenerateScene("balls", 500));
  const PrecisionRequirement req = AnalyzePrecision(p.view(), {}, 1);
  EXPECT_EQ(req.rays, 0u);
  for (const PrecisionCriterion& c : req.criteria) EXPECT_EQ(c.name.rfind("ray", 0) == 0, false) << c.name;
  EXPECT_EQ(req.Json()["criteria"].count("hit_overflow"), 0u);
  EXPECT_EQ(req.Json()["min_exponent_bits"], req.min_exponent_bits);
}

// Two vertices one fp32 ulp apart (in world units) need nearly every bit:
// in the frame they are 2^-19 apart at magnitude 8, so they collapse below
// 22 mantissa bits; a split plane never leaves its cell (rounding is
// monotone).
TEST(Precision, NearlyCoincidentVerticesNeedAllBits) {
  Scene s;
  const float x = 1.0f, x_next = std::nextafter(1.0f, 2.0f);
  s.triangles.push_back({{0, 0, 0}, {x, 0, 0}, {0, 1, 0}});
  s.triangles.push_back({{0, 0, 1}, {x_next, 0, 1}, {0, 1, 1}});
  s.triangles.push_back({{0, 0, 0}, {x_next, 0, 0}, {0, 1, 0}});
  s.material.assign(3, 0);
  s.colors.push_back({1, 1, 1});
  Prepared p(s);
  const PrecisionRequirement req = AnalyzePrecision(p.view(), {}, 1);
  EXPECT_EQ(req.min_mantissa_bits, 22);
  EXPECT_EQ(Criterion(req, "vertex_collapse").Failing(21), 2u);  // (1,0,0) and (x_next,0,0)
  EXPECT_EQ(Criterion(req, "split_order").Failing(0), 0u);
  EXPECT_NE(req.Shortfall(fp::kFp24).find("2 of 7 vertices collapse"), std::string::npos)
      << req.Shortfall(fp::kFp24);
}

}  // namespace
}  // namespace kdrt
