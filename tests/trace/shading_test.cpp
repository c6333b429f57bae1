// Any-hit queries, the secondary ray sets and shading from hit records
// (trace/shading.h, docs/shading.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>

#include <glm/geometric.hpp>

#include "scene/scene_builder.h"
#include "tests/trace/trace_test_util.h"
#include "trace/rays_file.h"
#include "trace/shading.h"

namespace kdrt {
namespace {

using testing::CameraRays;
using testing::Prepared;

// Any-hit answers the same yes/no as closest hit, with a hit inside
// [tmin, tmax] that is no closer than the closest, and never more work.
// Rays from points inside the scene box in every direction (a fixed LCG), so
// long triangles are met in a leaf before the leaf of the closest hit.
std::vector<Ray> RaysInsideTheBox(const Scene& scene, int count) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const Triangle& t : scene.triangles) {
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
  }
  uint32_t state = 12345;
  const auto next = [&]() {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) * 0x1.0p-24f;
  };
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 o = lo + (hi - lo) * glm::vec3(next(), next(), next());
    const glm::vec3 d(next() - 0.5f, next() - 0.5f, next() - 0.5f);
    rays.push_back(Ray{o, d, 0.0f, INFINITY});
  }
  return rays;
}

// On gears' tree without the automatic clipping: its large leaves of
// overlapping slivers are where an any-hit query stops on a triangle that
// is not the closest (with the clipping's small leaves some formats find
// the closest on all 2000 rays).
TEST(AnyHit, AgreesWithClosestHitOnOcclusion) {
  BuildOptions boxes;
  boxes.auto_clip = false;
  const Prepared p(GenerateScene("gears", 3000), boxes);
  const std::vector<Ray> rays = RaysInsideTheBox(p.scene, 2000);
  for (const fp::Format format : fp::Presets()) {
    SCOPED_TRACE(format.Name());
    TraceOptions closest, any;
    closest.format = any.format = format;
    any.query = Query::kAny;
    std::vector<RayCounters> cc, ca;
    const std::vector<Hit> hc = TraceRays(p.view(), rays, closest, nullptr, &cc);
    const std::vector<Hit> ha = TraceRays(p.view(), rays, any, nullptr, &ca);
    uint64_t nodes_closest = 0, nodes_any = 0, hits = 0, different = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      ASSERT_EQ(hc[i].IsHit(), ha[i].IsHit()) << "ray " << i;
      EXPECT_LE(ca[i].nodes, cc[i].nodes) << "ray " << i;
      nodes_closest += cc[i].nodes;
      nodes_any += ca[i].nodes;
      if (!ha[i].IsHit()) continue;
      ++hits;
      EXPECT_GE(ha[i].t, hc[i].t) << "ray " << i;
      EXPECT_LE(ha[i].t, rays[i].tmax) << "ray " << i;
      different += ha[i].prim != hc[i].prim;
    }
    EXPECT_GT(hits, rays.size() / 4);
    EXPECT_LT(nodes_any, nodes_closest) << "early exit saved no node on any ray";
    // Most rays hit their closest triangle in the first leaf with a hit, but
    // not all: both kinds must occur.
    EXPECT_GT(different, 0u);
  }
}

TEST(RayFile, KeepsTheQuery) {
  const std::string path = (std::filesystem::temp_directory_path() / "kdrt_query_rays.bin").string();
  const std::vector<Ray> rays = {Ray{{0, 0, 1}, {0, 0, -1}, 0.0f, 0.5f}};
  for (const Query q : {Query::kClosest, Query::kAny}) {
    WriteRaysFile(path, rays, q);
    Query got = q == Query::kAny ? Query::kClosest : Query::kAny;
    const std::vector<Ray> back = ReadRaysFile(path, &got);
    EXPECT_EQ(got, q);
    ASSERT_EQ(back.size(), 1u);
    EXPECT_EQ(back[0].tmax, 0.5f);
  }
  std::remove(path.c_str());
}

// A floor (y = 0), a small square occluder at y = 1 over the origin, a light
// at (0, 3, 0): the floor under the occluder is in shadow (|x| < 0.75), the
// floor at x = 2 is lit. Both primary rays pass beside the occluder.
struct ShadowScene {
  Scene scene;
  std::vector<Ray> primary;
  ShadowScene() {
    SceneBuilder b(&scene);
    const glm::vec3 floor[4] = {{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}};
    b.AddFan(floor, 4);
    const glm::vec3 occluder[4] = {{-0.5f, 1, -0.5f}, {0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}, {-0.5f, 1, 0.5f}};
    b.AddFan(occluder, 4);
    Light l;
    l.position = {0, 3, 0};
    scene.lights.push_back(l);
    const glm::vec3 eye(3, 2, 0.1f);
    for (const glm::vec3 target : {glm::vec3(0, 0, 0.1f), glm::vec3(2, 0, 0.1f)}) {
      primary.push_back(Ray{eye, target - eye, 0.0f, INFINITY});
    }
  }
};

TEST(Shading, ShadowRaysFindTheOccluder) {
  const ShadowScene s;
  const Prepared p(s.scene);
  TraceOptions to;
  const std::vector<Hit> hits = TraceRays(p.view(), s.primary, to);
  ASSERT_TRUE(hits[0].IsHit() && hits[1].IsHit());
  ASSERT_LT(hits[0].prim, 2u) << "the first ray must reach the floor, beside the occluder";

  const FrameShader shader(s.scene, ShadingOptions{});
  const std::vector<RayPass> passes = shader.SecondaryPasses(s.primary, hits);
  ASSERT_EQ(passes.size(), 1u);
  const RayPass& shadow = passes[0];
  EXPECT_EQ(shadow.name, "shadow");
  EXPECT_EQ(shadow.query, Query::kAny);
  ASSERT_EQ(shadow.rays.size(), 2u);
  to.query = Query::kAny;
  const std::vector<Hit> shadow_hits = TraceRays(p.view(), shadow.rays, to);
  EXPECT_TRUE(shadow_hits[0].IsHit());
  EXPECT_GE(shadow_hits[0].prim, 2u) << "the occluder casts the shadow";
  EXPECT_FALSE(shadow_hits[1].IsHit());

  const std::vector<float> rgb = shader.Shade(s.primary, hits, passes, {shadow_hits});
  // In shadow: the ambient term alone (0.1 x white).
  EXPECT_NEAR(rgb[0], 0.1f, 1e-6f);
  EXPECT_GT(rgb[3], rgb[0] + 0.2f);
}

TEST(Shading, RaySetsAreDeterministicAndSeeded) {
  const Prepared p(GenerateScene("room", 2000));
  const std::vector<Ray> rays = CameraRays(p.scene, 16);
  const std::vector<Hit> hits = TraceRays(p.view(), rays, TraceOptions{});
  ShadingOptions o;
  o.ao_samples = 3;
  o.bounce = true;
  const std::vector<RayPass> a = FrameShader(p.scene, o).SecondaryPasses(rays, hits);
  const std::vector<RayPass> b = FrameShader(p.scene, o).SecondaryPasses(rays, hits);
  o.seed = 2;
  const std::vector<RayPass> c = FrameShader(p.scene, o).SecondaryPasses(rays, hits);
  ASSERT_EQ(a.size(), 3u);
  size_t hit_count = 0;
  for (const Hit& h : hits) hit_count += h.IsHit();
  EXPECT_EQ(a[1].rays.size(), 3 * hit_count);
  EXPECT_EQ(a[2].rays.size(), hit_count);
  for (size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].rays.size(), b[k].rays.size());
    for (size_t i = 0; i < a[k].rays.size(); ++i) {
      EXPECT_EQ(std::memcmp(&a[k].rays[i], &b[k].rays[i], sizeof(Ray)), 0);
      if (i > 0) {
        EXPECT_LE(a[k].pixel[i - 1], a[k].pixel[i]) << "passes follow the primary order";
      }
    }
  }
  // The seed moves the AO and bounce directions, not the shadow rays.
  EXPECT_EQ(std::memcmp(a[0].rays.data(), c[0].rays.data(), a[0].rays.size() * sizeof(Ray)), 0);
  EXPECT_NE(std::memcmp(a[1].rays.data(), c[1].rays.data(), a[1].rays.size() * sizeof(Ray)), 0);
  // AO and bounce rays start on the side of the triangle the camera sees and
  // head into that half-space.
  for (size_t k = 1; k < a.size(); ++k) {
    for (size_t i = 0; i < a[k].rays.size(); ++i) {
      const uint32_t px = a[k].pixel[i];
      const Triangle& t = p.scene.triangles[hits[px].prim];
      glm::dvec3 n = glm::cross(glm::dvec3(t.v1 - t.v0), glm::dvec3(t.v2 - t.v0));
      if (glm::dot(n, glm::dvec3(rays[px].d)) > 0) n = -n;
      EXPECT_GT(glm::dot(glm::dvec3(a[k].rays[i].o - t.v0), n), 0.0) << a[k].name << " ray " << i;
      EXPECT_GE(glm::dot(glm::dvec3(a[k].rays[i].d), n), 0.0) << a[k].name << " ray " << i;
    }
  }
}

TEST(Shading, SceneWithoutLightsGetsOneAboveTheCamera) {
  Scene s = GenerateScene("tetra", 500);
  ASSERT_TRUE(s.lights.empty());
  const std::vector<Light> lights = ShadingLights(s);
  ASSERT_EQ(lights.size(), 1u);
  EXPECT_GT(glm::dot(lights[0].position - s.camera->from, s.camera->up), 0.0f);
  Light l;
  l.position = {1, 2, 3};
  s.lights = {l, l};
  EXPECT_EQ(ShadingLights(s).size(), 2u);
}

}  // namespace
}  // namespace kdrt
