// "balls": a sphereflake. A sphere of radius 1 at the origin carries nine
// spheres of a third of its radius touching it (six around its equator,
// three higher up, relative to the direction it grows in), and so on for
// `depth` levels: (9^(depth+1) - 1) / 8 spheres. A floor square lies below.
//
// Size mapping: the deepest level (0..6) whose spheres still get at least
// 8 segments (48 triangles) each within `size`, then the most segments
// (even, 4..256) that keep the total within `size`.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "scene/tessellate.h"
#include "scenes/gen/gen_common.h"

namespace kdrt::gen {

namespace {

constexpr int kMaxDepth = 6;
constexpr int kFloorTriangles = 2;

long SpheresUpTo(int depth) {
  long n = 0, level = 1;
  for (int d = 0; d <= depth; ++d, level *= 9) n += level;
  return n;
}

const glm::vec3 kLevelColors[] = {
    {0.85f, 0.65f, 0.25f}, {0.75f, 0.3f, 0.25f}, {0.3f, 0.6f, 0.35f}, {0.3f, 0.4f, 0.8f},
    {0.7f, 0.4f, 0.75f},   {0.4f, 0.75f, 0.75f}, {0.9f, 0.9f, 0.9f},
};

void AddFlake(SceneBuilder& b, const glm::dvec3& centre, double radius, const glm::dvec3& axis,
              int level, int depth, int segments) {
  b.SetColor(kLevelColors[level]);
  AddSphere(b, centre, radius, segments);
  if (level == depth) return;
  glm::dvec3 u, v;
  MakeFrame(axis, &u, &v);
  const double child_r = radius / 3.0;
  const double dist = radius + child_r;
  for (int i = 0; i < 9; ++i) {
    // Six at 10 degrees above the equator, 60 degrees apart; three at 55
    // degrees, between them.
    double elevation = (i < 6 ? 10.0 : 55.0) * kPi / 180.0;
    double azimuth = (i < 6 ? 60.0 * i : 30.0 + 120.0 * (i - 6)) * kPi / 180.0;
    glm::dvec3 dir = std::cos(elevation) * (std::cos(azimuth) * u + std::sin(azimuth) * v) +
                     std::sin(elevation) * axis;
    dir = glm::normalize(dir);
    AddFlake(b, centre + dist * dir, child_r, dir, level + 1, depth, segments);
  }
}

}  // namespace

Scene GenerateBalls(int size) {
  int depth = 0;
  while (depth < kMaxDepth && SpheresUpTo(depth + 1) * SphereTriangleCount(8) + kFloorTriangles <=
                                  size) {
    ++depth;
  }
  const long spheres = SpheresUpTo(depth);
  int segments = 4;
  while (segments < 256 &&
         spheres * SphereTriangleCount(segments + 2) + kFloorTriangles <= size) {
    segments += 2;
  }

  Scene scene;
  scene.background = glm::vec3(0.05f, 0.07f, 0.12f);
  SceneBuilder b(&scene);
  AddFlake(b, glm::dvec3(0.0), 1.0, glm::dvec3(0, 0, 1), 0, depth, segments);
  // Framed on the flake alone, as SPD's view looks at the balls.
  scene.camera = FramingCamera(scene, {2.1, 1.3, 1.7}, glm::vec3(0, 0, 1), 45.0);
  // The flake stays within distance 2 of the origin (1 + 2/3 + 2/9 + ...).
  b.SetColor(glm::vec3(0.6f, 0.6f, 0.6f));
  AddGrid(b, {-4, -4, -2}, {8, 0, 0}, {0, 8, 0}, 1, 1);
  return scene;
}

}  // namespace kdrt::gen
