// "rings": tori in concentric pentagonal rings, z up. Ring 0 is one flat
// torus at the origin; ring k (1..K) holds 5k tori on a circle of radius k,
// so neighbours in every ring are the same distance d = 2 pi / 5 apart.
// Tori alternate between flat (axis z) and upright (axis radial), which
// makes neighbours interlink like chain links; odd rings sit a little
// higher so adjacent rings clear each other. A floor square lies below.
//
// Size mapping: the most rings K whose 1 + 5K(K+1)/2 tori still get
// m = 6 tube segments (2m x m cells, 4 m^2 = 144 triangles) each within
// `size`, then the largest m (3..64) that keeps the total within `size`.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "scene/tessellate.h"
#include "scenes/gen/gen_common.h"

namespace kdrt::gen {

namespace {

constexpr int kFloorTriangles = 2;

long ToriFor(long rings) { return 1 + 5 * rings * (rings + 1) / 2; }
long TorusTriangles(long m) { return 4 * m * m; }

}  // namespace

Scene GenerateRings(int size) {
  long rings = 0;
  while (ToriFor(rings + 1) * TorusTriangles(6) + kFloorTriangles <= size) ++rings;
  const long tori = ToriFor(rings);
  int m = 3;
  while (m < 64 && tori * TorusTriangles(m + 1) + kFloorTriangles <= size) ++m;

  const double d = 2.0 * kPi / 5.0;
  const double major_r = 0.6 * d;
  const double minor_r = 0.1 * d;
  const glm::vec3 colors[] = {{0.8f, 0.25f, 0.2f}, {0.9f, 0.7f, 0.2f}, {0.25f, 0.6f, 0.3f},
                              {0.25f, 0.45f, 0.85f}, {0.65f, 0.35f, 0.75f}};

  Scene scene;
  scene.background = glm::vec3(0.1f, 0.1f, 0.15f);
  SceneBuilder b(&scene);
  b.SetColor(colors[0]);
  AddTorus(b, glm::dvec3(0.0), glm::dvec3(0, 0, 1), major_r, minor_r, 2 * m, m);
  for (long k = 1; k <= rings; ++k) {
    b.SetColor(colors[k % 5]);
    const long count = 5 * k;
    const double height = (k % 2 == 1) ? 0.5 * d : 0.0;
    for (long i = 0; i < count; ++i) {
      double a = 2.0 * kPi * i / count;
      glm::dvec3 radial(std::cos(a), std::sin(a), 0.0);
      glm::dvec3 centre = static_cast<double>(k) * radial + glm::dvec3(0, 0, height);
      glm::dvec3 axis = (i % 2 == 0) ? glm::dvec3(0, 0, 1) : radial;
      AddTorus(b, centre, axis, major_r, minor_r, 2 * m, m);
    }
  }
  scene.camera = FramingCamera(scene, {0.0, -2.2, 1.6}, glm::vec3(0, 0, 1), 45.0);
  const double extent = rings + 2.0;
  b.SetColor(glm::vec3(0.6f, 0.6f, 0.6f));
  const double floor_z = -major_r - minor_r - 0.05 * d;
  AddGrid(b, {-extent, -extent, floor_z}, {2 * extent, 0, 0}, {0, 2 * extent, 0}, 1, 1);
  return scene;
}

}  // namespace kdrt::gen
