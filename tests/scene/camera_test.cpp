#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <gtest/gtest.h>

#include "common/error.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace kdrt {
namespace {

constexpr double kPi = 3.14159265358979323846;

Camera TestCamera(int w, int h, float angle) {
  Camera c;
  c.from = glm::vec3(1.0f, 2.0f, 3.0f);
  c.at = glm::vec3(-2.0f, 0.5f, -4.0f);
  c.up = glm::vec3(0.1f, 1.0f, 0.0f);
  c.angle_deg = angle;
  c.hither = 0.125f;
  c.width = w;
  c.height = h;
  return c;
}

// The view basis, built independently of camera.cpp.
struct Basis {
  glm::dvec3 fwd, right, up;
};
Basis BasisOf(const Camera& c) {
  Basis b;
  b.fwd = glm::normalize(glm::dvec3(c.at) - glm::dvec3(c.from));
  b.right = glm::normalize(glm::cross(b.fwd, glm::dvec3(c.up)));
  b.up = glm::cross(b.right, b.fwd);
  return b;
}

TEST(PrimaryRay, CentreOfOddImageLooksExactlyAtAt) {
  Camera c = TestCamera(63, 31, 50.0f);
  CameraRay r = PrimaryRay(c, 31, 15);
  glm::dvec3 expect = glm::normalize(glm::dvec3(c.at) - glm::dvec3(c.from));
  EXPECT_EQ(r.d, glm::vec3(expect));
  EXPECT_EQ(r.o, c.from);
  EXPECT_EQ(r.tmin, c.hither);
}

TEST(PrimaryRay, FirstColumnIsHalfTheAngleFromTheAxis) {
  for (float angle : {10.0f, 45.0f, 90.0f, 120.0f}) {
    Camera c = TestCamera(64, 48, angle);
    Basis b = BasisOf(c);
    CameraRay r = PrimaryRay(c, 0, 0);
    glm::dvec3 d(r.d);
    // Horizontal angle: within the plane of the view axis and `right`.
    double horizontal = std::atan2(glm::dot(d, b.right), glm::dot(d, b.fwd));
    EXPECT_NEAR(horizontal, -0.5 * angle * kPi / 180.0, 1e-6) << angle;
    CameraRay last = PrimaryRay(c, 63, 0);
    glm::dvec3 dl(last.d);
    EXPECT_NEAR(std::atan2(glm::dot(dl, b.right), glm::dot(dl, b.fwd)), 0.5 * angle * kPi / 180.0,
                1e-6);
    EXPECT_NEAR(glm::length(d), 1.0, 1e-6);
  }
}

TEST(PrimaryRay, PixelsAreSquareAndRowZeroIsTheTop) {
  Camera c = TestCamera(101, 51, 40.0f);
  Basis b = BasisOf(c);
  // Tangent of the angle to the axis, per pixel step, on both image axes.
  auto tangents = [&](int px, int py) {
    glm::dvec3 d(PrimaryRay(c, px, py).d);
    return glm::dvec2(glm::dot(d, b.right), glm::dot(d, b.up)) / glm::dot(d, b.fwd);
  };
  glm::dvec2 top = tangents(50, 0);
  glm::dvec2 bottom = tangents(50, 50);
  glm::dvec2 left = tangents(0, 25);
  EXPECT_GT(top.y, 0.0);
  EXPECT_LT(bottom.y, 0.0);
  EXPECT_LT(left.x, 0.0);
  EXPECT_NEAR(top.y, -bottom.y, 1e-7);
  // 25 rows up spans as much as 25 columns sideways: square pixels.
  EXPECT_NEAR(top.y / 25.0, -left.x / 50.0, 1e-7);
  EXPECT_NEAR(-left.x, std::tan(20.0 * kPi / 180.0), 1e-6);
}

TEST(PrimaryRay, DegenerateSizesStayFinite) {
  for (auto wh : {glm::ivec2(1, 1), glm::ivec2(1, 9), glm::ivec2(9, 1), glm::ivec2(2, 2)}) {
    Camera c = TestCamera(wh.x, wh.y, 30.0f);
    for (int py = 0; py < wh.y; ++py) {
      for (int px = 0; px < wh.x; ++px) {
        CameraRay r = PrimaryRay(c, px, py);
        EXPECT_TRUE(std::isfinite(r.d.x) && std::isfinite(r.d.y) && std::isfinite(r.d.z));
        EXPECT_NEAR(glm::length(glm::dvec3(r.d)), 1.0, 1e-6);
      }
    }
  }
  Camera one = TestCamera(1, 1, 30.0f);
  EXPECT_EQ(PrimaryRay(one, 0, 0).d, glm::vec3(BasisOf(one).fwd));
  // A single column: the angle spans the rows.
  Camera column = TestCamera(1, 9, 30.0f);
  Basis b = BasisOf(column);
  glm::dvec3 d(PrimaryRay(column, 0, 0).d);
  EXPECT_NEAR(std::atan2(glm::dot(d, b.up), glm::dot(d, b.fwd)), 15.0 * kPi / 180.0, 1e-6);
}

TEST(PrimaryRay, IsDeterministicAndMatchesTheFrameOverload) {
  Camera c = TestCamera(32, 32, 45.0f);
  CameraFrame f = MakeCameraFrame(c);
  for (int i = 0; i < 32; ++i) {
    CameraRay a = PrimaryRay(c, i, 31 - i);
    CameraRay b = PrimaryRay(f, i, 31 - i);
    EXPECT_EQ(a.d, b.d);
  }
}

TEST(PrimaryRay, InvalidCamerasThrow) {
  Camera same = TestCamera(8, 8, 45.0f);
  same.at = same.from;
  EXPECT_THROW(PrimaryRay(same, 0, 0), InputError);
  Camera parallel = TestCamera(8, 8, 45.0f);
  parallel.up = parallel.at - parallel.from;
  EXPECT_THROW(PrimaryRay(parallel, 0, 0), InputError);
  Camera wide = TestCamera(8, 8, 180.0f);
  EXPECT_THROW(PrimaryRay(wide, 0, 0), InputError);
  Camera empty = TestCamera(0, 8, 45.0f);
  EXPECT_THROW(PrimaryRay(empty, 0, 0), InputError);
}

TEST(AutoCamera, FramesTheWholeBoxFromPlusZ) {
  Scene s;
  s.triangles.push_back({{-3, 1, 2}, {5, 1, 2}, {5, 4, 2}});
  s.triangles.push_back({{-3, 1, -7}, {5, 4, -7}, {-3, 4, 6}});
  for (auto wh : {glm::ivec2(512, 512), glm::ivec2(640, 200), glm::ivec2(100, 400)}) {
    Camera c = AutoCamera(s, wh.x, wh.y);
    EXPECT_EQ(c.width, wh.x);
    EXPECT_EQ(c.height, wh.y);
    EXPECT_EQ(c.angle_deg, 45.0f);
    EXPECT_EQ(c.up, glm::vec3(0, 1, 0));
    EXPECT_EQ(c.at, glm::vec3(1.0f, 2.5f, -0.5f));  // box centre
    EXPECT_EQ(c.from.x, c.at.x);
    EXPECT_EQ(c.from.y, c.at.y);
    EXPECT_GT(c.from.z, 6.0f);  // outside the box, on the +z side
    // Every box corner projects between the outer pixel centres.
    Basis b = BasisOf(c);
    double half_x = std::tan(22.5 * kPi / 180.0);
    double half_y = half_x * (wh.y - 1) / (wh.x - 1);
    for (int corner = 0; corner < 8; ++corner) {
      glm::dvec3 p((corner & 1) ? 5 : -3, (corner & 2) ? 4 : 1, (corner & 4) ? 6 : -7);
      glm::dvec3 v = p - glm::dvec3(c.from);
      double z = glm::dot(v, b.fwd);
      EXPECT_GT(z, 0.0);
      EXPECT_LE(std::abs(glm::dot(v, b.right) / z), half_x + 1e-9);
      EXPECT_LE(std::abs(glm::dot(v, b.up) / z), half_y + 1e-9);
    }
    EXPECT_NO_THROW(ValidateCamera(c));
  }
}

TEST(AutoCamera, EmptyOrPointSceneStillGivesAValidCamera) {
  Scene empty;
  EXPECT_NO_THROW(ValidateCamera(AutoCamera(empty, 16, 16)));
  Scene point;
  point.triangles.push_back({{2, 2, 2}, {2, 2, 2}, {2, 2, 2}});
  Camera c = AutoCamera(point, 16, 16);
  EXPECT_NO_THROW(ValidateCamera(c));
  EXPECT_EQ(c.at, glm::vec3(2, 2, 2));
  EXPECT_THROW(AutoCamera(point, 0, 16), InputError);
}

}  // namespace
}  // namespace kdrt
