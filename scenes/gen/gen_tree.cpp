// "tree": a trunk that splits into three branches, each of which splits
// again, `depth` times, y up. A branch is an open tapered cylinder (cone
// frustum) with c sides, 2c triangles; children are 0.7 times as long,
// tilted 35 degrees out and turned by the golden angle per level so the
// crown fills out without randomness. Every tip carries four leaves (two
// triangles each). A floor square lies below.
//
// Size mapping: the deepest level (0..12) whose (3^(depth+1) - 1) / 2
// branches with 3 sides plus 8 leaf triangles per tip fit in `size`, then
// the most sides c (3..32) that still fit.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "scene/tessellate.h"
#include "scenes/gen/gen_common.h"

namespace kdrt::gen {

namespace {

constexpr int kMaxDepth = 12;
constexpr int kBranching = 3;
constexpr int kLeavesPerTip = 4;
constexpr int kFloorTriangles = 2;

long Pow3(int n) {
  long p = 1;
  while (n-- > 0) p *= 3;
  return p;
}

long TreeTriangles(int depth, int sides) {
  long branches = (Pow3(depth + 1) - 1) / 2;
  long tips = Pow3(depth);
  return branches * 2 * sides + tips * kLeavesPerTip * 2 + kFloorTriangles;
}

struct TreeShape {
  int depth;
  int sides;
  glm::vec3 bark{0.45f, 0.3f, 0.18f};
  glm::vec3 leaf{0.2f, 0.6f, 0.2f};
};

void AddLeaves(SceneBuilder& b, const TreeShape& shape, const glm::dvec3& tip,
               const glm::dvec3& dir, double length) {
  glm::dvec3 u, v;
  MakeFrame(dir, &u, &v);
  b.SetColor(shape.leaf);
  for (int j = 0; j < kLeavesPerTip; ++j) {
    double a = (0.25 + j) * 2.0 * kPi / kLeavesPerTip;
    glm::dvec3 out = glm::normalize(std::cos(a) * u + std::sin(a) * v + 0.5 * dir);
    glm::dvec3 side = glm::normalize(glm::cross(out, dir));
    glm::vec3 quad[4] = {glm::vec3(tip), glm::vec3(tip + 0.5 * length * out + 0.25 * length * side),
                         glm::vec3(tip + length * out),
                         glm::vec3(tip + 0.5 * length * out - 0.25 * length * side)};
    b.AddFan(quad, 4);
  }
}

void AddBranch(SceneBuilder& b, const TreeShape& shape, const glm::dvec3& base,
               const glm::dvec3& dir, double length, double radius, double twist, int level) {
  const glm::dvec3 tip = base + length * dir;
  const double tip_radius = 0.65 * radius;
  b.SetColor(shape.bark);
  AddCone(b, base, radius, tip, tip_radius, shape.sides);
  if (level == shape.depth) {
    AddLeaves(b, shape, tip, dir, 0.6 * length);
    return;
  }
  glm::dvec3 u, v;
  MakeFrame(dir, &u, &v);
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  const double tilt = 35.0 * kPi / 180.0;
  for (int i = 0; i < kBranching; ++i) {
    double azimuth = twist + 2.0 * kPi * i / kBranching;
    glm::dvec3 across = std::cos(azimuth) * u + std::sin(azimuth) * v;
    glm::dvec3 child = glm::normalize(std::cos(tilt) * dir + std::sin(tilt) * across);
    AddBranch(b, shape, tip, child, 0.7 * length, tip_radius, twist + golden, level + 1);
  }
}

}  // namespace

Scene GenerateTree(int size) {
  TreeShape shape;
  shape.depth = 0;
  while (shape.depth < kMaxDepth && TreeTriangles(shape.depth + 1, 3) <= size) ++shape.depth;
  shape.sides = 3;
  while (shape.sides < 32 && TreeTriangles(shape.depth, shape.sides + 1) <= size) ++shape.sides;

  Scene scene;
  scene.background = glm::vec3(0.55f, 0.7f, 0.9f);
  SceneBuilder b(&scene);
  AddBranch(b, shape, glm::dvec3(0.0), glm::dvec3(0, 1, 0), 1.0, 0.08, 0.0, 0);
  scene.camera = FramingCamera(scene, {0.3, 0.25, 1.0}, glm::vec3(0, 1, 0), 45.0);
  b.SetColor(glm::vec3(0.35f, 0.3f, 0.2f));
  AddGrid(b, {-4, 0, 4}, {8, 0, 0}, {0, 0, -8}, 1, 1);
  return scene;
}

}  // namespace kdrt::gen
