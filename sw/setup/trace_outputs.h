// The files a tracing command writes (image, hit buffer, JSON stats), queued
// on an OutputSet so they appear whole or not at all.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/ray.h"
#include "scene/scene.h"
#include "setup/ray_set.h"
#include "trace/output_file.h"

namespace kdrt {

// <scene>.png for a file or gen:NAME:SIZE; empty for a ray file.
std::string DefaultImageName(const std::string& scene_arg, bool from_rays_file);

// Queues `json` as a file at `path`.
void AddJsonOutput(OutputSet& outputs, const std::string& path, const nlohmann::json& json);

// Queues the image (if image_path is set), the hit buffer and the JSON stats
// (if their paths are set) on `outputs`; nothing is renamed into place until
// outputs.Commit(). The image is `shaded` if given (trace/shading.h), else
// eye-light shading of the hits.
void AddTraceOutputs(OutputSet& outputs, const Scene& scene, const RaySet& rays, const std::vector<Hit>& hits,
                     const std::string& image_path, const std::string& hits_path, const std::string& json_path,
                     const nlohmann::json& stats, const std::vector<float>* shaded = nullptr);

}  // namespace kdrt
