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
#include "structures/structure.h"
#include "trace/frame.h"

namespace kdrt {

struct SceneSpec {
  std::string scene;        // a file or gen:NAME:SIZE
  int sphere_segments = 0;  // 0: loader default
  double cone_aspect = 0;   // LoadOptions::cone_aspect, for NFF files and gen:hoops
  bool strict = false;      // refuse data the loader would leave out (LoadOptions::strict)
  BuildOptions build;
  // A kd-tree split rule (the tree in the memory image, build.method) or a
  // software structure (structures/structure.h) built beside the image.
  AccelKind accel = AccelKind::kSah;
  StructureOptions structure;
};

struct PreparedScene {
  Scene scene;         // world coordinates: what the outputs show
  Frame frame;         // the image's scene-relative frame
  KdTree tree;         // built over the scene in the frame
  std::vector<uint8_t> image;
  double load_seconds = 0;
  // For a software structure: the image holds the triangles under a
  // single-leaf tree (nothing traces it), and the structure is built over
  // them. Held by pointer: the structure keeps the input's address.
  std::unique_ptr<StructureInput> structure_input;
  std::unique_ptr<Structure> structure;
  AccelKind accel = AccelKind::kSah;
};

// Loads (or generates) the scene alone. The scene's warnings (data of the
// file left out) are printed on stderr as "kdrt: warning: <text>"; the
// commands also list them in their JSON "warnings".
Scene LoadOrGenerate(const SceneSpec& spec);
// Loads (or generates) the scene, builds the tree and the memory image.
PreparedScene PrepareScene(const SceneSpec& spec);
// The tree and the memory image of a scene already in memory.
PreparedScene PrepareScene(Scene scene, const BuildOptions& build);
// The same with spec's choice of structure (spec.scene is not read).
PreparedScene PrepareScene(Scene scene, const SceneSpec& spec);

nlohmann::json TreeStatsJson(const TreeStats& s);
// The options a kd-tree was built with (`"build"` in the commands' JSON), so a
// report says which tree its numbers are for; max_depth is the one used.
nlohmann::json BuildOptionsJson(const BuildOptions& o, const TreeStats& s);
void PrintTreeStats(const PreparedScene& p);

}  // namespace kdrt
