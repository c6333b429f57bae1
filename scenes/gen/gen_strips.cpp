// "strips": Haines' SPD "rings" as a tessellator turns it into triangles:
// pentagonal rings of cylinders with a sphere at every corner, each cylinder
// one band of long thin quads from end to end (2S triangles of aspect about
// 90). The rings stand in a G x G grid, each tilted another way, so their
// cylinders run diagonally through space: a strip's box then spans many
// cells the strip itself barely touches, the case that makes a kd-tree's
// leaves large ("long thin cylinder strips and spheres";
// gen:rings' finely tessellated tori do not show it). A floor lies below.
//
// Size mapping: with S = 16 sides per cylinder and spheres of 8 segments
// (fewer below S = 16) a ring has 5 (2S + 48) triangles; G is the most rings
// per row whose G^2 rings fit in `size`, then S the largest (3..64) that
// keeps the total within it.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "scene/tessellate.h"
#include "scenes/gen/gen_common.h"

namespace kdrt::gen {

namespace {

constexpr int kFloorTriangles = 2;

// Spheres of 8 segments, fewer on the coarsest cylinders (tiny sizes).
int SphereSegments(int sides) { return std::clamp(sides / 2, 4, 8); }
long RingTriangles(int sides) { return 5 * (2 * sides + SphereTriangleCount(SphereSegments(sides))); }

}  // namespace

Scene GenerateStrips(int size) {
  long grid = 1;
  while ((grid + 1) * (grid + 1) * RingTriangles(16) + kFloorTriangles <= size) ++grid;
  const long rings = grid * grid;
  int sides = 3;
  while (sides < 64 && rings * RingTriangles(sides + 1) + kFloorTriangles <= size) ++sides;

  const double radius = 1.0;          // the pentagon's circumradius
  const double tube = 0.04 * radius;  // cylinder radius: strips of length 1.18 and width 0.25 / sides
  const double spacing = 1.6 * radius;
  const glm::vec3 colors[] = {{0.85f, 0.3f, 0.25f}, {0.9f, 0.75f, 0.25f}, {0.3f, 0.65f, 0.35f},
                              {0.3f, 0.5f, 0.85f}, {0.7f, 0.4f, 0.8f}};

  Scene scene;
  scene.background = glm::vec3(0.1f, 0.1f, 0.15f);
  SceneBuilder b(&scene);
  for (long i = 0; i < grid; ++i) {
    for (long j = 0; j < grid; ++j) {
      const long k = i * grid + j;
      b.SetColor(colors[k % 5]);
      const glm::dvec3 centre((i - 0.5 * (grid - 1)) * spacing, (j - 0.5 * (grid - 1)) * spacing, 0.0);
      // Tilt 30-70 degrees about a horizontal axis that turns from ring to ring.
      const double turn = 2.0 * kPi * static_cast<double>(k % 7) / 7.0;
      const double tilt = (30.0 + 20.0 * static_cast<double>(k % 3)) * kPi / 180.0;
      const glm::dvec3 normal = Rotate(glm::dvec3(0, 0, 1), glm::dvec3(std::cos(turn), std::sin(turn), 0), tilt);
      glm::dvec3 u, v;
      MakeFrame(normal, &u, &v);
      glm::dvec3 corner[5];
      for (int c = 0; c < 5; ++c) {
        const double a = 2.0 * kPi * c / 5.0;
        corner[c] = centre + radius * (std::cos(a) * u + std::sin(a) * v);
      }
      for (int c = 0; c < 5; ++c) {
        AddCone(b, corner[c], tube, corner[(c + 1) % 5], tube, sides);
        AddSphere(b, corner[c], 1.5 * tube, SphereSegments(sides));
      }
    }
  }
  scene.camera = FramingCamera(scene, {0.0, -2.0, 1.4}, glm::vec3(0, 0, 1), 45.0);
  const double extent = 0.5 * grid * spacing + radius;
  b.SetColor(glm::vec3(0.6f, 0.6f, 0.6f));
  AddGrid(b, {-extent, -extent, -1.1 * radius}, {2 * extent, 0, 0}, {0, 2 * extent, 0}, 1, 1);
  return scene;
}

}  // namespace kdrt::gen
