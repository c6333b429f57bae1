#include "tools/scene_options.h"

#include "common/error.h"

namespace kdrt::cli {

void AddSceneOptions(CLI::App& cmd, SceneSpec& spec, bool structures) {
  BuildOptions& b = spec.build;
  cmd.add_option("scene", spec.scene,
                 "Scene file (.nff, .obj, .ply, .off) or gen:NAME:SIZE for a procedural scene "
                 "(see `kdrt gen --help`)")
      ->required();
  // The parsers' InputError names the bad value (exit status 1).
  if (structures) {
    cmd.add_option_function<std::string>(
           "--accel",
           [&spec](const std::string& name) {
             spec.accel = ParseAccelKind(name);
             if (IsKdTree(spec.accel)) spec.build.method = SplitMethodOf(spec.accel);
           },
           "Acceleration structure: a kd-tree (sah, median, midpoint: the memory image the hardware reads) or a "
           "software structure of the reference tracer (grid, hgrid, octree, bvh; fp32 and fp64 only)")
        ->default_str(SplitMethodName(b.method));
    cmd.add_option("--grid-density", spec.structure.grid_density,
                   "Uniform grid resolution: cells per triangle (the lecture's n^3 = d |O|)")
        ->capture_default_str();
    cmd.add_option("--hgrid-density", spec.structure.hgrid_density,
                   "Hierarchical grid: cells per triangle of the top level and of each sub-grid")
        ->capture_default_str();
  } else {
    cmd.add_option_function<std::string>(
           "--accel",
           [&b](const std::string& name) {
             for (AccelKind kind : AllAccelKinds()) {
               if (!IsKdTree(kind) && name == AccelKindName(kind)) {
                 throw InputError("--accel " + name + ": this command reads the kd-tree the hardware reads (sah, "
                                  "median or midpoint); the software structures are for kdrt render and kdrt "
                                  "compare-accel");
               }
             }
             b.method = ParseSplitMethod(name);
           },
           "kd-tree split method: sah, median or midpoint")
        ->default_str(SplitMethodName(b.method));
  }
  cmd.add_option("--max-depth", b.max_depth, "Maximum tree depth (-1: round(8 + 1.3 log2 N))")->capture_default_str();
  cmd.add_option("--max-leaf", b.max_leaf_prims, "Make a leaf at this many triangles or fewer")->capture_default_str();
  cmd.add_option("--isect-cost", b.isect_cost, "SAH cost of a triangle test")->capture_default_str();
  cmd.add_option("--trav-cost", b.traversal_cost, "SAH cost of a traversal step")->capture_default_str();
  cmd.add_option("--empty-bonus", b.empty_bonus, "SAH bonus for empty children")->capture_default_str();
  cmd.add_flag("--perfect-splits", b.perfect_splits, "Clip triangles to the node box (SAH only)");
  cmd.add_flag("--no-auto-clip{false}", b.auto_clip,
               "SAH: never clip; by default a node of more than 16 triangles whose boxes give no good split is "
               "decided on its triangles clipped to its cell, its subtree with perfect splits (docs/kdtree.md)");
  cmd.add_option("--min-split-gain", b.min_split_gain,
                 "SAH: a split that does not cost less than (1 - G) x the leaf counts as a bad refinement (3 on a "
                 "path make a leaf); 0: any split cheaper than the leaf is good, pbrt-v3's rule (docs/kdtree.md)")
      ->capture_default_str();
  b.threads = 0;
  cmd.add_option("--build-threads", b.threads,
                 "SAH build threads (0: all cores); the tree is the same for any number")
      ->capture_default_str();
  cmd.add_option("--sphere-segments", spec.sphere_segments,
                 "Tessellation of NFF spheres and cones (0: the loader's default)");
  cmd.add_option("--cone-aspect", spec.cone_aspect,
                 "NFF cones and cylinders (and gen:hoops'): cut into bands along the axis so that no cell is more "
                 "than A times longer than wide; 0: one band from end to end, long slivers on thin cylinders "
                 "(docs/kdtree.md, \"Long thin cylinders\")")
      ->capture_default_str();
}

void AddShadingOptions(CLI::App& cmd, ShadingArgs& args) {
  cmd.add_flag("--shade", args.shade,
               "Shade with the scene's lights (NFF `l`; else one above the camera) and hard shadows: traces a "
               "shadow ray (any-hit query) per hit and light (docs/shading.md)");
  cmd.add_option("--ao", args.options.ao_samples, "Also N ambient-occlusion rays per hit (any-hit; implies --shade)")
      ->check(CLI::Range(0, 1024));
  cmd.add_flag("--bounce", args.options.bounce, "Also one diffuse bounce ray per hit (closest hit; implies --shade)");
  cmd.add_option("--seed", args.options.seed, "Seed of the AO and bounce directions")->capture_default_str();
  cmd.add_option("--write-rays", args.write_rays,
                 "Write the frame's ray sets to DIR as ray files: primary.rays, shadow.rays, ao.rays, bounce.rays "
                 "(needs --shade, --ao or --bounce)");
}

void CheckShadingArgs(const ShadingArgs& args, const RaySet& rays) {
  if (!args.write_rays.empty() && !args.On()) {
    throw InputError("--write-rays: the ray sets come from shading; add --shade (or --ao N, --bounce)");
  }
  if (args.On() && rays.query == Query::kAny) {
    throw InputError("--shade: the ray file holds any-hit queries (shadow rays), not primary rays to shade");
  }
}

}  // namespace kdrt::cli
