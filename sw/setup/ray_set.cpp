#include "setup/ray_set.h"

#include <cmath>
#include <sstream>

#include "common/error.h"
#include "scene/camera.h"
#include "trace/rays_file.h"

namespace kdrt {
namespace {

void ParseResolution(const std::string& res, int* w, int* h) {
  char x = 0;
  std::istringstream in(res);
  if (!(in >> *w >> x >> *h) || x != 'x' || *w < 1 || *h < 1 || *w > 65536 || *h > 65536 || !in.eof()) {
    throw InputError("--res " + QuoteBytes(res) + ": expected WxH with 1 <= W, H <= 65536, e.g. 512x512");
  }
  const long long pixels = static_cast<long long>(*w) * *h;
  if (pixels > kMaxCameraPixels) {
    throw InputError("--res " + res + ": " + std::to_string(pixels) + " camera rays; at most " +
                     std::to_string(kMaxCameraPixels) + " per frame (8192x8192)");
  }
}

Camera ParseCamera(const std::string& text, const Camera& base) {
  std::istringstream in(text);
  float f[10];
  for (float& v : f) {
    if (!(in >> v) || !std::isfinite(v)) {
      throw InputError("--camera '" + text + "': expected 10 finite numbers: from(3) at(3) up(3) angle");
    }
  }
  Camera c = base;
  c.from = {f[0], f[1], f[2]};
  c.at = {f[3], f[4], f[5]};
  c.up = {f[6], f[7], f[8]};
  c.angle_deg = f[9];
  if (!(c.angle_deg > 0 && c.angle_deg < 180)) throw InputError("--camera: angle must lie in (0, 180) degrees");
  return c;
}

}  // namespace

RaySet MakeRays(const Scene& scene, const std::string& rays_file, const std::string& camera, const std::string& res) {
  RaySet set;
  if (!rays_file.empty()) {
    set.rays = ReadRaysFile(rays_file, &set.query);
    set.width = static_cast<int>(set.rays.size());
    return set;
  }
  // --camera replaces the automatic camera as a whole: it is not computed
  // then (a scene too large for it is fine with an explicit camera).
  Camera cam = scene.camera ? *scene.camera : camera.empty() ? AutoCamera(scene, 512, 512) : Camera{};
  if (!camera.empty()) cam = ParseCamera(camera, cam);
  if (!res.empty()) ParseResolution(res, &cam.width, &cam.height);
  set.width = cam.width;
  set.height = cam.height;
  set.rays.reserve(static_cast<size_t>(cam.width) * cam.height);
  for (int y = 0; y < cam.height; ++y) {
    for (int x = 0; x < cam.width; ++x) {
      const CameraRay cr = PrimaryRay(cam, x, y);
      set.rays.push_back(Ray{cr.o, cr.d, cr.tmin, INFINITY});
    }
  }
  return set;
}

}  // namespace kdrt
