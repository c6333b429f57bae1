// The four-wide fp32 leaf test (trace/leaf_x4.h) against the scalar
// watertight test it replaces in the fp32 traversal: the same hit decision
// and the same bits of t, u and v for every lane, on triangles and rays made
// to sit on the edge cases (rays through vertices and edges, degenerate and
// subnormal triangles, coordinates that overflow, zero direction
// components), and whole traces with large leaves against the soft-float
// fp32 model, which has no four-wide path.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "fp/ftz.h"
#include "trace/leaf_x4.h"
#include "trace_test_util.h"

namespace kdrt {
namespace {

#if KDRT_HAVE_LEAF_X4

img::TriangleRecord Record(const float v[9], uint32_t id) {
  img::TriangleRecord t{};
  std::memcpy(t.v0, v, 3 * sizeof(float));
  std::memcpy(t.v1, v + 3, 3 * sizeof(float));
  std::memcpy(t.v2, v + 6, 3 * sizeof(float));
  t.id = id;
  return t;
}

// A coordinate from a small set of values that reach the corner cases, or
// a random one.
float Coordinate(std::mt19937& rng) {
  static const float kSpecial[] = {0.0f,     -0.0f,   1.0f,     -1.0f,   0.5f,     1e-40f, -1e-40f,
                                   1e38f,    -1e38f,  3e38f,    1e-20f,  2.0f,     0.25f,  -0.5f};
  std::uniform_int_distribution<int> pick(0, 3);
  if (pick(rng) == 0) {
    std::uniform_int_distribution<size_t> k(0, sizeof kSpecial / sizeof kSpecial[0] - 1);
    return kSpecial[k(rng)];
  }
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  return u(rng);
}

TEST(LeafX4, EveryLaneIsTheScalarTestBitForBit) {
  fp::ScopedFtzDaz ftz;
  const fp::NativeF32Arith a;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  uint64_t hits = 0, tests = 0;
  for (int round = 0; round < 20000; ++round) {
    // Four triangles; some share vertices, some are degenerate.
    std::vector<img::TriangleRecord> tris;
    float v[9];
    for (int k = 0; k < 4; ++k) {
      for (float& c : v) c = Coordinate(rng);
      if (k > 0 && round % 3 == 0) std::memcpy(v, tris.back().v1, 6 * sizeof(float));  // a shared edge
      if (round % 11 == 0) std::memcpy(v + 6, v + 3, 3 * sizeof(float));                // a degenerate one
      tris.push_back(Record(v, static_cast<uint32_t>(k)));
    }
    // A ray at a vertex, an edge midpoint or anywhere, from a random origin;
    // sometimes with zero direction components.
    Ray ray;
    ray.o = {unit(rng) * 3, unit(rng) * 3, unit(rng) * 3};
    const img::TriangleRecord& aim = tris[static_cast<size_t>(round) % 4];
    glm::vec3 target;
    switch (round % 3) {
      case 0: target = {aim.v0[0], aim.v0[1], aim.v0[2]}; break;
      case 1:
        target = {(aim.v0[0] + aim.v1[0]) * 0.5f, (aim.v0[1] + aim.v1[1]) * 0.5f, (aim.v0[2] + aim.v1[2]) * 0.5f};
        break;
      default: target = {unit(rng), unit(rng), unit(rng)};
    }
    ray.d = target - ray.o;
    if (round % 7 == 0) ray.d[round % 3] = (round % 2) ? 0.0f : -0.0f;
    ray.tmin = round % 5 == 0 ? 0.5f : 0.0f;
    ray.tmax = round % 13 == 0 ? 1.0f : INFINITY;
    const RaySetup<fp::NativeF32Arith> r = SetupRay(a, ray);
    const float tmax = round % 17 == 0 ? 0.75f : r.tmax;
    const uint32_t ids[4] = {0, 1, 2, 3};
    for (uint32_t n = 1; n <= 4; ++n) {
      float t[4], u[4], w[4];
      const unsigned mask = IntersectWatertightX4(r, tris.data(), ids, n, tmax, t, u, w);
      EXPECT_EQ(mask >> n, 0u) << "a lane past n hit";
      for (uint32_t k = 0; k < n; ++k) {
        const Candidate<fp::NativeF32Arith> c = IntersectWatertight(a, r, tris[k], tmax);
        ++tests;
        ASSERT_EQ(c.hit, ((mask >> k) & 1u) != 0) << "round " << round << " lane " << k << " of " << n;
        if (!c.hit) continue;
        ++hits;
        ASSERT_EQ(fp::BitsOf(c.t), fp::BitsOf(t[k])) << "round " << round << " lane " << k;
        ASSERT_EQ(fp::BitsOf(c.u), fp::BitsOf(u[k])) << "round " << round << " lane " << k;
        ASSERT_EQ(fp::BitsOf(c.v), fp::BitsOf(w[k])) << "round " << round << " lane " << k;
      }
    }
  }
  // The cases are not all misses: the aimed rays hit.
  EXPECT_GT(hits, tests / 20);
}

// Whole traces through large leaves (strips, gears: tens of triangles a
// leaf, groups of 1 to 4) on the native path, against the soft-float fp32
// model, which tests one triangle at a time: the same hits, paths and test
// counts. The trees are built without the automatic clipping, which keeps
// their leaves large.
TEST(LeafX4, TracesWithLargeLeavesMatchTheSoftFloatModel) {
  BuildOptions boxes;
  boxes.auto_clip = false;
  for (const char* name : {"strips", "gears", "tree"}) {
    testing::Prepared p(GenerateScene(name, 3000), boxes);
    const ImageView image = p.view();
    const std::vector<Ray> rays = testing::CameraRays(p.scene, 48);
    const fp::SoftArith soft(fp::kFp32);
    fp::ScopedFtzDaz ftz;
    const fp::NativeF32Arith native;
    uint64_t tests = 0;
    for (const Ray& ray : rays) {
      RayCounters cs, cn;
      const Hit hs = ToHit(soft, TraceRay(soft, image, ray, IsectMethod::kWatertight, Query::kClosest, &cs));
      const Hit hn = ToHit(native, TraceRay(native, image, ray, IsectMethod::kWatertight, Query::kClosest, &cn));
      ASSERT_TRUE(testing::SameBits(hs, hn)) << name << ": prim " << hs.prim << " vs " << hn.prim;
      ASSERT_EQ(cs.tri_tests, cn.tri_tests) << name;
      tests += cn.tri_tests;
    }
    EXPECT_GT(tests, 4 * rays.size()) << name << ": the leaves are large";
  }
}

#endif

}  // namespace
}  // namespace kdrt
