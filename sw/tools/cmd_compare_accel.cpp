// kdrt compare-accel: the acceleration structures side by side, Havran-style.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "common/error.h"
#include "setup/accel_compare.h"
#include "setup/accel_report.h"
#include "tools/commands.h"
#include "tools/scene_options.h"
#include "trace/output_file.h"

namespace kdrt::cli {
namespace {

struct CompareAccelArgs {
  std::vector<std::string> scenes;
  std::string accel = "sah,median,midpoint,grid,hgrid,octree,bvh";
  std::string res = "256x256";
  std::string format = "fp32";
  std::string json;
  std::string html;
  int threads = 1;
  int repeat = 1;
  int sphere_segments = 0;
  double cone_aspect = 0;
  double grid_density = StructureOptions{}.grid_density;
  double hgrid_density = StructureOptions{}.hgrid_density;
  bool quiet = false;
  bool markdown = false;
};

std::vector<AccelKind> ParseKinds(const std::string& list) {
  std::vector<AccelKind> kinds;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    if (!name.empty()) kinds.push_back(ParseAccelKind(name));
  }
  if (kinds.empty()) throw InputError("--accel: no structure named");
  return kinds;
}

int Run(const CompareAccelArgs& args) {
  AccelCompareOptions o;
  o.kinds = ParseKinds(args.accel);
  o.res = args.res;
  o.threads = args.threads;
  o.repeat = args.repeat;
  o.format = fp::ParseFormat(args.format);
  o.spec.sphere_segments = args.sphere_segments;
  o.spec.cone_aspect = args.cone_aspect;
  o.spec.structure.grid_density = args.grid_density;
  o.spec.structure.hgrid_density = args.hgrid_density;
  o.progress = !args.quiet && isatty(STDERR_FILENO);
  CheckStructureOptions(o.spec.structure);
  // Every scene file must open before the first scene's long run.
  for (const std::string& scene : args.scenes) {
    if (scene.rfind("gen:", 0) != 0 && !std::ifstream(scene)) throw InputError(scene, 0, "cannot open scene file");
  }
  if (!args.json.empty()) CheckWritable(args.json);
  if (!args.html.empty()) CheckDirectoryOutput(args.html, "index.html");

  std::vector<AccelComparison> results;
  nlohmann::json warnings = nlohmann::json::array();
  bool differs = false;
  for (const std::string& scene : args.scenes) {
    if (!args.quiet) std::fprintf(stderr, "compare-accel: %s\n", scene.c_str());
    results.push_back(CompareAccels(scene, o));
    for (const AccelRow& r : results.back().rows) {
      if (!r.error.empty()) {
        // Reported, not fatal: the other structures' rows stand.
        const std::string w = results.back().scene + ": " + AccelKindName(r.kind) + " not built: " + r.error;
        std::fprintf(stderr, "kdrt: warning: %s\n", w.c_str());
        warnings.push_back(w);
        continue;
      }
      if (r.mismatches == 0) continue;
      differs = true;
      // A structure that does not return the kd-tree's hits is a bug, never a tolerance.
      const std::string w = results.back().scene + ": " + AccelKindName(r.kind) + " differs from the SAH kd-tree on " +
                            std::to_string(r.mismatches) + " rays";
      std::fprintf(stderr, "kdrt: warning: %s\n", w.c_str());
      warnings.push_back(w);
    }
  }

  OutputSet outputs;
  if (!args.json.empty()) {
    nlohmann::json j = {{"command", "compare-accel"}, {"format", args.format}, {"threads", args.threads},
                        {"repeat", args.repeat}, {"grid_density", args.grid_density},
                        {"hgrid_density", args.hgrid_density}, {"warnings", warnings}};
    j["scenes"] = nlohmann::json::array();
    for (const AccelComparison& c : results) j["scenes"].push_back(AccelComparisonJson(c));
    outputs.Add(args.json, [&](const std::string& tmp) {
      std::ofstream f(tmp);
      f << j.dump(2) << "\n";
      if (!f) throw InputError(args.json, 0, "write failed");
    });
  }
  if (!args.html.empty()) {
    outputs.AddDirectory(args.html, "index.html", [&](const std::string& dir) { WriteAccelHtml(results, dir); });
  }
  outputs.Commit();
  if (!args.quiet) {
    std::printf("%s", AccelTable(results, args.markdown).c_str());
    std::printf("(%s, %d thread%s, the fastest of %d trace%s; x best: trace time over the scene's fastest, *)\n",
                args.format.c_str(), args.threads, args.threads == 1 ? "" : "s", args.repeat,
                args.repeat == 1 ? "" : "s");
    if (!args.json.empty()) std::printf("stats          %s\n", args.json.c_str());
    if (!args.html.empty()) std::printf("report         %s/index.html\n", args.html.c_str());
  }
  return differs ? 1 : 0;
}

}  // namespace

Runner AddCompareAccelCommand(CLI::App& app) {
  auto args = std::make_shared<CompareAccelArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare-accel",
      "Build and trace every acceleration structure (kd-trees, grid, hgrid, octree, BVH) on the same rays: build "
      "time, memory, nodes and tests per ray, mailbox hits, Mrays/s and the ratio to the fastest, per scene "
      "(Havran's table; docs/structures.md). Exit 1 if a structure's hits differ from the SAH kd-tree's; a structure "
      "that cannot be built on a scene (too large for the memory image) is a warning and an empty row");
  cmd->add_option("scenes", args->scenes, "Scene files or gen:NAME:SIZE")->required();
  cmd->add_option("--accel", args->accel, "Structures to compare, comma-separated")->capture_default_str();
  cmd->add_option("--res", args->res, "Camera resolution WxH")->capture_default_str();
  cmd->add_option("--format", args->format, "fp32 or fp64")->capture_default_str();
  cmd->add_option("--threads", args->threads, "Tracing threads (1: single-thread timings; 0: all cores)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--repeat", args->repeat, "Trace each structure this many times and keep the fastest")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  cmd->add_option("--grid-density", args->grid_density, "Uniform grid cells per triangle")->capture_default_str();
  cmd->add_option("--hgrid-density", args->hgrid_density, "Hierarchical grid cells per triangle (each level)")
      ->capture_default_str();
  cmd->add_option("--sphere-segments", args->sphere_segments,
                  "Tessellation of NFF spheres and cones (0: the loader's default)");
  cmd->add_option("--cone-aspect", args->cone_aspect,
                  "NFF cones and cylinders (and gen:hoops'): bands of cells at most A times longer than wide; 0: one "
                  "band from end to end")
      ->capture_default_str();
  cmd->add_option("--json", args->json, "Machine-readable results");
  cmd->add_option("--html", args->html, "Write a report page (index.html) to this directory");
  cmd->add_flag("--markdown", args->markdown, "Print the table as markdown (for docs)");
  cmd->add_flag("-q,--quiet", args->quiet, "No table on stdout, no progress on stderr");
  return [cmd, args]() { return cmd->parsed() ? Run(*args) : -1; };
}

}  // namespace kdrt::cli
