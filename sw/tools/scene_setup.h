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
#include "scene/scene.h"

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

nlohmann::json TreeStatsJson(const TreeStats& s);
void PrintTreeStats(const PreparedScene& p);

}  // namespace kdrt::cli
