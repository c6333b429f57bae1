// kdrt synth: the physical cost of the core `kdrt sim` runs. The same scene
// and core options give the same rt_core parameters and model key as kdrt
// sim (tools/core_config.h); scripts/synth-core.sh synthesizes every unit of
// that configuration on the OSU 0.18 um library and times it with OpenSTA
// into build/phys/<key>/core.json, which kdrt sim then reports
// (docs/simulator.md, "Physical cost").
#include <cstdio>
#include <fstream>

#include "common/error.h"
#include "setup/prepared_scene.h"
#include "sim/phys.h"
#include "sim/run_options.h"
#include "tools/commands.h"
#include "tools/core_config.h"
#include "tools/scene_options.h"
#include "trace/output_file.h"

namespace kdrt::cli {
namespace {

struct SynthArgs {
  SceneSpec scene;  // scene.scene empty: no scene, rt_core's defaults with the options on top
  CoreConfigArgs core;
  uint64_t mem_size = 0;
  bool allow_overflow = false;
  double period_ns = 0;
  int jobs = 0;
  bool force = false;
  bool which = false;
  std::string json;
  bool quiet = false;
};

std::string Params(const nlohmann::json& params) {
  std::string s;
  if (!params.is_object()) return s;
  for (const auto& [k, v] : params.items()) s += (s.empty() ? "" : " ") + k + "=" + v.dump();
  return s;
}

void PrintTable(const nlohmann::json& core, const std::string& path, std::FILE* out) {
  auto d = [](const nlohmann::json& v) { return v.is_number() ? v.get<double>() : 0.0; };
  std::fprintf(out, "synthesis      %s\n", path.c_str());
  std::fprintf(out, "library        %s, period target %.2f ns, %s\n", core["library"].get<std::string>().c_str(),
               d(core.value("period_target_ns", nlohmann::json(0))), core.value("scope", "").c_str());
  std::fprintf(out, "%-16s %5s %12s %10s %8s  %s\n", "unit", "count", "um^2 each", "flip-flops", "crit ns",
               "critical path; parameters");
  for (const auto& u : core["units"]) {
    std::string path_text;
    if (u.contains("crit_path") && u["crit_path"].is_object()) {
      path_text = u["crit_path"].value("from", "?") + " -> " + u["crit_path"].value("to", "?");
    }
    std::fprintf(out, "%-16s %5.0f %12.0f %10.0f %8.2f  %s; %s%s\n", u["unit"].get<std::string>().c_str(),
                 d(u["count"]), d(u["area_um2"]), d(u["flip_flops"]), d(u["crit_ns"]), path_text.c_str(),
                 Params(u.value("params", nlohmann::json::object())).c_str(),
                 u.value("estimated", false) ? ("  [ESTIMATED: " + u.value("method", std::string("not stated")) + "]").c_str()
                                             : "");
    if (u.contains("srams")) {
      for (const auto& m : u["srams"]) {
        std::fprintf(out, "  sram %-10s %3.0f x %6.0f words x %4.0f bits, %10.0f um^2, access %.2f ns (%s)\n",
                     m.value("name", "?").c_str(), d(m.value("count", nlohmann::json(1))), d(m["words"]),
                     d(m["width"]), d(m.value("area_um2", nlohmann::json(0))),
                     d(m.value("access_ns", nlohmann::json(0))), m.value("source", "?").c_str());
      }
    }
  }
  const auto& a = core["area_um2"];
  std::fprintf(out, "clock          %.2f ns (%.0f MHz), critical unit %s\n", d(core["clock_ns"]),
               1e3 / d(core["clock_ns"]), core["critical_unit"].get<std::string>().c_str());
  std::fprintf(out, "area           %.3f mm^2 logic + %.3f mm^2 SRAM = %.3f mm^2\n", d(a["logic"]) * 1e-6,
               d(a["sram"]) * 1e-6, d(a["total"]) * 1e-6);
  for (const auto& n : core.value("notes", nlohmann::json::array())) {
    if (n.is_string()) std::fprintf(out, "note           %s\n", n.get<std::string>().c_str());
  }
}

int RunSynth(const SynthArgs& args) {
  if (args.period_ns < 0) throw InputError("--period must be a positive number of ns");
  const CoreFormats formats = ResolveFormats(args.core);
  sim::CoreConfig config;
  if (args.scene.scene.empty()) {
    config = sim::ConfigWithoutScene(formats.format, formats.overrides);
    std::fprintf(stderr,
                 "kdrt synth: no scene: rt_core's defaults with the options on top; kdrt sim sizes the stack, "
                 "index and address widths for its scene (give the scene to synthesize what it runs)\n");
  } else {
    const PreparedScene p = PrepareScene(args.scene);
    config = ChooseSceneCore(formats, p.image, args.mem_size, args.allow_overflow).choice.config;
  }
  const std::string path = sim::PhysPath(config);
  if (args.which) {
    const nlohmann::json core = sim::ReadCoreJson(config);
    std::printf("model          %s\n", config.Key().c_str());
    std::printf("synthesis      %s (%s)\n", path.c_str(), sim::SynthesisState(config, core).c_str());
    return 0;
  }
  nlohmann::json core = args.force ? nlohmann::json(nullptr) : sim::ReadCoreJson(config);
  if (core.is_null()) {
    if (!args.force && sim::HasSynthesisOfOtherSources(config)) {
      std::fprintf(stderr, "kdrt synth: %s\n", sim::NoSynthesisLine(config).c_str());
    }
    std::fprintf(stderr, "kdrt synth: synthesizing every unit of %s on the OSU 0.18 um library (takes minutes)\n",
                 config.Key().c_str());
    core = sim::SynthesizeCore(config, args.period_ns, args.jobs);
  } else if (!args.quiet) {
    std::fprintf(stderr, "kdrt synth: %s is synthesized already (--force synthesizes it again)\n", config.Key().c_str());
  }
  for (const auto& u : core["units"]) {
    if (u.value("estimated", false)) {
      std::fprintf(stderr, "kdrt synth: warning: %s is estimated (%s), not synthesized\n",
                   u["unit"].get<std::string>().c_str(), u.value("method", std::string("not stated")).c_str());
    }
  }
  if (args.json == "-") {
    nlohmann::json j = core;
    j["key"] = config.Key();
    j["source"] = path;
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  if (!args.json.empty()) {
    nlohmann::json j = core;
    j["key"] = config.Key();
    j["source"] = path;
    OutputSet outputs;
    outputs.Add(args.json, [&](const std::string& tmp) {
      std::ofstream f(tmp);
      f << j.dump(2) << "\n";
      if (!f) throw InputError(args.json + ": cannot be written");
    });
    outputs.Commit();
  }
  if (!args.quiet) {
    std::printf("model          %s\n", config.Key().c_str());
    PrintTable(core, path, stdout);
  }
  return 0;
}

}  // namespace

Runner AddSynthCommand(CLI::App& app) {
  auto args = std::make_shared<SynthArgs>();
  CLI::App* cmd = app.add_subcommand(
      "synth",
      "Synthesize the core kdrt sim runs (the same scene and core options) on the OSU 0.18 um library: area, "
      "flip-flops and critical path per unit, clock, area; kept in build/phys/<model key>/ for kdrt sim (minutes)");
  AddSceneOptions(*cmd, args->scene);
  cmd->get_option("scene")->required(false)->description(
      "The scene kdrt sim would run (its stack, index and address widths size the core); without one: rt_core's "
      "defaults with the options on top");
  AddFormatOptions(*cmd, args->core);
  sim::AddParamOptions(*cmd, args->core.overrides);
  cmd->add_option("--mem-size", args->mem_size, "Modelled memory in bytes, as kdrt sim's (sizes the address width)");
  cmd->add_flag("--allow-overflow", args->allow_overflow,
                "Accept a --stack-depth below the tree depth, as kdrt sim's");
  cmd->add_option("--period", args->period_ns, "Clock period target in ns for the mapping (default: synth-core.sh's)");
  cmd->add_option("--jobs", args->jobs, "Unit syntheses at once (default: synth-core.sh's, 1; each may take GBs)")
      ->check(CLI::Range(1, 64));
  cmd->add_flag("--force", args->force,
                "Write core.json again even when build/phys has one (units whose RTL, parameters and flow are "
                "unchanged come from the cache in build/phys/units)");
  cmd->add_flag("--which", args->which, "Print the model key and whether it is synthesized; synthesize nothing");
  cmd->add_option("--json", args->json, "Write the synthesis (core.json with the model key and its path) to this file; -: to stdout instead of the table");
  cmd->add_flag("-q,--quiet", args->quiet, "No table on stdout");
  return [cmd, args]() { return cmd->parsed() ? RunSynth(*args) : -1; };
}

}  // namespace kdrt::cli
