// The rays a command traces: the ray file if given, else one ray per pixel
// centre of the scene's camera (or the automatic one), with --camera and
// --res applied.
#pragma once

#include <string>
#include <vector>

#include "common/ray.h"
#include "scene/scene.h"

namespace kdrt {

// width x height is the image (count x 1 for a ray file).
struct RaySet {
  std::vector<Ray> rays;
  int width = 0;
  int height = 1;
  Query query = Query::kClosest;  // a ray file's (shadow rays: kAny)
};

// Throws InputError on a malformed --res or --camera, or a bad ray file.
RaySet MakeRays(const Scene& scene, const std::string& rays_file, const std::string& camera, const std::string& res);

}  // namespace kdrt
