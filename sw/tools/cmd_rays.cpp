// kdrt rays: a closed mesh and its watertightness rays (trace/watertight.h),
// written as an NFF scene and a KDRTRAYS file for `kdrt render --rays`.
#include <cstdio>

#include "common/error.h"
#include "scene/nff_writer.h"
#include "tools/commands.h"
#include "trace/rays_file.h"
#include "trace/watertight.h"

namespace kdrt::cli {
namespace {

struct RaysArgs {
  std::string mesh = "sphere";
  int size = 0;  // 0: the mesh's default
  uint32_t seed = 1;
  std::string scene_out;
  std::string rays_out;
};

int Run(const RaysArgs& args) {
  Scene scene;
  if (args.mesh == "sphere") {
    const int rings = args.size > 0 ? args.size : 16;
    scene = ClosedSphereMesh(rings, 2 * rings);
  } else if (args.mesh == "cube") {
    scene = ClosedCubeMesh(args.size > 0 ? args.size : 8);
  } else {
    throw InputError("--mesh '" + args.mesh + "': expected sphere or cube");
  }
  const std::vector<Ray> rays = WatertightRays(scene, args.seed);
  // Scene first: if it fails, no ray file is left that belongs to no scene.
  WriteNff(scene, args.scene_out);
  WriteRaysFile(args.rays_out, rays);
  std::printf("mesh           %s, %zu triangles -> %s\n", scene.source.c_str(), scene.triangles.size(),
              args.scene_out.c_str());
  std::printf("rays           %zu (6 per triangle: 3 vertices, 3 edge midpoints) -> %s\n", rays.size(),
              args.rays_out.c_str());
  return 0;
}

}  // namespace

Runner AddRaysCommand(CLI::App& app) {
  auto args = std::make_shared<RaysArgs>();
  CLI::App* cmd = app.add_subcommand("rays", "Write a closed mesh and rays aimed at its vertices and edges "
                                             "(count the misses with render --rays)");
  cmd->add_option("--mesh", args->mesh, "sphere (N rings, 2N segments) or cube (N x N quads per face)")
      ->capture_default_str();
  cmd->add_option("--size", args->size, "N (default: 16 for the sphere, 8 for the cube)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--seed", args->seed, "Seed of the origin jitter")->capture_default_str();
  cmd->add_option("--scene-out", args->scene_out, "NFF file for the mesh")->required();
  cmd->add_option("--rays-out", args->rays_out, "KDRTRAYS file for the rays")->required();
  return [cmd, args]() { return cmd->parsed() ? Run(*args) : -1; };
}

}  // namespace kdrt::cli
