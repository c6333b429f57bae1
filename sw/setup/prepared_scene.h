// What every scene-reading command and the `kdrt sim` front end share: the
// scene argument (a file, or gen:NAME:SIZE for a procedural scene), building
// the tree and the memory image, and reporting them. Used by `kdrt render`,
// `kdrt info` and `kdrt sim`; the simulation models never load a scene.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "accel/kdtree.h"
#include "scene/scene.h"
#include "trace/frame.h"

namespace kdrt {

struct SceneSpec {
  std::string scene;        // a file or gen:NAME:SIZE
  int sphere_segments = 0;  // 0: loader default
  BuildOptions build;
};

struct PreparedScene {
  Scene scene;         // world coordinates: what the outputs show
  Frame frame;         // the image's scene-relative frame
  KdTree tree;         // built over the scene in the frame
  std::vector<uint8_t> image;
  double load_seconds = 0;
};

// Loads (or generates) the scene, builds the tree and the memory image.
PreparedScene PrepareScene(const SceneSpec& spec);
// The tree and the memory image of a scene already in memory.
PreparedScene PrepareScene(Scene scene, const BuildOptions& build);

nlohmann::json TreeStatsJson(const TreeStats& s);
void PrintTreeStats(const PreparedScene& p);

}  // namespace kdrt
