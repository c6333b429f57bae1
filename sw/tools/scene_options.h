// The command-line options of every scene-reading command: the scene and the
// kd-tree build options, bound straight to SceneSpec (setup/prepared_scene.h).
#pragma once

#include <CLI/CLI.hpp>

#include "setup/prepared_scene.h"
#include "setup/ray_set.h"
#include "trace/shading.h"

namespace kdrt::cli {

// `structures`: --accel also takes the software structures (grid, hgrid,
// octree, bvh) and --grid-density is offered; otherwise --accel names a
// kd-tree split rule only (the hardware reads a kd-tree).
void AddSceneOptions(CLI::App& cmd, SceneSpec& spec, bool structures = false);

// --shade, --ao, --bounce, --seed, --write-rays (kdrt render and kdrt sim).
struct ShadingArgs {
  bool shade = false;
  ShadingOptions options;
  std::string write_rays;  // directory for the frame's ray files
  // Shading was asked for (--shade, or --ao / --bounce, which imply it).
  bool On() const { return shade || options.ao_samples > 0 || options.bounce; }
};
void AddShadingOptions(CLI::App& cmd, ShadingArgs& args);
// Throws InputError for --write-rays without shading, or shading an any-hit ray file.
void CheckShadingArgs(const ShadingArgs& args, const RaySet& rays);

}  // namespace kdrt::cli
