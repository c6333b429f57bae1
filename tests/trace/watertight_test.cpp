// Watertightness through the whole tracer: rays aimed at the vertices and edge
// midpoints of closed meshes (trace/watertight.h) must all hit, in every
// preset format.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <tuple>

#include <glm/glm.hpp>

#include "common/error.h"
#include "trace/watertight.h"
#include "trace_test_util.h"

namespace kdrt {
namespace {

using testing::Prepared;

// A vertex identified by its bits: closedness is about identical floats.
using VertexKey = std::tuple<uint32_t, uint32_t, uint32_t>;
VertexKey Key(const glm::vec3& p) {
  uint32_t b[3];
  std::memcpy(b, &p[0], 12);
  return {b[0], b[1], b[2]};
}

// Closed and consistently wound: every directed edge appears exactly once and
// its reverse appears exactly once.
void ExpectClosed(const Scene& s) {
  std::map<std::pair<VertexKey, VertexKey>, int> directed;
  for (const Triangle& t : s.triangles) {
    const glm::vec3* v[3] = {&t.v0, &t.v1, &t.v2};
    for (int k = 0; k < 3; ++k) ++directed[{Key(*v[k]), Key(*v[(k + 1) % 3])}];
  }
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << s.source;
    const auto it = directed.find({edge.second, edge.first});
    ASSERT_TRUE(it != directed.end()) << s.source << ": open edge";
  }
}

// Outward winding: the signed volume (divergence theorem) is positive and
// close to the solid's volume.
double SignedVolume(const Scene& s) {
  double vol = 0;
  for (const Triangle& t : s.triangles) {
    const glm::dvec3 a(t.v0), b(t.v1), c(t.v2);
    vol += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return vol;
}

size_t CountMisses(const ImageView& image, const std::vector<Ray>& rays, const fp::Format& f) {
  TraceOptions o;
  o.format = f;
  o.threads = 2;
  size_t misses = 0;
  for (const Hit& h : TraceRays(image, rays, o)) misses += !h.IsHit();
  return misses;
}

TEST(Watertight, MeshesAreClosedAndOutwardWound) {
  const Scene sphere = ClosedSphereMesh(12, 24);
  EXPECT_EQ(sphere.triangles.size(), 2u * 24 * 11);
  ExpectClosed(sphere);
  EXPECT_NEAR(SignedVolume(sphere), 4.0 / 3.0 * M_PI, 0.2);
  const Scene cube = ClosedCubeMesh(5);
  EXPECT_EQ(cube.triangles.size(), 12u * 5 * 5);
  ExpectClosed(cube);
  EXPECT_NEAR(SignedVolume(cube), 8.0, 1e-5);
}

TEST(Watertight, SixRaysPerTriangleThroughTheTarget) {
  const Scene cube = ClosedCubeMesh(2);
  const std::vector<Ray> rays = WatertightRays(cube, 3);
  ASSERT_EQ(rays.size(), 6 * cube.triangles.size());
  const Triangle& t = cube.triangles[1];
  const glm::vec3 targets[2] = {t.v0, (t.v1 + t.v2) * 0.5f};
  for (int i = 0; i < 2; ++i) {
    const Ray& r = rays[6 + (i == 0 ? 0 : 4)];
    EXPECT_EQ(r.o + r.d, targets[i]);  // exact up to one rounding per axis
    EXPECT_GT(glm::length(r.o), 2.5f);  // starts outside the cube
  }
  EXPECT_NE(rays[0].o, WatertightRays(cube, 4)[0].o);  // the seed matters
}

TEST(Watertight, BadSizesAreInputErrors) {
  EXPECT_THROW(ClosedSphereMesh(1, 8), InputError);
  EXPECT_THROW(ClosedSphereMesh(4, 2), InputError);
  EXPECT_THROW(ClosedCubeMesh(0), InputError);
}

// The test alone, brute force over every triangle: no ray may slip through.
TEST(Watertight, IntersectionAloneHasNoMisses) {
  const Scene meshes[2] = {ClosedSphereMesh(6, 12), ClosedCubeMesh(3)};
  for (const Scene& mesh : meshes) {
    Prepared p(mesh);
    const ImageView image = p.view();
    const std::vector<Ray> rays = WatertightRays(mesh, 1);
    for (const fp::Format& f : fp::Presets()) {
      const fp::SoftArith a(f);
      size_t misses = 0;
      for (const Ray& ray : rays) misses += !testing::BruteForce(a, image, ray).IsHit();
      EXPECT_EQ(misses, 0u) << mesh.source << " in " << f.Name();
    }
  }
}

// Through the kd-tree: the traversal must not lose these rays either.
TEST(Watertight, TracerHasNoMissesInAnyPreset) {
  const Scene meshes[2] = {ClosedSphereMesh(16, 32), ClosedCubeMesh(8)};
  for (const Scene& mesh : meshes) {
    Prepared p(mesh);
    const std::vector<Ray> rays = WatertightRays(mesh, 1);
    for (const fp::Format& f : fp::Presets()) {
      EXPECT_EQ(CountMisses(p.view(), rays, f), 0u) << mesh.source << " in " << f.Name();
    }
  }
}

// The double-precision reference is watertight too: the same test in double.
TEST(Watertight, TracerHasNoMissesInFp64) {
  const Scene meshes[2] = {ClosedSphereMesh(16, 32), ClosedCubeMesh(8)};
  for (const Scene& mesh : meshes) {
    Prepared p(mesh);
    EXPECT_EQ(CountMisses(p.view(), WatertightRays(mesh, 1), fp::kFp64), 0u) << mesh.source;
  }
}

// The count can fail: with both x faces of the cube removed, the rays aimed
// at points inside those faces go through the open ends.
TEST(Watertight, OpenMeshHasMisses) {
  const int n = 4;
  const Scene cube = ClosedCubeMesh(n);
  const std::vector<Ray> rays = WatertightRays(cube, 1);
  Scene open = cube;
  const size_t x_faces = 4 * n * n;  // generated first: -x, then +x
  open.triangles.erase(open.triangles.begin(), open.triangles.begin() + x_faces);
  open.material.erase(open.material.begin(), open.material.begin() + x_faces);
  Prepared p(open);
  EXPECT_GT(CountMisses(p.view(), rays, fp::kFp32), rays.size() / 10);
}

}  // namespace
}  // namespace kdrt
