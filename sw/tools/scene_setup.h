// What every scene-reading command shares: the scene argument (a file, or
// gen:NAME:SIZE for a procedural scene), the kd-tree options, building the
// tree and the memory image, and reporting them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "accel/kdtree.h"
#include "common/ray.h"
#include "scene/scene.h"
#include "trace/output_file.h"

namespace kdrt::cli {

struct SceneArgs {
  std::string scene;
  std::string accel = "sah";
  int max_depth = -1;
  int max_leaf_prims = 1;
  float isect_cost = 80.0f;
  float traversal_cost = 1.0f;
  float empty_bonus = 0.5f;
  bool perfect_splits = false;
  int sphere_segments = 0;  // 0: loader default
};

void AddSceneOptions(CLI::App& cmd, SceneArgs& args);

struct PreparedScene {
  Scene scene;
  KdTree tree;
  std::vector<uint8_t> image;
  double load_seconds = 0;
};

// Loads (or generates) the scene, builds the tree and the memory image.
PreparedScene PrepareScene(const SceneArgs& args);

// The rays a command traces: the ray file if given, else one ray per pixel
// centre of the scene's camera (or the automatic one), with --camera and
// --res applied. width x height is the image (count x 1 for a ray file).
struct RaySet {
  std::vector<Ray> rays;
  int width = 0;
  int height = 1;
};
RaySet MakeRays(const Scene& scene, const std::string& rays_file, const std::string& camera,
                const std::string& res);

// <scene>.png for a file or gen:NAME:SIZE; empty for a ray file.
std::string DefaultImageName(const std::string& scene_arg, bool from_rays_file);

// Queues the image (if image_path is set), the hit buffer and the JSON stats
// (if their paths are set) on `outputs`; nothing is renamed into place until
// outputs.Commit().
void AddTraceOutputs(OutputSet& outputs, const Scene& scene, const RaySet& rays, const std::vector<Hit>& hits,
                     const std::string& image_path, const std::string& hits_path, const std::string& json_path,
                     const nlohmann::json& stats);

nlohmann::json TreeStatsJson(const TreeStats& s);
void PrintTreeStats(const PreparedScene& p);

}  // namespace kdrt::cli
