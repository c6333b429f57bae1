// Shading a frame from its hit records, and the secondary ray sets that
// shading needs (docs/shading.md).
//
// A frame is traced in passes: the primary rays; from their hits the shadow
// rays (one any-hit query to each light in front of the surface), and on
// request ambient-occlusion rays (any-hit, a short cosine-weighted
// hemisphere) and one diffuse bounce ray (closest hit) per hit. The image is
// a pure function of the rays and of every pass's hit records, so a frame
// whose hit records are the reference's bit for bit (kdrt sim) is the
// reference's image byte for byte. Random numbers come from a counter-based
// hash of (seed, pixel, sample): the ray sets do not depend on thread count
// or order.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/ray.h"
#include "scene/scene.h"

namespace kdrt {

struct ShadingOptions {
  int ao_samples = 0;   // ambient-occlusion rays per hit (0: none)
  bool bounce = false;  // one diffuse bounce ray per hit
  uint32_t seed = 1;
};

// One pass of a frame: its rays and, for each, the primary ray it serves.
struct RayPass {
  std::string name;  // "primary", "shadow", "ao", "bounce"
  Query query = Query::kClosest;
  std::vector<Ray> rays;
  std::vector<uint32_t> pixel;   // index of the primary ray
  std::vector<uint16_t> sample;  // light index (shadow) or sample number (ao)
};

// The lights shading uses: the scene's `l` lines, else one white light
// above and to the right of the camera (scene's own, else the automatic
// one): from + 0.25 * diagonal * (up + right), diagonal of the scene box.
std::vector<Light> ShadingLights(const Scene& scene);

class FrameShader {
 public:
  FrameShader(const Scene& scene, const ShadingOptions& options);

  // The secondary passes for the primary rays and their hits, in the order
  // shadow, ao (if ao_samples > 0), bounce (if bounce). Every pass is
  // returned, even when it has no rays.
  std::vector<RayPass> SecondaryPasses(const std::vector<Ray>& primary, const std::vector<Hit>& primary_hits) const;

  // RGB per primary ray (row 0 at the top for a camera frame). `hits[k]`
  // are the records of `passes[k]`.
  std::vector<float> Shade(const std::vector<Ray>& primary, const std::vector<Hit>& primary_hits,
                           const std::vector<RayPass>& passes, const std::vector<std::vector<Hit>>& hits) const;

  const std::vector<Light>& lights() const { return lights_; }
  float offset() const { return offset_; }

 private:
  struct Surface;
  Surface SurfaceAt(const Ray& ray, const Hit& hit) const;

  const Scene& scene_;
  ShadingOptions options_;
  std::vector<Light> lights_;
  std::vector<glm::vec3> intensity_;  // per light
  float offset_ = 0;                  // origin offset along the normal
  float ao_radius_ = 0;
};

}  // namespace kdrt
