#include "scene/scene.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "common/error.h"
#include "scene/loaders.h"
#include "scene/tessellate.h"

namespace kdrt {

namespace {

constexpr int kMaxSegments = 4096;

std::string LowerExtension(const std::string& path) {
  size_t slash = path.find_last_of('/');
  size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

Scene LoadScene(const std::string& path) { return LoadScene(path, LoadOptions()); }

Scene LoadScene(const std::string& path, const LoadOptions& options) {
  if (options.sphere_segments < 3 || options.sphere_segments > kMaxSegments ||
      options.cone_segments < 3 || options.cone_segments > kMaxSegments) {
    throw InputError(path, 0,
                     "sphere and cone segments must be in 3.." + std::to_string(kMaxSegments));
  }
  if (!IsValidConeAspect(options.cone_aspect)) {
    throw InputError(path, 0, kConeAspectRule);
  }
  std::string ext = LowerExtension(path);
  Scene scene;
  if (ext == "nff") {
    scene = LoadNff(path, options);
  } else if (ext == "obj") {
    scene = LoadObj(path, options);
  } else if (ext == "ply") {
    scene = LoadPly(path, options);
  } else if (ext == "off") {
    scene = LoadOff(path, options);
  } else {
    throw InputError(path, 0,
                     "unknown scene file extension " + QuoteBytes(ext) +
                         " (expected .nff, .obj, .ply, .off)");
  }
  // The one check of the scene as a whole, for every format. Coordinates were
  // checked as they were read (RequireFinite), where the line is known.
  if (scene.triangles.empty()) throw InputError(path, 0, "scene has no triangles");
  // Zero-area triangles are never hit: a scene of nothing else is as empty.
  if (std::all_of(scene.triangles.begin(), scene.triangles.end(), IsDegenerate)) {
    throw InputError(path, 0,
                     "scene has no triangle with an area (all " + std::to_string(scene.triangles.size()) +
                         " are degenerate: zero area in float)");
  }
  return scene;
}

void IgnoredData(Scene* scene, const LoadOptions& options, const std::string& file, int line,
                 const std::string& what) {
  if (options.strict) throw InputError(file, line, what + " (--strict)");
  scene->warnings.push_back(InputError(file, line, what).what());
}

bool IsDegenerate(const Triangle& t) {
  const glm::vec3 e1 = t.v1 - t.v0;
  const glm::vec3 e2 = t.v2 - t.v0;
  const float cx = e1.y * e2.z - e1.z * e2.y;
  const float cy = e1.z * e2.x - e1.x * e2.z;
  const float cz = e1.x * e2.y - e1.y * e2.x;
  return cx == 0.0f && cy == 0.0f && cz == 0.0f;
}

}  // namespace kdrt
