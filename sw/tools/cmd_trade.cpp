// kdrt trade: the speed/accuracy trade of the number formats in one command
// (docs/trade.md): accuracy against fp64, work, cycles, area and memory per
// format, side by side, and the smallest format that meets a target.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "common/error.h"
#include "fp/format.h"
#include "setup/prepared_scene.h"
#include "setup/ray_set.h"
#include "setup/trace_outputs.h"
#include "tools/commands.h"
#include "tools/scene_options.h"
#include "trace/output_file.h"
#include "trade/report.h"
#include "trade/trade.h"

namespace kdrt::cli {
namespace {

struct TradeArgs {
  SceneSpec scene;
  std::string formats;
  std::string res;
  std::string rays;
  std::string camera;
  std::string json, csv, html;
  double target_mismatch = 1e-3;
  bool sim = false;
  uint64_t sim_rays = 0;
  bool area_estimate = false;
  bool no_area = false;
  int threads = 0;
  bool quiet = false;
};

// The formats to trade: soft formats, each once. fp64 is the truth and is
// always traced, so naming it is allowed and changes nothing.
std::vector<fp::Format> ParseFormatList(const std::string& list) {
  if (list.empty()) return fp::Presets();
  std::vector<fp::Format> out;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    if (name.empty()) throw InputError("--formats '" + list + "': an empty format name");
    const fp::Format f = fp::ParseFormat(name);
    if (f.IsFp64()) continue;
    if (std::find(out.begin(), out.end(), f) != out.end()) {
      throw InputError("--formats '" + list + "': " + f.Name() + " is named twice");
    }
    out.push_back(f);
  }
  if (out.empty()) throw InputError("--formats '" + list + "': no format to compare with fp64");
  return out;
}

int Run(const TradeArgs& args) {
  trade::TradeOptions o;
  o.formats = ParseFormatList(args.formats);
  if (!(args.target_mismatch >= 0 && args.target_mismatch <= 1)) {
    throw InputError("--target-mismatch " + std::to_string(args.target_mismatch) + ": must be a fraction in [0, 1]");
  }
  // Every output is checked before minutes of work, and written only at the end.
  if (!args.json.empty()) CheckWritable(args.json);
  if (!args.csv.empty()) CheckWritable(args.csv);
  if (!args.html.empty()) CheckDirectoryOutput(args.html, "index.html");

  o.target_mismatch = args.target_mismatch;
  o.sim = args.sim;
  o.sim_rays = args.sim_rays;
  o.area = !args.no_area;
  o.area_options.estimate = args.area_estimate;
  o.threads = args.threads;
  if (!args.quiet) {
    o.progress = [](const std::string& text) { std::fprintf(stderr, "trade: %s\n", text.c_str()); };
    o.area_options.progress = o.progress;
  }

  const PreparedScene p = PrepareScene(args.scene);
  const RaySet rays = MakeRays(p.scene, args.rays, args.camera, args.res);
  const trade::TradeResult t = trade::MeasureTrade(p, rays, o);

  OutputSet outputs;
  if (!args.json.empty()) AddJsonOutput(outputs, args.json, trade::TradeJson(t));
  if (!args.csv.empty()) {
    const std::string csv = trade::TradeCsv(t);
    outputs.Add(args.csv, [&](const std::string& tmp) {
      FILE* f = std::fopen(tmp.c_str(), "w");
      if (f == nullptr || std::fwrite(csv.data(), 1, csv.size(), f) != csv.size() || std::fclose(f) != 0) {
        throw InputError(args.csv, 0, "cannot write");
      }
    });
  }
  if (!args.html.empty()) {
    outputs.AddDirectory(args.html, "index.html", [&](const std::string& dir) { trade::WriteHtml(t, dir); });
  }
  outputs.Commit();

  if (!args.quiet) {
    trade::PrintTable(t, stdout);
    if (!args.json.empty()) std::printf("stats          %s\n", args.json.c_str());
    if (!args.csv.empty()) std::printf("csv            %s\n", args.csv.c_str());
    if (!args.html.empty()) std::printf("page           %s/index.html\n", args.html.c_str());
  }
  return 0;
}

}  // namespace

Runner AddTradeCommand(CLI::App& app) {
  auto args = std::make_shared<TradeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "trade", "The speed/accuracy trade: accuracy against fp64, work, cycles, area and memory per format");
  AddSceneOptions(*cmd, args->scene);
  cmd->add_option("--formats", args->formats,
                  "Comma-separated formats to compare with fp64 (default: " + fp::PresetNames() + "; eXmY too)");
  cmd->add_option("--res", args->res, "Image resolution WxH (default: the scene's, else 512x512)");
  cmd->add_option("--rays", args->rays, "Trace this ray file (KDRTRAYS) instead of the camera");
  cmd->add_option("--camera", args->camera, "Override the camera: \"fx fy fz ax ay az ux uy uz angle\"");
  cmd->add_flag("--sim", args->sim, "Also run the RTL core in every format: cycles per ray, efficiency, bytes per ray");
  cmd->add_option("--sim-rays", args->sim_rays,
                  "Simulate at most this many rays (every k-th; the output says it is a subsample); 0: all")
      ->capture_default_str();
  cmd->add_option("--target-mismatch", args->target_mismatch,
                  "Recommend the smallest format with at most this fraction of rays whose hit differs from fp64's "
                  "(hit/miss or triangle) and no holes")
      ->capture_default_str();
  cmd->add_flag("--area-estimate", args->area_estimate,
                "For a format never synthesized, estimate its area from the presets instead of running Yosys");
  cmd->add_flag("--no-area", args->no_area, "No area columns (no synthesis)");
  cmd->add_option("--json", args->json, "Machine-readable results");
  cmd->add_option("--csv", args->csv, "One row per format");
  cmd->add_option("--html", args->html, "A page with the table, images and plots: DIR/index.html");
  cmd->add_option("--threads", args->threads, "Threads of the software tracer (0: all cores)");
  cmd->add_flag("-q,--quiet", args->quiet, "No table on stdout, no progress on stderr");
  return [cmd, args]() { return cmd->parsed() ? Run(*args) : -1; };
}

}  // namespace kdrt::cli
