// "hoops": Haines' SPD "rings" scene as kdrt's NFF loader sees it, with the
// cylinders long and thin. A cluster is six pentagonal hoops of
// circumradius 1 around one centre, each in the plane normal to one of the
// six five-fold axes of an icosahedron, so every hoop passes through the
// others; a hoop is five NFF cylinders (`c`, radius 1/50 of their length)
// with an NFF sphere (`s`, the same radius) at every corner. The clusters
// form a square pyramid of layers (layer L holds (L+1)^2 of them, 2 apart,
// the layers 2.6 apart) that the camera looks into from beyond its apex, with a
// backdrop behind the last layer.
//
// The primitives are tessellated exactly as the NFF loader tessellates
// `c` and `s` (AddCone, AddSphere with S segments; the loader's default is
// 16), with the loader's cone_aspect: by default each cylinder is one band
// of S quads from end to end, slivers about 130 times longer than wide at
// S = 16. Their boxes span cells they barely touch, the case that makes
// kd-tree leaves large (docs/kdtree.md, "Long thin cylinders"); with
// cone_aspect A the cylinders are cut into bands of cells at most A times
// longer than wide.
//
// Size mapping: the most layers D whose D(D+1)(2D+1)/6 clusters of 30
// cylinders and 30 spheres at S = 16 and one band (7680 triangles a
// cluster) fit in `size` (at least one layer), then the largest S (3..64)
// that keeps the total within it with the cylinders' bands. Sizes below one
// cluster at S = 3 get a single cluster of fewer hoops.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "scene/tessellate.h"
#include "scenes/gen/gen_common.h"

namespace kdrt::gen {

namespace {

constexpr int kBackdropTriangles = 2;
constexpr int kHoopsPerCluster = 6;
constexpr int kCorners = 5;
constexpr double kLengthPerRadius = 50.0;
constexpr double kClusterSpacing = 2.0;
constexpr double kLayerSpacing = 2.6;

long ClustersFor(long layers) { return layers * (layers + 1) * (2 * layers + 1) / 6; }
// A hoop's side (the length of each of its cylinders) at circumradius 1.
double HoopEdge() { return 2.0 * std::sin(kPi / kCorners); }
// Every cylinder has the same length and radius, so the same bands.
int CylinderBands(int segments, double aspect) {
  const double edge = HoopEdge();
  return ConeBands(glm::dvec3(0.0), edge / kLengthPerRadius, glm::dvec3(edge, 0.0, 0.0), edge / kLengthPerRadius,
                   segments, aspect);
}
long HoopTriangles(int segments, double aspect) {
  return kCorners * (2L * segments * CylinderBands(segments, aspect) + SphereTriangleCount(segments));
}
long ClusterTriangles(int segments, double aspect) { return kHoopsPerCluster * HoopTriangles(segments, aspect); }

}  // namespace

Scene GenerateHoops(int size, const LoadOptions& tessellation) {
  const double aspect = tessellation.cone_aspect;
  long layers = 1;
  // The layers as for one band, so that every cone_aspect gives the same
  // hoops at a size, tessellated into about as many triangles.
  while (ClustersFor(layers + 1) * ClusterTriangles(16, 0.0) + kBackdropTriangles <= size) ++layers;
  const long clusters = ClustersFor(layers);
  // Below one cluster at S = 3, fewer hoops (at least one).
  int hoops = kHoopsPerCluster;
  while (hoops > 1 && hoops * HoopTriangles(3, aspect) + kBackdropTriangles > size) --hoops;
  int segments = 3;
  while (segments < 64 && clusters * hoops * HoopTriangles(segments + 1, aspect) + kBackdropTriangles <= size) {
    ++segments;
  }

  // The five-fold axes of an icosahedron (its vertices), one of each
  // opposite pair.
  const double phi = 0.5 * (1.0 + std::sqrt(5.0));
  const glm::dvec3 axes[kHoopsPerCluster] = {{0, 1, phi}, {0, -1, phi}, {1, phi, 0},
                                             {-1, phi, 0}, {phi, 0, 1}, {-phi, 0, 1}};
  const double radius = HoopEdge() / kLengthPerRadius;
  const int bands = CylinderBands(segments, aspect);
  // Corners of the six hoops of a cluster centred at the origin.
  glm::dvec3 corner[kHoopsPerCluster][kCorners];
  for (int h = 0; h < kHoopsPerCluster; ++h) {
    glm::dvec3 u, v;
    MakeFrame(glm::normalize(axes[h]), &u, &v);
    for (int c = 0; c < kCorners; ++c) {
      const double a = 2.0 * kPi * c / kCorners;
      corner[h][c] = std::cos(a) * u + std::sin(a) * v;
    }
  }
  const glm::vec3 colors[kHoopsPerCluster] = {{0.9f, 0.2f, 0.2f}, {0.2f, 0.8f, 0.25f}, {0.25f, 0.35f, 0.9f},
                                              {0.2f, 0.8f, 0.8f}, {0.8f, 0.25f, 0.8f}, {0.85f, 0.8f, 0.2f}};

  Scene scene;
  scene.background = glm::vec3(0.08f, 0.36f, 0.75f);
  SceneBuilder b(&scene);
  for (long layer = 0; layer < layers; ++layer) {
    const double y = kLayerSpacing * static_cast<double>(layer + 1);
    for (long iz = 0; iz <= layer; ++iz) {
      for (long ix = 0; ix <= layer; ++ix) {
        const glm::dvec3 centre(kClusterSpacing * (ix - 0.5 * layer), y, kClusterSpacing * (iz - 0.5 * layer));
        for (int h = 0; h < hoops; ++h) {
          b.SetColor(colors[h]);
          for (int c = 0; c < kCorners; ++c) {
            const glm::dvec3 p = centre + corner[h][c];
            AddCone(b, p, radius, centre + corner[h][(c + 1) % kCorners], radius, segments, bands);
            AddSphere(b, p, radius, segments);
          }
        }
      }
    }
  }
  // Beyond the pyramid's apex, looking along +y into it (45 degrees spans
  // about the layers' width at every depth).
  Camera cam;
  cam.from = glm::vec3(-0.6f, static_cast<float>(-kLayerSpacing), 0.4f);
  cam.at = glm::vec3(-0.6f, static_cast<float>(1.0 - kLayerSpacing), 0.4f);
  cam.up = glm::vec3(0.0f, 0.0f, 1.0f);
  cam.angle_deg = 45.0f;
  cam.hither = 0.0f;
  cam.width = kDefaultResolution;
  cam.height = kDefaultResolution;
  scene.camera = cam;
  const double back_y = kLayerSpacing * static_cast<double>(layers + 1);
  const double half = 0.5 * kClusterSpacing * static_cast<double>(layers) + 1.5;
  b.SetColor(glm::vec3(1.0f, 1.0f, 1.0f));
  AddGrid(b, {-half, back_y, -half}, {0, 0, 2 * half}, {2 * half, 0, 0}, 1, 1);
  return scene;
}

}  // namespace kdrt::gen
