// kdrt gen: write a procedural scene as NFF.
#include <cstdio>

#include "scene/nff_writer.h"
#include "scenes/gen/generators.h"
#include "tools/commands.h"

namespace kdrt::cli {
namespace {

struct GenArgs {
  std::string name;
  int size = 1000;
  std::string out;
  bool list = false;
  double cone_aspect = 0;
};

int Run(const GenArgs& args) {
  if (args.list || args.name.empty()) {
    for (const std::string& n : GeneratorNames()) std::printf("%-8s %s\n", n.c_str(), GeneratorDescription(n).c_str());
    return 0;
  }
  LoadOptions tessellation;
  tessellation.cone_aspect = args.cone_aspect;
  const Scene scene = GenerateScene(args.name, args.size, tessellation);
  const std::string out = args.out.empty() ? args.name + ".nff" : args.out;
  WriteNff(scene, out);
  std::printf("%s: %zu triangles -> %s\n", scene.source.c_str(), scene.triangles.size(), out.c_str());
  return 0;
}

}  // namespace

Runner AddGenCommand(CLI::App& app) {
  auto args = std::make_shared<GenArgs>();
  CLI::App* cmd = app.add_subcommand("gen", "Write a procedural scene (room, balls, rings, tetra, tree, gears, strips, hoops) as NFF");
  cmd->add_option("name", args->name, "Generator name (omit to list them)");
  cmd->add_option("--size", args->size, "Approximate number of triangles")->capture_default_str();
  cmd->add_option("-o,--output", args->out, "NFF file to write (default: NAME.nff)");
  cmd->add_flag("--list", args->list, "List the generators");
  cmd->add_option("--cone-aspect", args->cone_aspect,
                  "gen:hoops' cylinders as the NFF loader's --cone-aspect makes them: bands of cells at most A times "
                  "longer than wide; 0: one band from end to end")
      ->capture_default_str();
  return [cmd, args]() { return cmd->parsed() ? Run(*args) : -1; };
}

}  // namespace kdrt::cli
