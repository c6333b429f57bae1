// Embree 3 as an independent oracle for tests and benchmarks: the same
// triangles in an Embree scene, traced one ray at a time with rtcIntersect1 or in packets
// (rtcIntersect4/8/16) for the speed benchmark.
#pragma once

#include <memory>
#include <vector>

#include "common/ray.h"
#include "scene/scene.h"

namespace kdrt {

class EmbreeScene {
 public:
  // Builds with RTC_BUILD_QUALITY_HIGH; `threads` limits Embree's build
  // threads (1 for single-thread comparisons). `robust` sets
  // RTC_SCENE_FLAG_ROBUST: without it Embree's fast test lets rays slip
  // through shared edges of closed meshes (seen on the room scene), so the
  // oracle tests use it and the speed benchmark does not.
  explicit EmbreeScene(const Scene& scene, int threads = 1, bool robust = true);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  double build_seconds() const { return build_seconds_; }
  // prim = triangle id in scene order, u/v = weights of v1/v2.
  Hit Intersect(const Ray& ray) const;
  // rays[0..n) (n <= width) as one packet: rtcIntersect4, 8 or 16.
  void IntersectPacket(const Ray* rays, int n, int width, Hit* out) const;
  // Shadow queries: whether anything lies in [tmin, tmax] (rtcOccluded1, and
  // rtcOccluded4, 8 or 16 for a packet).
  bool Occluded(const Ray& ray) const;
  void OccludedPacket(const Ray* rays, int n, int width, bool* out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double build_seconds_ = 0;
};

}  // namespace kdrt
