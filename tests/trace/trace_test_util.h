// Shared helpers for the trace tests: scenes, camera rays, brute force.
#pragma once

#include <cmath>
#include <random>
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
  best.u = best.v = a.Zero();
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

// A world-space ray whose framed origin is exactly `framed_o` (the frame
// subtracts the origin in fp32 and scales by a power of two); false if no
// float nearby maps there.
inline bool RayAtFramedPoint(const Frame& f, const glm::vec3& framed_o, const glm::vec3& d, Ray* out) {
  Ray r{glm::vec3(0.0f), d, 0.0f, INFINITY};
  for (int i = 0; i < 3; ++i) {
    r.o[i] = static_cast<float>(double(f.origin[i]) + std::ldexp(double(framed_o[i]), -f.scale_log2));
  }
  for (int attempt = 0; attempt < 8; ++attempt) {
    const FramedRay fr = ToFrame(r, f);
    bool exact = true;
    for (int i = 0; i < 3; ++i) {
      if (fr.ray.o[i] == framed_o[i]) continue;
      exact = false;
      r.o[i] = std::nextafter(r.o[i], fr.ray.o[i] < framed_o[i] ? INFINITY : -INFINITY);
    }
    if (exact) {
      *out = r;
      return true;
    }
  }
  return false;
}

// Rays lying in the tree's split planes: a zero direction component and the
// origin exactly on the plane, so the split distance is 0 x inf = NaN
// (InPlane in trace/traversal.h). A triangle touching the plane from one side
// is listed in that side's child only, so such a ray must see both children
// and may stop in neither before it has seen the other. Planes of every inner
// node down to depth 4 and a sample below; per plane, rays across it at
// random and along the axes, from points on the plane around the scene.
inline std::vector<Ray> SplitPlaneRays(const ImageView& image, uint32_t seed) {
  const img::Header& h = image.header();
  const Frame frame = image.frame();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::normal_distribution<float> gauss;
  std::vector<Ray> rays;
  struct Visit {
    uint32_t node;
    int depth;
  };
  std::vector<Visit> todo{{0, 0}};
  size_t inner = 0;
  while (!todo.empty()) {
    const Visit v = todo.back();
    todo.pop_back();
    const img::Node n = image.node(v.node);
    if (n.IsLeaf()) continue;
    todo.push_back({image.next(v.node), v.depth + 1});
    todo.push_back({n.AboveChild(), v.depth + 1});
    if (v.depth > 4 && ++inner % 8 != 0) continue;
    const int k = static_cast<int>(n.Axis()), a = (k + 1) % 3, b = (k + 2) % 3;
    for (int i = 0; i < 4; ++i) {
      glm::vec3 o;
      o[k] = n.Split();
      for (int j : {a, b}) o[j] = h.bounds_min[j] + (h.bounds_max[j] - h.bounds_min[j]) * (1.2f * u01(rng) - 0.1f);
      glm::vec3 d(0.0f);
      if (i < 2) {
        d[a] = gauss(rng);
        d[b] = gauss(rng);
      } else {
        d[i == 2 ? a : b] = u01(rng) < 0.5f ? -1.0f : 1.0f;
      }
      Ray r;
      if (RayAtFramedPoint(frame, o, d, &r)) rays.push_back(r);
    }
  }
  return rays;
}

using kdrt::SameBits;  // trace/hit_compare.h

}  // namespace kdrt::testing
