// kdrt info: tree statistics and memory image size of a scene.
#include <cstdio>
#include <fstream>

#include "common/error.h"
#include "tools/commands.h"
#include "setup/prepared_scene.h"
#include "setup/ray_set.h"
#include "setup/trace_outputs.h"
#include "tools/scene_options.h"
#include "trace/output_file.h"

namespace kdrt::cli {
namespace {

struct InfoArgs {
  SceneSpec scene;
  std::string json;
  std::string image_out;
};

int Run(const InfoArgs& args) {
  const PreparedScene p = PrepareScene(args.scene);
  OutputSet outputs;
  if (!args.json.empty()) {
    nlohmann::json j = {{"command", "info"},
                        {"scene", p.scene.source},
                        {"triangles", p.scene.triangles.size()},
                        {"accel", SplitMethodName(args.scene.build.method)},
                        {"tree", TreeStatsJson(p.tree.stats)},
                        {"image_bytes", p.image.size()}};
    AddJsonOutput(outputs, args.json, j);
  }
  if (!args.image_out.empty()) {
    outputs.Add(args.image_out, [&](const std::string& tmp) {
      std::ofstream f(tmp, std::ios::binary);
      f.write(reinterpret_cast<const char*>(p.image.data()), static_cast<std::streamsize>(p.image.size()));
      if (!f) throw InputError(args.image_out, 0, "cannot write memory image");
    });
  }
  outputs.Commit();
  PrintTreeStats(p);
  return 0;
}

}  // namespace

Runner AddInfoCommand(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd = app.add_subcommand("info", "Build the kd-tree and print its statistics and the image size");
  AddSceneOptions(*cmd, args->scene);
  cmd->add_option("--json", args->json, "Machine-readable statistics");
  cmd->add_option("--image", args->image_out, "Write the memory image (docs/memory-image.md) to this file");
  return [cmd, args]() { return cmd->parsed() ? Run(*args) : -1; };
}

}  // namespace kdrt::cli
