#include "setup/trace_outputs.h"

#include <fstream>

#include "common/error.h"
#include "trace/images.h"

namespace kdrt {

std::string DefaultImageName(const std::string& scene, bool from_rays_file) {
  if (from_rays_file) return "";
  if (scene.rfind("gen:", 0) == 0) {
    std::string s = scene.substr(4);
    for (char& c : s) c = c == ':' ? '_' : c;
    return s + ".png";
  }
  const size_t slash = scene.find_last_of('/');
  std::string base = scene.substr(slash == std::string::npos ? 0 : slash + 1);
  const size_t dot = base.find_last_of('.');
  return base.substr(0, dot) + ".png";
}

void AddJsonOutput(OutputSet& outputs, const std::string& path, const nlohmann::json& json) {
  outputs.Add(path, [&](const std::string& tmp) {
    std::ofstream f(tmp);
    f << json.dump(2) << "\n";
    if (!f) throw InputError(path, 0, "cannot write JSON stats");
  });
}

void AddTraceOutputs(OutputSet& outputs, const Scene& scene, const RaySet& rays, const std::vector<Hit>& hits,
                     const std::string& image_path, const std::string& hits_path, const std::string& json_path,
                     const nlohmann::json& stats, const std::vector<float>* shaded) {
  if (!image_path.empty()) {
    const std::vector<float> rgb = shaded ? *shaded : ShadeEyeLight(scene, rays.rays, hits);
    outputs.Add(image_path, [&](const std::string& tmp) { WriteRgbImage(tmp, rays.width, rays.height, rgb); });
  }
  if (!hits_path.empty()) {
    outputs.Add(hits_path, [&](const std::string& tmp) { WriteHitBuffer(tmp, rays.width, rays.height, hits); });
  }
  if (!json_path.empty()) AddJsonOutput(outputs, json_path, stats);
}

}  // namespace kdrt
