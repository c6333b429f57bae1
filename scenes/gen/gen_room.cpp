// "room": a closed Cornell-box-like room, 10 units on a side (x, z in
// [-5, 5], y in [0, 10], y up): red left wall, green right wall, the others
// white, a tall and a short box (each turned about y, no bottom face) and a
// sphere on the short box. The camera stands inside, by the front wall.
//
// Size mapping: walls n x n cells each (12 n^2 triangles, ~60% of size),
// boxes k cells per 3 units (28 k^2, ~25%), sphere with s segments
// (s^2 - 2s, ~15%).
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "scene/tessellate.h"
#include "scenes/gen/gen_common.h"

namespace kdrt::gen {

namespace {

int RoundAtLeast(double x, int lo) { return std::max(lo, static_cast<int>(std::lround(x))); }

// An upright box standing on the floor, turned by `turn` radians about y;
// the four sides and the top, each cut into cells of about `cell` units.
void AddBox(SceneBuilder& b, const glm::dvec3& centre_floor, const glm::dvec3& size, double turn,
            double cell) {
  const glm::dvec3 y(0, 1, 0);
  const glm::dvec3 ex = Rotate(glm::dvec3(size.x, 0, 0), y, turn);
  const glm::dvec3 ez = Rotate(glm::dvec3(0, 0, size.z), y, turn);
  const glm::dvec3 ey(0, size.y, 0);
  const glm::dvec3 c0 = centre_floor - 0.5 * ex - 0.5 * ez;  // floor corner
  auto cells = [&](const glm::dvec3& e) { return RoundAtLeast(glm::length(e) / cell, 1); };
  // Each face is wound so edge_u x edge_v points out of the box.
  AddGrid(b, c0, ey, ex, cells(ey), cells(ex));       // -z side
  AddGrid(b, c0 + ex, ey, ez, cells(ey), cells(ez));  // +x side
  AddGrid(b, c0 + ez, ex, ey, cells(ex), cells(ey));  // +z side
  AddGrid(b, c0, ez, ey, cells(ez), cells(ey));       // -x side
  AddGrid(b, c0 + ey, ez, ex, cells(ez), cells(ex));  // top
}

}  // namespace

Scene GenerateRoom(int size) {
  const int n = RoundAtLeast(std::sqrt(0.60 * size / 12.0), 1);
  const int k = RoundAtLeast(std::sqrt(0.25 * size / 28.0), 1);
  // Even s with s^2 - 2s close to 15% of the size.
  const int s = 2 * RoundAtLeast(0.5 * (1.0 + std::sqrt(1.0 + 0.15 * size)), 2);

  Scene scene;
  scene.background = glm::vec3(0.0f);
  SceneBuilder b(&scene);
  const glm::vec3 white(0.73f, 0.73f, 0.73f), red(0.63f, 0.065f, 0.05f),
      green(0.14f, 0.45f, 0.091f);
  const double w = 10.0;
  // Walls face into the room.
  b.SetColor(white);
  AddGrid(b, {-5, 0, -5}, {0, 0, w}, {w, 0, 0}, n, n);   // floor, +y
  AddGrid(b, {-5, w, -5}, {w, 0, 0}, {0, 0, w}, n, n);   // ceiling, -y
  AddGrid(b, {-5, 0, -5}, {w, 0, 0}, {0, w, 0}, n, n);   // back, +z
  AddGrid(b, {-5, 0, 5}, {0, w, 0}, {w, 0, 0}, n, n);    // front, -z
  b.SetColor(red);
  AddGrid(b, {-5, 0, -5}, {0, w, 0}, {0, 0, w}, n, n);   // left, +x
  b.SetColor(green);
  AddGrid(b, {5, 0, -5}, {0, 0, w}, {0, w, 0}, n, n);    // right, -x

  const double cell = 3.0 / k;
  b.SetColor(white);
  AddBox(b, {-1.8, 0, -2.2}, {3, 6, 3}, 17.0 * kPi / 180.0, cell);
  b.SetColor(glm::vec3(0.8f, 0.75f, 0.55f));
  AddBox(b, {1.8, 0, -0.3}, {3, 3, 3}, -17.0 * kPi / 180.0, cell);
  b.SetColor(glm::vec3(0.3f, 0.4f, 0.85f));
  AddSphere(b, {1.8, 4.2, -0.3}, 1.2, s);

  Camera cam;
  cam.from = glm::vec3(0.0f, 5.0f, 4.9f);
  cam.at = glm::vec3(0.0f, 5.0f, 0.0f);
  cam.up = glm::vec3(0.0f, 1.0f, 0.0f);
  cam.angle_deg = 70.0f;
  cam.hither = 0.0f;
  cam.width = kDefaultResolution;
  cam.height = kDefaultResolution;
  scene.camera = cam;
  return scene;
}

}  // namespace kdrt::gen
