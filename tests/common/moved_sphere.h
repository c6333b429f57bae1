// The extremes of docs/precision.md as test inputs, shared by the trace and
// the sim tests.
#pragma once

#include <vector>

#include "common/ray.h"
#include "scene/scene.h"
#include "trace/watertight.h"

namespace kdrt::testing {

// The closed sphere of `kdrt rays` (16 x 32, 960 triangles) and its
// watertightness rays, every point mapped to p * scale + offset (on each
// axis) and directions scaled, each coordinate rounded to float once so the
// mesh stays closed: the extremes of docs/precision.md.
struct MeshAndRays {
  Scene scene;
  std::vector<Ray> rays;
};
inline MeshAndRays MovedSphere(double offset, double scale) {
  MeshAndRays m{ClosedSphereMesh(16, 32), {}};
  m.rays = WatertightRays(m.scene, 1);
  auto move = [&](glm::vec3& p) {
    for (int i = 0; i < 3; ++i) p[i] = static_cast<float>(p[i] * scale + offset);
  };
  for (Triangle& t : m.scene.triangles) {
    move(t.v0);
    move(t.v1);
    move(t.v2);
  }
  for (Ray& r : m.rays) {
    move(r.o);
    for (int i = 0; i < 3; ++i) r.d[i] = static_cast<float>(r.d[i] * scale);
  }
  return m;
}

// The unit sphere and its rays beside one large triangle `distance` away
// ("a teapot in a stadium"): the image's frame spans the stadium, so the
// sphere's detail is a few units of the last place of a narrow format and
// its vertices collapse there. (An offset or a scale alone no longer breaks
// any format: the frame removes it.)
inline MeshAndRays SphereInStadium(double distance) {
  MeshAndRays m = MovedSphere(0, 1);
  const float d = static_cast<float>(distance);
  m.scene.triangles.push_back({{d, -d, -d}, {d, d, -d}, {d, 0.0f, d}});
  m.scene.material.push_back(0);
  return m;
}

}  // namespace kdrt::testing
