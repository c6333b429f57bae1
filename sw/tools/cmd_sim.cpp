// kdrt sim: the cycle simulator front end (docs/simulator.md).
//
// Verilator fixes the core's parameters at build time, so the simulator is a
// family of executables (sim/sim_main.cpp), one per configuration. This
// front end loads the scene once, builds the tree, the memory image and the
// rays, derives what the scene needs of the core, picks the prebuilt model of
// the format when it covers that (otherwise builds a scene-sized one once),
// hands the model the image and the rays, and writes the outputs from the
// RTL's hit records.
#include <unistd.h>

#include <algorithm>
#include <cinttypes>
#include <cstdio>

#include "common/error.h"
#include "fp/format.h"
#include "setup/precision_check.h"
#include "setup/prepared_scene.h"
#include "setup/ray_set.h"
#include "setup/shaded_frame.h"
#include "setup/trace_outputs.h"
#include "sim/model_runner.h"
#include "sim/phys.h"
#include "sim/ray_queue.h"
#include "sim/run_options.h"
#include "sim/sim_report.h"
#include "tools/commands.h"
#include "tools/core_config.h"
#include "tools/scene_options.h"
#include "trace/tracer.h"

namespace kdrt::cli {
namespace {

struct SimArgs {
  SceneSpec scene;
  std::string res;
  std::string out;
  std::string hits;
  std::string json;
  CoreConfigArgs core;  // --format, --trav-format, --image-format and the parameter options
  std::string rays;
  std::string camera;
  sim::RunOptions run;
  bool ray_order_given = false;  // --ray-order on the command line (else: morton for a frame, a ray file's own)
  bool quiet = false;
  bool strict = false;
  bool which_model = false;  // print the model choice and stop
  bool build_model = false;  // build the model if needed and stop
  bool synth = false;        // synthesize the configuration first when build/phys has none
  std::string model = "rtl";  // rtl, fast or both
  ShadingArgs shading;
};

// A secondary pass's model run failed (its message is on stderr already).
struct PassFailed {
  int exit_code;
};

// The report's "physical" block: the synthesis of exactly this configuration,
// or null and a line on stderr saying there is none. Estimated units are
// warnings too.
void AddPhysical(const nlohmann::json& core_json, const sim::CoreConfig& config, int cores, bool shaded,
                 nlohmann::json* report) {
  nlohmann::json& r = *report;
  if (core_json.is_null()) {
    r["physical"] = nullptr;
    std::fprintf(stderr, "kdrt sim: %s\n", sim::NoSynthesisLine(config).c_str());
    return;
  }
  // One core's cycles per ray: several cores share the rays, so the
  // system's cycles per ray times N.
  const double cpr = r["cycles_per_ray"].get<double>() * std::max(1, cores);
  nlohmann::json p = sim::PhysicalBlock(core_json, sim::PhysPath(config), config, cpr);
  if (cores > 0) {
    p["notes"].push_back("--cores " + std::to_string(cores) +
                         ": the rate and the area are one core's; the L2 and the wires between cores are in neither");
  }
  if (shaded) p["notes"].push_back("--shade: the rate is the primary rays'; the passes are in \"passes\"");
  for (const auto& e : p["estimated_units"]) {
    const std::string w = "physical: " + e["unit"].get<std::string>() + " is estimated (" +
                          e["method"].get<std::string>() + "), not synthesized";
    std::fprintf(stderr, "kdrt sim: warning: %s\n", w.c_str());
    r["warnings"].push_back(w);
  }
  r["physical"] = std::move(p);
}

int RunSim(SimArgs args) {
  sim::CheckRunOptions(args.run);
  const std::vector<std::string> run_warnings = sim::RunOptionWarnings(args.run);
  for (const std::string& w : run_warnings) std::fprintf(stderr, "kdrt: warning: %s\n", w.c_str());
  if (args.model != "rtl" && args.model != "fast" && args.model != "both") {
    throw InputError("--model " + args.model + ": expected rtl, fast or both");
  }
  if (args.model == "fast" && (!args.run.trace.empty() || args.run.systemc)) {
    throw InputError("--model fast: no waveform or --systemc (the fast model is plain C++, not the RTL)");
  }
  const CoreFormats formats = ResolveFormats(args.core);
  const fp::Format format = formats.format, image_format = formats.image_format;
  args.scene.strict = args.strict;
  const PreparedScene p = PrepareScene(args.scene);
  const ImageView image(p.image);
  const SceneCore sc = ChooseSceneCore(formats, p.image, args.run.mem_size, args.run.allow_overflow);
  const std::vector<uint8_t>& core_image = sc.core_image;
  const sim::SceneRequirements& req = sc.req;
  const sim::ConfigChoice& choice = sc.choice;
  const sim::ModelLocation loc = sim::LocateModel(choice);
  // A corrupt core.json stops here, before anything runs or is written.
  nlohmann::json core_json = sim::ReadCoreJson(choice.config);
  if (args.which_model) {
    std::printf("scene needs    stack %d, node index %d bits, triangle index %d bits, address %d bits (%" PRIu64
                " bytes)\n",
                req.stack_depth, req.node_idx_bits, req.tri_idx_bits, req.addr_bits, req.image_bytes);
    std::printf("model          %s (%s)\n", choice.config.Key().c_str(), choice.prebuilt ? "prebuilt" : "scene-sized");
    const char* state = loc.built ? "built" : loc.stale ? "out of date: sources changed, rebuilt on use" : "not built yet";
    std::printf("executable     %s (%s%s)\n", loc.path.c_str(), state,
                loc.quick ? "; a quick build, one unit at -O1 without waveforms: KDRT_QUICK_MODELS" : "");
    std::string synthesis = sim::SynthesisState(choice.config, core_json);
    if (core_json.is_null()) synthesis += ": kdrt synth, or kdrt sim --synth";
    std::printf("synthesis      %s (%s)\n", sim::PhysPath(choice.config).c_str(), synthesis.c_str());
    return 0;
  }
  if (args.build_model) {
    if (!loc.built) sim::BuildModel(choice, loc);
    std::printf("model          %s: %s\n", choice.config.Key().c_str(), loc.path.c_str());
    return 0;
  }
  const RaySet ray_set = MakeRays(p.scene, args.rays, args.camera, args.res);
  CheckShadingArgs(args.shading, ray_set);
  if (!args.rays.empty() && !args.ray_order_given) args.run.ray_order = "linear";  // a file has no frame
  if (args.run.ray_order != "linear") {
    if (!args.rays.empty()) {
      throw InputError("--ray-order " + args.run.ray_order +
                       " orders the camera's frame; a ray file (--rays) is issued in its own order");
    }
    args.run.frame_width = static_cast<uint32_t>(ray_set.width);
  }
  if (args.run.trace_ray >= static_cast<int64_t>(ray_set.rays.size())) {
    throw InputError("--trace-ray " + std::to_string(args.run.trace_ray) + ": there are only " +
                     std::to_string(ray_set.rays.size()) + " rays");
  }
  // Before a model is built or run: --strict refuses here, with nothing written.
  const PrecisionCheck check = CheckPrecision(image, ray_set.rays, format, args.strict, 0, "", image_format);
  const bool rtl = args.model != "fast", fast = args.model != "rtl";
  if (rtl && !loc.built) sim::BuildModel(choice, loc);
  if (args.synth && core_json.is_null()) {
    std::fprintf(stderr, "kdrt sim: synthesizing %s on the OSU 0.18 um library (takes minutes)\n",
                 choice.config.Key().c_str());
    core_json = sim::SynthesizeCore(choice.config, 0);
  }

  // The waveform is written by the model; it gets a temporary name and is
  // published with the other outputs (or kept alone when the run fails).
  OutputSet outputs;
  std::string trace_tmp;
  if (!args.run.trace.empty()) outputs.Add(args.run.trace, [&](const std::string& tmp) { trace_tmp = tmp; });
  args.run.mem_size = choice.mem_size;
  args.run.progress = args.run.progress || (!args.quiet && isatty(STDERR_FILENO));
  // One run of the chosen cycle model(s); with both, the RTL's report with
  // the fast model's figures and its error beside it.
  const auto run_model = [&](const std::vector<Ray>& rays, const sim::RunOptions& run_options,
                             const std::string& trace_path, Query query) {
    if (!rtl) return sim::RunFast(choice.config, core_image, rays, run_options, query);
    sim::ModelRun r = sim::RunModel(loc, choice.config, core_image, rays, run_options, trace_path, query);
    if (r.exit_code != 0) return r;
    r.report["cycle_model"] = "rtl";
    if (fast) {
      const sim::ModelRun f = sim::RunFast(choice.config, core_image, rays, run_options, query);
      const double rtl_cpr = r.report["cycles_per_ray"], fast_cpr = f.report["cycles_per_ray"];
      const double rtl_s = r.report["sim_seconds"], fast_s = f.report["sim_seconds"];
      r.report["fast"] = {{"cycles", f.report["cycles"]},
                          {"cycles_per_ray", fast_cpr},
                          {"error", rtl_cpr > 0 ? (fast_cpr - rtl_cpr) / rtl_cpr : 0.0},
                          {"sim_seconds", fast_s},
                          {"speedup", fast_s > 0 ? rtl_s / fast_s : 0.0},
                          {"report", f.report}};
    }
    return r;
  };
  const sim::ModelRun run = run_model(ray_set.rays, args.run, trace_tmp, ray_set.query);
  if (run.exit_code != 0) {
    if (!trace_tmp.empty() && std::rename(trace_tmp.c_str(), args.run.trace.c_str()) == 0) {
      std::fprintf(stderr, "kdrt sim: waveform up to the failure in %s\n", args.run.trace.c_str());
    }
    return run.exit_code;
  }

  nlohmann::json report = run.report;
  sim::AddScene({p.scene.source, ray_set.width, ray_set.height, p.scene.triangles.size(), p.tree.stats.nodes,
                 p.tree.stats.max_depth},
                &report);
  report["build"] = BuildOptionsJson(args.scene.build, p.tree.stats);
  report["ray_order"] = args.run.ray_order;
  report["precision"] = check.requirement.Json();
  report["warnings"] = check.warnings;
  for (const std::string& w : p.scene.warnings) report["warnings"].push_back(w);
  for (const std::string& w : run_warnings) report["warnings"].push_back(w);
  AddPhysical(core_json, choice.config, args.run.cores, args.shading.On(), &report);

  // Shading: each secondary pass is one more run of the same model (the
  // waveform and --trace-ray cover the primary pass only).
  ShadedFrame frame;
  if (args.shading.On()) {
    sim::RunOptions pass_run = args.run;
    // A pass's rays are a list of the frame's hits, not a frame: in Z-order
    // they are issued by their pixels' Z-order (the model sees them sorted,
    // and its hits are put back in the pass's order).
    const int streams = sim::MortonStreams(args.run.ray_order);
    const bool by_pixel = streams > 0;
    pass_run.ray_order = "linear";
    pass_run.trace.clear();
    pass_run.trace_ray = -1;
    const PassTracer trace = [&](const RayPass& pass, nlohmann::json* stats) {
      if (!args.quiet) std::fprintf(stderr, "kdrt sim: %s pass, %zu rays\n", pass.name.c_str(), pass.rays.size());
      for (const std::string& w :
           CheckPrecision(image, pass.rays, format, args.strict, 0, pass.name, image_format).warnings) {
        report["warnings"].push_back(w);
      }
      std::vector<uint32_t> order;
      std::vector<Ray> rays;
      if (by_pixel) {
        order = sim::InterleaveStreams(sim::PixelIssueOrder(pass.pixel, static_cast<uint32_t>(ray_set.width)),
                                       streams);
        rays.reserve(order.size());
        for (uint32_t i : order) rays.push_back(pass.rays[i]);
      }
      sim::ModelRun r = run_model(by_pixel ? rays : pass.rays, pass_run, "", pass.query);
      if (r.exit_code != 0) {
        if (by_pixel) {
          std::fprintf(stderr,
                       "kdrt sim: the %s pass issued its rays by their pixels' Z-order: a ray number above is a "
                       "position in that order (--ray-order linear keeps the pass's own order)\n",
                       pass.name.c_str());
        }
        throw PassFailed{r.exit_code};
      }
      *stats = std::move(r.report);
      (*stats)["ray_order"] = by_pixel ? args.run.ray_order + " by pixel" : "linear";
      if (!by_pixel) return std::move(r.hits);
      std::vector<Hit> hits(r.hits.size());
      for (size_t k = 0; k < order.size(); ++k) hits[order[k]] = r.hits[k];
      return hits;
    };
    try {
      nlohmann::json primary = run.report;
      primary["ray_order"] = args.run.ray_order;
      frame = TraceShadedFrame(p.scene, args.shading.options, ray_set.rays, run.hits, primary, trace);
    } catch (const PassFailed& f) {
      return f.exit_code;
    }
    report["passes"] = PassesJson(frame.passes);
    report["frame"] = sim::FrameTotals(report["passes"]);
  }

  const std::string out = args.out.empty() ? DefaultImageName(args.scene.scene, !args.rays.empty()) : args.out;
  AddTraceOutputs(outputs, p.scene, ray_set, run.hits, out, args.hits, args.json, report,
                  args.shading.On() ? &frame.rgb : nullptr);
  if (!args.shading.write_rays.empty()) AddRayPassFiles(outputs, args.shading.write_rays, frame.passes);
  outputs.Commit();

  if (!args.quiet) {
    sim::PrintReport(report, stdout);
    sim::PrintCores(report, stdout);
    sim::PrintPhysical(report["physical"], choice.config, stdout);
    if (report.contains("fast")) {
      const auto& f = report["fast"];
      std::printf("fast model     %.2f cycles per ray (error %+.2f %% against the RTL), %.3f s (%.0fx the RTL's speed)\n",
                  f["cycles_per_ray"].get<double>(), 100 * f["error"].get<double>(), f["sim_seconds"].get<double>(),
                  f["speedup"].get<double>());
    }
    if (report.value("cycle_model", "") == "fast") {
      std::printf("cycle model    fast (C++, not the RTL; hits from the reference model)\n");
    }
    if (args.shading.On()) sim::PrintPasses(report["passes"], report["frame"], stdout);
    if (!out.empty()) std::printf("image          %s\n", out.c_str());
    if (!args.hits.empty()) std::printf("hit buffer     %s\n", args.hits.c_str());
    if (!args.json.empty()) std::printf("stats          %s\n", args.json.c_str());
    if (!args.run.trace.empty()) std::printf("waveform       %s\n", args.run.trace.c_str());
    if (!args.shading.write_rays.empty()) std::printf("ray sets       %s\n", args.shading.write_rays.c_str());
  }
  return 0;
}

}  // namespace

Runner AddSimCommand(CLI::App& app) {
  auto args = std::make_shared<SimArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sim", "Run the RTL core (Verilator) on a scene, checked ray by ray against the reference; report cycles");
  AddSceneOptions(*cmd, args->scene);
  cmd->add_option("--res", args->res, "Image resolution WxH (default: the scene's, else 512x512)");
  cmd->add_option("-o,--output", args->out, "Image file (.png, .ppm, .exr; default: <scene>.png)");
  cmd->add_option("--hits", args->hits, "EXR hit buffer with channels t, prim, u, v");
  cmd->add_option("--json", args->json, "Machine-readable statistics");
  AddFormatOptions(*cmd, args->core);
  cmd->add_option("--rays", args->rays, "Trace this ray file (KDRTRAYS) instead of the camera");
  cmd->add_option("--camera", args->camera, "Override the camera: \"fx fy fz ax ay az ux uy uz angle\"");
  // The camera's rays enter the core in kFrameRayOrder unless told otherwise
  // (the model binaries' own default stays the ray list's order).
  args->run.ray_order = sim::kFrameRayOrder;
  sim::AddRunOptions(*cmd, args->run);
  cmd->get_option("--ray-order")->each([args](const std::string&) { args->ray_order_given = true; });
  sim::AddParamOptions(*cmd, args->core.overrides);
  AddShadingOptions(*cmd, args->shading);
  cmd->add_flag("-q,--quiet", args->quiet, "No report on stdout");
  cmd->add_flag("--strict", args->strict,
                "Refuse (exit 1, no output) instead of warning: a format that cannot represent the scene, or "
                "data of the scene file the reader would leave out");
  cmd->add_flag("--which-model", args->which_model,
                "Print the model the scene needs and whether it is built; run nothing");
  cmd->add_option("--model", args->model,
                  "Cycle model: rtl (the Verilated core, checked ray by ray), fast (the C++ cycle model, "
                  "docs/simulator.md; hits from the reference) or both (the RTL's report and the fast model's error)")
      ->capture_default_str();
  cmd->add_flag("--synth", args->synth,
                "Synthesize the configuration that runs (kdrt synth: every unit on the OSU 0.18 um library, "
                "minutes) when build/phys has no synthesis of it, and report its physical cost");
  cmd->add_flag("--build-model", args->build_model,
                "Build the model the scene needs (if it is missing or out of date) and stop; run nothing");
  return [cmd, args]() { return cmd->parsed() ? RunSim(*args) : -1; };
}

}  // namespace kdrt::cli
