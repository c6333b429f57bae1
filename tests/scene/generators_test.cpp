#include <cmath>
#include <cstring>

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
  EXPECT_EQ(names, (std::vector<std::string>{"room", "balls", "rings", "tetra", "tree"}));
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

INSTANTIATE_TEST_SUITE_P(All, EachGenerator, ::testing::ValuesIn(GeneratorNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
}  // namespace kdrt
