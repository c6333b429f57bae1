// kdrt extremes: the numerics suite. For every case (setup/extreme_cases.h)
// and format: holes among the rays that must hit, disagreement with the
// reference format (fp64 by default: hit/miss, triangle), whether the
// scene's precision requirement (trace/precision.h) warns about the format,
// and, with --sim, the RTL core's records against the reference tracer's in
// the same format.
#include <unistd.h>

#include <cstdio>
#include <optional>
#include <regex>
#include <sstream>

#include "common/error.h"
#include "fp/format.h"
#include "setup/extreme_cases.h"
#include "setup/prepared_scene.h"
#include "setup/trace_outputs.h"
#include "sim/core_params.h"
#include "sim/model_runner.h"
#include "sim/run_options.h"
#include "tools/commands.h"
#include "trace/hit_compare.h"
#include "trace/precision.h"
#include "trace/tracer.h"

namespace kdrt::cli {
namespace {

struct ExtremesArgs {
  std::string formats;  // default: the presets
  std::string reference = "fp64";
  std::string trav_format;  // empty: each format traverses in itself
  std::string datapath;     // empty: each format computes in itself; else each format is the image's
  std::string cases;    // a regular expression over the case names
  std::string json;
  bool reduced = false;
  bool sim = false;
  bool quiet = false;
  sim::ConfigOverrides core;  // with --sim: the core's parameters (kdrt sim's options)
};

std::vector<fp::Format> ParseFormats(const std::string& list) {
  if (list.empty()) return fp::Presets();
  std::vector<fp::Format> out;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) out.push_back(fp::ParseFormat(name));
  return out;
}

struct Cell {
  uint64_t holes = 0;          // must-hit rays that missed
  uint64_t hitmiss = 0;        // hit/miss differs from the reference
  uint64_t prim = 0;           // both hit, other triangle
  int64_t sim_mismatch = -1;   // records that differ from render's (-1: not simulated)
  std::string warning;         // the requirement's shortfall ("" when the format suffices)
};

Cell Measure(const ExtremeCase& c, const std::vector<Hit>& hits, const std::vector<Hit>& ref) {
  Cell cell;
  for (size_t i = 0; i < hits.size(); ++i) {
    cell.holes += c.must_hit[i] && !hits[i].IsHit();
    cell.hitmiss += hits[i].IsHit() != ref[i].IsHit();
    cell.prim += hits[i].IsHit() && ref[i].IsHit() && hits[i].prim != ref[i].prim;
  }
  return cell;
}

int Run(const ExtremesArgs& args) {
  const std::vector<fp::Format> formats = ParseFormats(args.formats);
  const fp::Format reference = fp::ParseFormat(args.reference);
  const std::regex pick(args.cases.empty() ? ".*" : args.cases);
  // --datapath W: every listed format is the image's, W computes (the
  // storage criteria of the precision check judged by the image's format).
  std::optional<fp::Format> datapath;
  if (!args.datapath.empty()) {
    datapath = fp::ParseFormat(args.datapath);
    for (const fp::Format& f : formats) CheckImageFormat(*datapath, f);
  }
  std::optional<fp::Format> trav;
  if (!args.trav_format.empty()) {
    trav = fp::ParseFormat(args.trav_format);
    for (const fp::Format& f : formats) CheckTravFormat(datapath.value_or(f), *trav);
    if (args.sim) sim::CheckRtlTravFormat(*trav);
  }
  std::vector<ExtremeCase> cases;
  for (ExtremeCase& c : MakeExtremeCases(args.reduced)) {
    if (std::regex_search(c.name, pick)) cases.push_back(std::move(c));
  }
  if (cases.empty()) throw InputError("--cases '" + args.cases + "' matches no case");
  const bool progress = !args.quiet && isatty(STDERR_FILENO);

  nlohmann::json rows = nlohmann::json::array();
  if (!args.quiet) {
    std::printf("%-34s %7s %7s", "case", "rays", "needs");
    for (const fp::Format& f : formats) std::printf("  %-22s", (f.Name() + " holes/hm/prim" + (args.sim ? "/sim" : "")).c_str());
    std::printf("\n");
  }
  for (const ExtremeCase& c : cases) {
    if (progress) std::fprintf(stderr, "extremes: %s\n", c.name.c_str());
    const PreparedScene p = PrepareScene(c.scene, BuildOptions{});
    const ImageView image(p.image);
    TraceOptions to;
    to.format = reference;
    const std::vector<Hit> ref = TraceRays(image, c.rays, to);
    const PrecisionRequirement req = AnalyzePrecision(image, c.rays);
    uint64_t must = 0;
    for (uint8_t m : c.must_hit) must += m;
    nlohmann::json row = {{"case", c.name},         {"group", c.group},       {"triangles", c.scene.triangles.size()},
                          {"rays", c.rays.size()},  {"must_hit", must},       {"tree_depth", p.tree.stats.max_depth},
                          {"refs_per_triangle", p.tree.stats.refs_per_triangle}, {"image_bytes", p.image.size()},
                          {"reference", reference.Name()}, {"minimal_format", req.MinimalFormat()}};
    if (!args.quiet) std::printf("%-34s %7zu %7s", c.name.c_str(), c.rays.size(), req.MinimalFormat().c_str());
    for (const fp::Format& f : formats) {
      TraceOptions fo = to;
      fo.format = datapath.value_or(f);
      fo.trav_format = trav;
      // With --datapath, f's packed image (its own format's is the same
      // hits as the fp32 image's, so the fp32 image serves without it).
      const std::vector<uint8_t> packed = datapath ? sim::CoreImage(p.image, f) : std::vector<uint8_t>{};
      const std::vector<Hit> hits = TraceRays(datapath ? ImageView(packed) : image, c.rays, fo);
      Cell cell = Measure(c, hits, ref);
      cell.warning = req.Shortfall(fo.format, f);
      if (args.sim) {
        sim::RunOptions run;
        const sim::ModelRun m = sim::Simulate(p.image, c.rays, fo.format, run, Query::kClosest, trav, f, args.core);
        if (m.exit_code != 0) {
          throw InputError("kdrt sim failed on case '" + c.name + "' in " + f.Name() + " (exit " +
                           std::to_string(m.exit_code) + ")");
        }
        cell.sim_mismatch = 0;
        for (size_t i = 0; i < hits.size(); ++i) cell.sim_mismatch += !SameBits(hits[i], m.hits[i]);
      }
      nlohmann::json j = {{"holes", cell.holes},
                          {"hitmiss_mismatch", cell.hitmiss},
                          {"prim_mismatch", cell.prim},
                          {"warning", cell.warning}};
      if (cell.sim_mismatch >= 0) j["sim_mismatch"] = cell.sim_mismatch;
      row["formats"][f.Name()] = j;
      if (!args.quiet) {
        std::string text = std::to_string(cell.holes) + "/" + std::to_string(cell.hitmiss) + "/" +
                           std::to_string(cell.prim);
        if (cell.sim_mismatch >= 0) text += "/" + std::to_string(cell.sim_mismatch);
        if (!cell.warning.empty()) text += " W";
        std::printf("  %-22s", text.c_str());
      }
    }
    if (!args.quiet) std::printf("\n");
    std::fflush(stdout);
    rows.push_back(row);
  }
  if (!args.quiet) {
    std::printf("holes: must-hit rays that missed; hm, prim: rays whose hit/miss or triangle differs from %s%s;\n"
                "W: the scene's precision requirement says the format cannot represent the case (the JSON has "
                "the warning)\n",
                reference.Name().c_str(), args.sim ? "; sim: RTL records that differ from render's" : "");
    if (trav) {
      std::printf("every format traversed in %s (--trav-format; the test in the format)\n", trav->Name().c_str());
    }
    if (datapath) {
      std::printf("every format is the image's, the datapath computes in %s (--datapath)\n",
                  datapath->Name().c_str());
    }
  }
  if (!args.json.empty()) {
    OutputSet outputs;
    nlohmann::json j = {{"command", "extremes"}, {"reference", reference.Name()}, {"cases", rows}};
    if (trav) j["trav_format"] = trav->Name();
    if (datapath) j["datapath"] = datapath->Name();
    AddJsonOutput(outputs, args.json, j);
    outputs.Commit();
  }
  return 0;
}

}  // namespace

Runner AddExtremesCommand(CLI::App& app) {
  auto args = std::make_shared<ExtremesArgs>();
  CLI::App* cmd = app.add_subcommand(
      "extremes", "The numerics suite: holes and disagreement with the reference format, case by format");
  cmd->add_option("--formats", args->formats, "Comma-separated formats (default: " + fp::PresetNames() + ")");
  cmd->add_option("--reference", args->reference, "The format the others are compared with")->capture_default_str();
  cmd->add_option("--trav-format", args->trav_format,
                  "Traverse in this format (at least every listed format's bits), test in each listed one; "
                  "with --sim, the RTL core with that traversal datapath (at most fp32)");
  cmd->add_option("--datapath", args->datapath,
                  "Compute in this format (at least every listed format's bits) and read each listed format's "
                  "image (kdrt render --image-format); with --sim, the RTL core reading that image");
  cmd->add_option("--cases", args->cases, "Only the cases whose name matches this regular expression");
  cmd->add_option("--json", args->json, "Machine-readable results");
  cmd->add_flag("--reduced", args->reduced, "The smaller set `make test` runs");
  cmd->add_flag("--sim", args->sim, "Also run the RTL core (kdrt sim) on every case and format and compare");
  cmd->add_flag("-q,--quiet", args->quiet, "No table on stdout");
  // With --sim, the core's parameters as kdrt sim takes them (--threads,
  // --cache-mshrs, ...); each case's scene sizes what is left unset.
  sim::AddParamOptions(*cmd, args->core);
  return [cmd, args]() { return cmd->parsed() ? Run(*args) : -1; };
}

}  // namespace kdrt::cli
