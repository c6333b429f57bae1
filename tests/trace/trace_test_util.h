// Shared helpers for the trace tests: scenes, camera rays, brute force.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "accel/kdtree.h"
#include "common/ray.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "scenes/gen/generators.h"
#include "trace/memory_image.h"
#include "trace/tracer.h"
#include "trace/traversal.h"
#include "trace/hit_compare.h"
#include "tests/common/moved_sphere.h"

namespace kdrt::testing {

inline std::vector<Ray> CameraRays(const Scene& scene, int res) {
  Camera cam = scene.camera ? *scene.camera : AutoCamera(scene, res, res);
  cam.width = cam.height = res;
  std::vector<Ray> rays;
  for (int y = 0; y < res; ++y) {
    for (int x = 0; x < res; ++x) {
      const CameraRay cr = PrimaryRay(cam, x, y);
      rays.push_back(Ray{cr.o, cr.d, cr.tmin, INFINITY});
    }
  }
  return rays;
}

// A scene with its image (and the tree over its framed copy), kept together
// so views stay valid.
struct Prepared {
  Scene scene;
  FramedImage image;
  std::vector<uint8_t>& bytes = image.bytes;
  explicit Prepared(Scene s, BuildOptions options = {})
      : scene(std::move(s)), image(BuildFramedImage(scene, options)) {}
  ImageView view() const { return ImageView(image.bytes); }
};

// Every triangle tested, same test and same closest-hit rule as the tree.
template <class A>
Hit BruteForce(const A& a, const ImageView& image, const Ray& ray) {
  const FramedRay framed = ToFrame(ray, image.frame());
  const RaySetup<A> r = SetupRay(a, framed.ray);
  TraceResult<A> best;
  best.t_scale_log2 = framed.t_scale_log2;
  best.t = r.tmax;
  for (uint32_t id = 0; id < image.header().tri_count; ++id) {
    const Candidate<A> c = IntersectWatertight(a, r, image.triangle(id), r.tmax);
    if (c.hit && (a.Lt(c.t, best.t) || (a.Eq(c.t, best.t) && id < best.prim))) {
      best.t = c.t;
      best.u = c.u;
      best.v = c.v;
      best.prim = id;
    }
  }
  return ToHit(a, best);
}

using kdrt::SameBits;  // trace/hit_compare.h

}  // namespace kdrt::testing
