#include "tools/scene_options.h"

namespace kdrt::cli {

void AddSceneOptions(CLI::App& cmd, SceneSpec& spec) {
  BuildOptions& b = spec.build;
  cmd.add_option("scene", spec.scene,
                 "Scene file (.nff, .obj, .ply, .off) or gen:NAME:SIZE for a procedural scene "
                 "(see `kdrt gen --help`)")
      ->required();
  // ParseSplitMethod's InputError names the bad value (exit status 1).
  cmd.add_option_function<std::string>(
         "--accel", [&b](const std::string& name) { b.method = ParseSplitMethod(name); },
         "kd-tree split method: sah, median or midpoint")
      ->default_str(SplitMethodName(b.method));
  cmd.add_option("--max-depth", b.max_depth, "Maximum tree depth (-1: round(8 + 1.3 log2 N))")->capture_default_str();
  cmd.add_option("--max-leaf", b.max_leaf_prims, "Make a leaf at this many triangles or fewer")->capture_default_str();
  cmd.add_option("--isect-cost", b.isect_cost, "SAH cost of a triangle test")->capture_default_str();
  cmd.add_option("--trav-cost", b.traversal_cost, "SAH cost of a traversal step")->capture_default_str();
  cmd.add_option("--empty-bonus", b.empty_bonus, "SAH bonus for empty children")->capture_default_str();
  cmd.add_flag("--perfect-splits", b.perfect_splits, "Clip triangles to the node box (SAH only)");
  cmd.add_option("--sphere-segments", spec.sphere_segments,
                 "Tessellation of NFF spheres and cones (0: the loader's default)");
}

}  // namespace kdrt::cli
