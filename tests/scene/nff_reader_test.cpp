#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "scene/scene.h"
#include "tests/scene/scene_test_util.h"

namespace kdrt {
namespace {

using testing::TempDir;

const char kSmallNff[] =
    "# a hand-written NFF scene\n"
    "v\n"
    "from 1 2 10\n"
    "at 0.5 -1 0\n"
    "up 0 1 0\n"
    "angle 30\n"
    "hither 0.25\n"
    "resolution 64 48\n"
    "b 0.1 0.2 0.3\n"
    "l 5 5 5\n"
    "l 1 2 3 0.5 0.5 0.5\n"
    "\n"
    "f 1 0 0 0.7 0.3 4 0 1\n"
    "p 4\n"
    "0 0 0\n"
    "1 0 0\n"
    "1 1 0\n"
    "0 1 0\n"
    "# a comment between polygons\n"
    "f 0 1 0 0.7 0.3 4 0 1\n"
    "p 3\n"
    "  2 0 0\n"
    "\t3 0 0\n"
    "2 1 0\n"
    "f 1 0 0 0.5 0.5 10 0 1.5\n"
    "pp 5\n"
    "0 0 5 0 0 1\n"
    "1 0 5 0 0 1\n"
    "2 1 5 0 0 1\n"
    "1 2 5 0 0 1\n"
    "0 1 5 0 0 1\n";

TEST(NffReader, SmallFileTrianglesFanColoursCamera) {
  TempDir dir;
  Scene s = LoadScene(dir.Write("small.nff", kSmallNff));
  ASSERT_EQ(s.triangles.size(), 6u);  // quad 2 + triangle 1 + pentagon 3
  ASSERT_EQ(s.material.size(), 6u);

  // Quad fanned from its first vertex, in file order.
  EXPECT_EQ(s.triangles[0].v0, glm::vec3(0, 0, 0));
  EXPECT_EQ(s.triangles[0].v1, glm::vec3(1, 0, 0));
  EXPECT_EQ(s.triangles[0].v2, glm::vec3(1, 1, 0));
  EXPECT_EQ(s.triangles[1].v0, glm::vec3(0, 0, 0));
  EXPECT_EQ(s.triangles[1].v1, glm::vec3(1, 1, 0));
  EXPECT_EQ(s.triangles[1].v2, glm::vec3(0, 1, 0));
  EXPECT_EQ(s.triangles[2].v0, glm::vec3(2, 0, 0));
  EXPECT_EQ(s.triangles[2].v2, glm::vec3(2, 1, 0));
  // Pentagon patch: normals ignored, fan (0,1,2) (0,2,3) (0,3,4).
  EXPECT_EQ(s.triangles[3].v1, glm::vec3(1, 0, 5));
  EXPECT_EQ(s.triangles[4].v1, glm::vec3(2, 1, 5));
  EXPECT_EQ(s.triangles[5].v0, glm::vec3(0, 0, 5));
  EXPECT_EQ(s.triangles[5].v1, glm::vec3(1, 2, 5));
  EXPECT_EQ(s.triangles[5].v2, glm::vec3(0, 1, 5));

  auto color = [&](int i) { return s.colors.at(s.material[i]); };
  EXPECT_EQ(color(0), glm::vec3(1, 0, 0));
  EXPECT_EQ(color(1), glm::vec3(1, 0, 0));
  EXPECT_EQ(color(2), glm::vec3(0, 1, 0));
  for (int i = 3; i < 6; ++i) EXPECT_EQ(color(i), glm::vec3(1, 0, 0));
  EXPECT_EQ(s.material[0], s.material[1]);
  EXPECT_NE(s.material[0], s.material[3]);  // same colour, another finish: another entry
  ASSERT_EQ(s.finishes.size(), s.colors.size());
  EXPECT_EQ(s.finishes[s.material[0]].kd, 0.7f);
  EXPECT_EQ(s.finishes[s.material[0]].ks, 0.3f);
  EXPECT_EQ(s.finishes[s.material[0]].shine, 4.0f);
  EXPECT_EQ(s.finishes[s.material[3]].kd, 0.5f);
  EXPECT_EQ(s.finishes[s.material[3]].shine, 10.0f);
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].position, glm::vec3(5, 5, 5));
  EXPECT_FALSE(s.lights[0].has_color);
  EXPECT_EQ(s.lights[1].position, glm::vec3(1, 2, 3));
  EXPECT_TRUE(s.lights[1].has_color);
  EXPECT_EQ(s.lights[1].color, glm::vec3(0.5f));

  EXPECT_EQ(s.background, glm::vec3(0.1f, 0.2f, 0.3f));
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_EQ(s.camera->from, glm::vec3(1, 2, 10));
  EXPECT_EQ(s.camera->at, glm::vec3(0.5f, -1, 0));
  EXPECT_EQ(s.camera->up, glm::vec3(0, 1, 0));
  EXPECT_EQ(s.camera->angle_deg, 30.0f);
  EXPECT_EQ(s.camera->hither, 0.25f);
  EXPECT_EQ(s.camera->width, 64);
  EXPECT_EQ(s.camera->height, 48);
}

TEST(NffReader, NoFillLineMeansWhiteAndNoViewMeansNoCamera) {
  TempDir dir;
  Scene s = LoadScene(dir.Write("plain.nff", "p 3\n0 0 0\n1 0 0\n0 1 0\n"));
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.colors.at(s.material[0]), glm::vec3(1, 1, 1));
  EXPECT_FALSE(s.camera.has_value());
}

TEST(NffReader, CrlfLineEndingsAndUpperCaseExtension) {
  TempDir dir;
  Scene s = LoadScene(dir.Write("crlf.NFF", "b 0 0 1\r\np 3\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n"));
  EXPECT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.background, glm::vec3(0, 0, 1));
  EXPECT_EQ(s.triangles[0].v1, glm::vec3(1, 0, 0));
}

TEST(NffReader, ZeroAreaTrianglesKeepTheirNumber) {
  TempDir dir;
  Scene s = LoadScene(dir.Write("degenerate.nff",
                                "p 3\n0 0 0\n1 0 0\n0 1 0\n"
                                "p 3\n0 0 0\n1 1 1\n2 2 2\n"  // collinear
                                "p 3\n5 5 5\n5 5 5\n5 5 5\n"  // a point
                                "p 3\n0 0 1\n1 0 1\n0 1 1\n"));
  ASSERT_EQ(s.triangles.size(), 4u);
  EXPECT_FALSE(IsDegenerate(s.triangles[0]));
  EXPECT_TRUE(IsDegenerate(s.triangles[1]));
  EXPECT_TRUE(IsDegenerate(s.triangles[2]));
  EXPECT_FALSE(IsDegenerate(s.triangles[3]));
  EXPECT_EQ(s.triangles[3].v0, glm::vec3(0, 0, 1));
}

TEST(NffReader, IsDegenerateUsesExactFloatCrossProduct) {
  // Tiny but non-zero in float: not degenerate.
  Triangle tiny{{0, 0, 0}, {1e-10f, 0, 0}, {0, 1e-10f, 0}};
  EXPECT_FALSE(IsDegenerate(tiny));
  // The cross product underflows to zero in float.
  Triangle underflow{{0, 0, 0}, {1e-30f, 0, 0}, {0, 1e-30f, 0}};
  EXPECT_TRUE(IsDegenerate(underflow));
}

// Expected counts follow the documented rule: `segments` slices and
// max(2, segments / 2) stacks, the two caps as single triangles.
int DocumentedSphereTriangles(int segments) {
  int stacks = segments / 2 < 2 ? 2 : segments / 2;
  return segments * 2 + (stacks - 2) * segments * 2;
}

TEST(NffReader, SphereTessellationFollowsOption) {
  TempDir dir;
  std::string path = dir.Write("sphere.nff", "s 1 2 3 0.5\n");
  Scene def = LoadScene(path);
  EXPECT_EQ(def.triangles.size(), static_cast<size_t>(DocumentedSphereTriangles(16)));
  for (int seg : {3, 4, 7, 8, 33}) {
    LoadOptions opt;
    opt.sphere_segments = seg;
    Scene s = LoadScene(path, opt);
    EXPECT_EQ(s.triangles.size(), static_cast<size_t>(DocumentedSphereTriangles(seg))) << seg;
    for (const Triangle& t : s.triangles) {
      EXPECT_FALSE(IsDegenerate(t));
      for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
        EXPECT_NEAR(glm::length(glm::dvec3(v) - glm::dvec3(1, 2, 3)), 0.5, 1e-6);
      }
      // Outward facing: the normal points away from the centre.
      glm::vec3 n = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
      EXPECT_GT(glm::dot(n, (t.v0 + t.v1 + t.v2) / 3.0f - glm::vec3(1, 2, 3)), 0.0f);
    }
  }
  LoadOptions bad;
  bad.sphere_segments = 2;
  EXPECT_THROW(LoadScene(path, bad), InputError);
}

TEST(NffReader, ConeTessellationFollowsOption) {
  TempDir dir;
  std::string frustum = dir.Write("frustum.nff", "c\n0 0 0 1\n0 0 2 0.5\n");
  std::string cone = dir.Write("cone.nff", "c\n1 1 1 2\n1 4 1 0\n");
  LoadOptions opt;
  opt.cone_segments = 12;
  Scene f = LoadScene(frustum, opt);
  EXPECT_EQ(f.triangles.size(), 24u);
  for (const Triangle& t : f.triangles) {
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      double r = std::hypot(double(v.x), double(v.y));
      EXPECT_NEAR(r, v.z == 0.0f ? 1.0 : 0.5, 1e-6);
    }
  }
  Scene c = LoadScene(cone, opt);
  EXPECT_EQ(c.triangles.size(), 12u);  // one triangle per side: apex radius 0
  EXPECT_EQ(LoadScene(frustum).triangles.size(), 32u);  // default 16 sides
  for (const Triangle& t : c.triangles) EXPECT_FALSE(IsDegenerate(t));
}

// --cone-aspect: a cylinder 50 times longer than its radius (one band of
// slivers about 130 times longer than wide at 16 sides) is cut into rings
// along its axis so that no cell is more than A times longer than wide. The
// rings are computed once, so neighbouring bands share their vertices bit for
// bit: every edge inside the surface belongs to exactly two triangles, as in
// one band (no crack for the watertight test).
TEST(NffReader, ConeAspectCutsLongCylindersIntoBands) {
  TempDir dir;
  const std::string file = dir.Write("long.nff", "c\n0 0 0 0.02\n0.3 0.4 1 0.02\n");
  LoadOptions one, banded;
  banded.cone_aspect = 4;
  const Scene a = LoadScene(file, one), b = LoadScene(file, banded);
  ASSERT_EQ(a.triangles.size(), 32u);
  // One band of slivers is said (a warning naming the cone's line and the
  // option), not refused, even with --strict; bands are not.
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_NE(a.warnings[0].find("long.nff:1:"), std::string::npos) << a.warnings[0];
  EXPECT_NE(a.warnings[0].find("--cone-aspect"), std::string::npos) << a.warnings[0];
  EXPECT_TRUE(b.warnings.empty());
  LoadOptions strict;
  strict.strict = true;
  EXPECT_EQ(LoadScene(file, strict).warnings.size(), 1u);
  const double length = std::sqrt(0.3 * 0.3 + 0.4 * 0.4 + 1.0);
  const double side = 2 * 0.02 * std::sin(3.14159265358979323846 / 16);
  const size_t bands = static_cast<size_t>(std::ceil(length / (4 * side)));
  ASSERT_EQ(b.triangles.size(), 32u * bands);
  // Each cell is at most 4 times longer than its widest side (within float rounding).
  for (const Triangle& t : b.triangles) {
    const float e[3] = {glm::length(t.v1 - t.v0), glm::length(t.v2 - t.v1), glm::length(t.v0 - t.v2)};
    const float shortest = std::min({e[0], e[1], e[2]});
    EXPECT_LE(glm::length(t.v2 - t.v1), 4.0f * float(side) * 1.0001f);
    EXPECT_GT(shortest, 0.0f);
    EXPECT_FALSE(IsDegenerate(t));
  }
  // Edges: the two end rings' 32 edges once, every other edge twice.
  std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> edges;
  auto key = [](const glm::vec3& p) { return std::array<float, 3>{p.x, p.y, p.z}; };
  for (const Triangle& t : b.triangles) {
    const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
    for (int i = 0; i < 3; ++i) {
      auto p = key(v[i]), q = key(v[(i + 1) % 3]);
      if (q < p) std::swap(p, q);
      ++edges[{p, q}];
    }
  }
  int once = 0;
  for (const auto& [edge, n] : edges) {
    EXPECT_LE(n, 2);
    once += n == 1;
  }
  EXPECT_EQ(once, 32);
  // The end rings are the one-band cylinder's: the same float vertices.
  std::set<std::array<float, 3>> ends_a, ends_b;
  for (const Triangle& t : a.triangles) {
    for (const glm::vec3& p : {t.v0, t.v1, t.v2}) ends_a.insert(key(p));
  }
  for (const Triangle& t : b.triangles) {
    for (const glm::vec3& p : {t.v0, t.v1, t.v2}) {
      if (ends_a.count(key(p)) != 0) ends_b.insert(key(p));
    }
  }
  EXPECT_EQ(ends_b, ends_a);
  // A short cylinder needs no bands; 0 and values below 1 are refused or one band.
  EXPECT_EQ(LoadScene(dir.Write("short.nff", "c\n0 0 0 1\n0 0 0.1 1\n"), banded).triangles.size(), 32u);
  LoadOptions bad;
  bad.cone_aspect = 0.5;
  EXPECT_THROW(LoadScene(file, bad), InputError);
}

TEST(NffReader, PrimitivesKeepFileOrderAndColours) {
  TempDir dir;
  LoadOptions opt;
  opt.sphere_segments = 4;  // 8 triangles
  opt.cone_segments = 3;    // 6 triangles
  Scene s = LoadScene(dir.Write("mix.nff",
                                "f 0 0 1 1 0 0 0 1\n"
                                "p 3\n0 0 0\n1 0 0\n0 1 0\n"
                                "f 1 1 0 1 0 0 0 1\n"
                                "s 10 0 0 1\n"
                                "f 0 1 1 1 0 0 0 1\n"
                                "c\n20 0 0 1\n20 0 1 1\n"
                                "p 3\n0 0 9\n1 0 9\n0 1 9\n"),
                      opt);
  ASSERT_EQ(s.triangles.size(), 1u + 8u + 6u + 1u);
  EXPECT_EQ(s.colors[s.material[0]], glm::vec3(0, 0, 1));
  for (int i = 1; i <= 8; ++i) {
    EXPECT_NEAR(s.triangles[i].v0.x, 10.0f, 1.0f);
    EXPECT_EQ(s.colors[s.material[i]], glm::vec3(1, 1, 0));
  }
  for (int i = 9; i <= 14; ++i) {
    EXPECT_NEAR(s.triangles[i].v0.x, 20.0f, 1.0f);
    EXPECT_EQ(s.colors[s.material[i]], glm::vec3(0, 1, 1));
  }
  EXPECT_EQ(s.triangles[15].v0, glm::vec3(0, 0, 9));
}

}  // namespace
}  // namespace kdrt

namespace kdrt {
namespace {

TEST(NffReader, ExampleScenesInTheRepositoryLoad) {
  const std::string dir = std::string(KDRT_SOURCE_DIR) + "/scenes/";
  Scene simple = LoadScene(dir + "simple.nff");
  // floor quad 2 + sphere 224 + cylinder 32 + cone 16 + pentagon 3
  EXPECT_EQ(simple.triangles.size(), 2u + 224u + 32u + 16u + 3u);
  ASSERT_TRUE(simple.camera.has_value());
  EXPECT_EQ(simple.camera->width, 512);
  EXPECT_EQ(simple.colors.size(), 5u);
  Scene pyramid = LoadScene(dir + "pyramid.nff");
  EXPECT_EQ(pyramid.triangles.size(), 6u);
  EXPECT_FALSE(pyramid.camera.has_value());
}

}  // namespace
}  // namespace kdrt
