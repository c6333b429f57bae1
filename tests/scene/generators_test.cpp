#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <tuple>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/error.h"
#include "scene/camera.h"
#include "scenes/gen/generators.h"

namespace kdrt {
namespace {

bool Finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

TEST(Generators, NamesAndDescriptions) {
  std::vector<std::string> names = GeneratorNames();
  EXPECT_EQ(names, (std::vector<std::string>{"room", "balls", "rings", "tetra", "tree", "gears", "strips", "hoops"}));
  for (const std::string& n : names) EXPECT_FALSE(GeneratorDescription(n).empty());
  EXPECT_THROW(GeneratorDescription("teapot"), InputError);
  EXPECT_THROW(GenerateScene("teapot", 100), InputError);
  EXPECT_THROW(GenerateScene("room", 0), InputError);
  EXPECT_THROW(GenerateScene("room", -5), InputError);
  EXPECT_THROW(GenerateScene("room", kMaxGeneratorSize + 1), InputError);
}

class EachGenerator : public ::testing::TestWithParam<std::string> {};

TEST_P(EachGenerator, CountGrowsWithSizeAndGeometryIsSound) {
  const std::string name = GetParam();
  size_t previous = 0;
  for (int size : {300, 4000, 60000}) {
    Scene s = GenerateScene(name, size);
    const size_t n = s.triangles.size();
    EXPECT_GT(n, previous) << name << " " << size;
    // Roughly proportional: within a factor of 3 of the target.
    EXPECT_GE(n * 3, static_cast<size_t>(size)) << name << " " << size;
    EXPECT_LE(n, static_cast<size_t>(size) * 3) << name << " " << size;
    previous = n;

    ASSERT_EQ(s.material.size(), n);
    size_t degenerate = 0;
    for (size_t i = 0; i < n; ++i) {
      const Triangle& t = s.triangles[i];
      ASSERT_TRUE(Finite(t.v0) && Finite(t.v1) && Finite(t.v2)) << name << " triangle " << i;
      ASSERT_LT(s.material[i], s.colors.size());
      if (IsDegenerate(t)) ++degenerate;
    }
    EXPECT_LE(degenerate * 1000, n) << name << ": " << degenerate << " degenerate";
    ASSERT_TRUE(s.camera.has_value());
    EXPECT_EQ(s.camera->width, 512);
    EXPECT_EQ(s.camera->height, 512);
    EXPECT_NO_THROW(ValidateCamera(*s.camera));
    EXPECT_GE(s.colors.size(), 2u);
    EXPECT_FALSE(s.source.empty());
  }
}

TEST_P(EachGenerator, IsDeterministic) {
  Scene a = GenerateScene(GetParam(), 3000);
  Scene b = GenerateScene(GetParam(), 3000);
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  EXPECT_EQ(std::memcmp(a.triangles.data(), b.triangles.data(),
                        a.triangles.size() * sizeof(Triangle)),
            0);
  EXPECT_EQ(a.material, b.material);
}

TEST_P(EachGenerator, SmallestSizeWorks) {
  Scene s = GenerateScene(GetParam(), 1);
  EXPECT_GT(s.triangles.size(), 0u);
  EXPECT_LE(s.triangles.size(), 200u);
}

TEST(Gears, CountIsNearSize) {
  for (int size : {1000, 10000, 100000}) {
    const double n = static_cast<double>(GenerateScene("gears", size).triangles.size());
    EXPECT_GE(n * 1.5, size) << size;
    EXPECT_LE(n, size * 1.5) << size;
  }
}

// Bit pattern of a vertex, for exact comparisons.
std::tuple<uint32_t, uint32_t, uint32_t> Bits(const glm::vec3& v) {
  uint32_t x, y, z;
  std::memcpy(&x, &v.x, 4);
  std::memcpy(&y, &v.y, 4);
  std::memcpy(&z, &v.z, 4);
  return {x, y, z};
}

// Signed area in the xz plane, positive when counter-clockwise seen from +y.
double AreaXZ(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return 0.5 * ((c.x - a.x) * (b.z - a.z) - (b.x - a.x) * (c.z - a.z));
}

// The first triangles of the scene form a fan: same first vertex, each
// triangle's last vertex the next one's second. Returns the polygon.
std::vector<glm::dvec3> LeadingFan(const Scene& s, size_t start, size_t* count) {
  const std::vector<Triangle>& t = s.triangles;
  size_t i = start;
  std::vector<glm::dvec3> poly{glm::dvec3(t[i].v0), glm::dvec3(t[i].v1)};
  while (i < t.size() && Bits(t[i].v0) == Bits(t[start].v0) &&
         (i == start || Bits(t[i].v1) == Bits(t[i - 1].v2))) {
    poly.emplace_back(t[i].v2);
    ++i;
  }
  *count = i - start;
  return poly;
}

bool InPolygonXZ(const std::vector<glm::dvec3>& p, double x, double z) {
  bool in = false;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p[i].z > z) != (p[j].z > z) &&
        x < p[j].x + (z - p[j].z) * (p[i].x - p[j].x) / (p[i].z - p[j].z)) {
      in = !in;
    }
  }
  return in;
}

bool InTriangleXZ(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double x,
                  double z) {
  const glm::dvec3 q(x, 0, z);
  const double d1 = AreaXZ(a, b, q), d2 = AreaXZ(b, c, q), d3 = AreaXZ(c, a, q);
  return (d1 > 0 && d2 > 0 && d3 > 0) || (d1 < 0 && d2 < 0 && d3 < 0);
}

// The point of the scene: every gear face is one concave polygon fanned from
// its first vertex, so its triangles overlap and stick out of the outline.
TEST(Gears, FacesAreFannedConcavePolygons) {
  Scene s = GenerateScene("gears", 3000);
  size_t top_count = 0;
  const std::vector<glm::dvec3> top = LeadingFan(s, 0, &top_count);
  const size_t n = top.size();
  ASSERT_GE(top_count, 30u);
  EXPECT_EQ(top_count, n - 2);  // n - 2 triangles from the n-vertex outline
  std::set<std::tuple<uint32_t, uint32_t, uint32_t>> distinct;
  for (const glm::dvec3& v : top) {
    distinct.insert(Bits(glm::vec3(v)));
    EXPECT_EQ(v.y, top[0].y);  // flat face
  }
  EXPECT_EQ(distinct.size(), n);
  // Then the bottom face: the same outline, lower and the other way round,
  // fanned from the same first vertex: (p0, p[n-1], p[n-2]), ...
  const Triangle* bottom = &s.triangles[top_count];
  for (size_t k = 0; k < top_count; ++k) {
    const Triangle& t = bottom[k];
    EXPECT_EQ(Bits(t.v0), Bits(bottom[0].v0));
    EXPECT_TRUE(t.v0.x == top[0].x && t.v0.z == top[0].z && t.v0.y < top[0].y) << k;
    EXPECT_TRUE(t.v1.x == top[n - 1 - k].x && t.v1.z == top[n - 1 - k].z) << k;
    EXPECT_TRUE(t.v2.x == top[n - 2 - k].x && t.v2.z == top[n - 2 - k].z) << k;
    EXPECT_TRUE(t.v1.y == t.v0.y && t.v2.y == t.v0.y) << k;
  }

  // Concave outline: turns both ways.
  int left = 0, right = 0;
  for (size_t i = 0; i < n; ++i) {
    const double turn = AreaXZ(top[i], top[(i + 1) % n], top[(i + 2) % n]);
    if (turn > 0) ++left;
    if (turn < 0) ++right;
  }
  EXPECT_GT(left, 0);
  EXPECT_GT(right, 0);

  // The fan's signed areas add up to the polygon's; triangles of the other
  // winding mean the fan overlaps itself.
  double polygon = 0.0, unsigned_sum = 0.0;
  int reversed = 0;
  for (size_t i = 1; i + 1 < n; ++i) {
    const double a = AreaXZ(top[0], top[i], top[i + 1]);
    polygon += a;
    unsigned_sum += std::fabs(a);
    if (a < 0) ++reversed;
  }
  EXPECT_GT(polygon, 0.0);  // counter-clockwise seen from above: faces +y
  EXPECT_GT(reversed, 0);
  EXPECT_GT(unsigned_sum, 1.05 * polygon);

  // Sample the face's bounding square: some points outside the outline lie
  // inside a fan triangle.
  double lo_x = top[0].x, hi_x = lo_x, lo_z = top[0].z, hi_z = lo_z;
  for (const glm::dvec3& v : top) {
    lo_x = std::min(lo_x, v.x), hi_x = std::max(hi_x, v.x);
    lo_z = std::min(lo_z, v.z), hi_z = std::max(hi_z, v.z);
  }
  const int m = 200;
  int outside = 0, outside_covered = 0;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      const double x = lo_x + (hi_x - lo_x) * (i + 0.5) / m;
      const double z = lo_z + (hi_z - lo_z) * (j + 0.5) / m;
      if (InPolygonXZ(top, x, z)) continue;
      ++outside;
      for (size_t k = 1; k + 1 < n; ++k) {
        if (InTriangleXZ(top[0], top[k], top[k + 1], x, z)) {
          ++outside_covered;
          break;
        }
      }
    }
  }
  EXPECT_GT(outside_covered * 100, outside) << outside_covered << " of " << outside;
}

INSTANTIATE_TEST_SUITE_P(All, EachGenerator, ::testing::ValuesIn(GeneratorNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
}  // namespace kdrt

namespace kdrt {
namespace {

// gen:hoops with the loader's cone_aspect: the same hoops (the same bounds:
// the same clusters and layers), about as many triangles (fewer sides per
// cylinder for its bands), and no cylinder cell longer than A times its
// side; the other generators ignore the option.
TEST(Hoops, ConeAspectBandsTheSameHoops) {
  LoadOptions banded;
  banded.cone_aspect = 4;
  for (int size : {5000, 100000}) {
    const Scene one = GenerateScene("hoops", size), cut = GenerateScene("hoops", size, banded);
    EXPECT_LE(cut.triangles.size(), static_cast<size_t>(size));
    EXPECT_GT(cut.triangles.size(), one.triangles.size() * 6 / 10) << size;  // S steps coarsely
    glm::vec3 lo_a(1e30f), hi_a(-1e30f), lo_b(1e30f), hi_b(-1e30f);
    for (const Triangle& t : one.triangles) {
      for (const glm::vec3& p : {t.v0, t.v1, t.v2}) lo_a = glm::min(lo_a, p), hi_a = glm::max(hi_a, p);
    }
    float longest_a = 0, longest_b = 0;
    for (const Triangle& t : cut.triangles) {
      for (const glm::vec3& p : {t.v0, t.v1, t.v2}) lo_b = glm::min(lo_b, p), hi_b = glm::max(hi_b, p);
    }
    // The backdrop (the last two triangles) aside, the longest edge.
    for (size_t i = 0; i + 2 < one.triangles.size(); ++i) {
      const Triangle& t = one.triangles[i];
      longest_a = std::max({longest_a, glm::length(t.v1 - t.v0), glm::length(t.v2 - t.v1)});
    }
    for (size_t i = 0; i + 2 < cut.triangles.size(); ++i) {
      const Triangle& t = cut.triangles[i];
      longest_b = std::max({longest_b, glm::length(t.v1 - t.v0), glm::length(t.v2 - t.v1)});
    }
    EXPECT_NEAR(glm::length(hi_a - hi_b) + glm::length(lo_a - lo_b), 0.0f, 0.05f) << size;
    EXPECT_GT(longest_a, 1.0f) << size;  // one band: slivers the cylinder's length (1.18)
    EXPECT_LT(longest_b, 0.3f) << size;   // bands of cells at most 4 sides long
  }
  const Scene balls = GenerateScene("balls", 5000, banded);
  EXPECT_EQ(balls.triangles.size(), GenerateScene("balls", 5000).triangles.size());
  LoadOptions bad;
  bad.cone_aspect = -1;
  EXPECT_THROW(GenerateScene("hoops", 5000, bad), InputError);
}

}  // namespace
}  // namespace kdrt
