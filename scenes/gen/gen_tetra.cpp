// "tetra": a Sierpinski tetrahedron. A regular tetrahedron (corners
// (1,1,1), (1,-1,-1), (-1,1,-1), (-1,-1,1)) is replaced by the four
// half-size tetrahedra at its corners, `depth` times: 4^depth tetrahedra,
// 4^(depth+1) triangles. Corners are exact binary fractions, so every
// coordinate is exact in float. A floor square lies below.
//
// Size mapping: depth = round(log4(size / 4)), clamped to 0..11, so the
// count is within a factor of two of `size` (from size 4 on).
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "scene/tessellate.h"
#include "scenes/gen/gen_common.h"

namespace kdrt::gen {

namespace {

constexpr int kMaxDepth = 11;

const glm::vec3 kCornerColors[] = {
    {0.85f, 0.3f, 0.25f}, {0.3f, 0.75f, 0.35f}, {0.3f, 0.45f, 0.9f}, {0.9f, 0.8f, 0.3f}};

void AddFace(SceneBuilder& b, const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
             const glm::dvec3& opposite) {
  // Wind the face so its normal points away from the fourth corner.
  glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
  if (glm::dot(n, opposite - p0) > 0.0) {
    b.AddTriangle(glm::vec3(p0), glm::vec3(p2), glm::vec3(p1));
  } else {
    b.AddTriangle(glm::vec3(p0), glm::vec3(p1), glm::vec3(p2));
  }
}

void AddSierpinski(SceneBuilder& b, const glm::dvec3 (&c)[4], int depth) {
  if (depth == 0) {
    AddFace(b, c[0], c[1], c[2], c[3]);
    AddFace(b, c[0], c[1], c[3], c[2]);
    AddFace(b, c[0], c[2], c[3], c[1]);
    AddFace(b, c[1], c[2], c[3], c[0]);
    return;
  }
  for (int keep = 0; keep < 4; ++keep) {
    glm::dvec3 sub[4];
    for (int j = 0; j < 4; ++j) sub[j] = 0.5 * (c[keep] + c[j]);
    AddSierpinski(b, sub, depth - 1);
  }
}

}  // namespace

Scene GenerateTetra(int size) {
  int depth = static_cast<int>(std::lround(std::log(std::max(1.0, size / 4.0)) / std::log(4.0)));
  depth = std::clamp(depth, 0, kMaxDepth);

  Scene scene;
  scene.background = glm::vec3(0.08f, 0.08f, 0.1f);
  SceneBuilder b(&scene);
  const glm::dvec3 corners[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  if (depth == 0) {
    b.SetColor(kCornerColors[0]);
    AddSierpinski(b, corners, 0);
  } else {
    for (int keep = 0; keep < 4; ++keep) {
      b.SetColor(kCornerColors[keep]);
      glm::dvec3 sub[4];
      for (int j = 0; j < 4; ++j) sub[j] = 0.5 * (corners[keep] + corners[j]);
      AddSierpinski(b, sub, depth - 1);
    }
  }
  scene.camera = FramingCamera(scene, {1.6, 1.1, 2.6}, glm::vec3(0, 1, 0), 45.0);
  b.SetColor(glm::vec3(0.55f, 0.55f, 0.55f));
  AddGrid(b, {-4, -1.25, 4}, {8, 0, 0}, {0, 0, -8}, 1, 1);
  return scene;
}

}  // namespace kdrt::gen
