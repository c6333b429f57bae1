// One simulator executable (kdrt-sim-<format>, or a scene-sized model under
// build/sim-models/): the whole of `kdrt sim` around one Verilated rt_core
// configuration. It takes the options of `kdrt sim`; the front end in `kdrt`
// picks or builds the model and starts this program with its arguments.
#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "common/error.h"
#include "sim/core_harness.h"
#include "sim/sim_args.h"
#include "sim/sim_report.h"
#include "trace/images.h"
#include "trace/output_file.h"
#include "trace/tracer.h"

#ifdef KDRT_SIM_SYSTEMC
#include "sim/sc_top.h"
#endif

namespace kdrt::sim {
namespace {

CoreConfig CompiledConfig() {
  CoreConfig c;
  c.e = KDRT_SIM_E;
  c.m = KDRT_SIM_M;
  c.threads = KDRT_SIM_THREADS;
  c.stack_depth = KDRT_SIM_STACK_DEPTH;
  c.node_idx_width = KDRT_SIM_NODE_IDX_WIDTH;
  c.tri_idx_width = KDRT_SIM_TRI_IDX_WIDTH;
  c.addr_width = KDRT_SIM_ADDR_WIDTH;
  c.node_cache_lines = KDRT_SIM_NODE_CACHE_LINES;
  c.list_cache_lines = KDRT_SIM_LIST_CACHE_LINES;
  c.tri_cache_lines = KDRT_SIM_TRI_CACHE_LINES;
  return c;
}

// A model started by hand must not silently ignore an option it cannot honour.
void CheckOverridesMatch(const CoreConfig& c, const ConfigOverrides& ov) {
  auto check = [&](const char* option, int asked, int have) {
    if (asked != 0 && asked != have) {
      throw InputError(std::string(option) + " " + std::to_string(asked) + ": this model (" + c.Key() + ") has " +
                       std::to_string(have) + "; run it through `kdrt sim`, which builds the model it needs");
    }
  };
  check("--threads", ov.threads, c.threads);
  check("--stack-depth", ov.stack_depth, c.stack_depth);
  check("--node-idx-width", ov.node_idx_width, c.node_idx_width);
  check("--tri-idx-width", ov.tri_idx_width, c.tri_idx_width);
  check("--addr-width", ov.addr_width, c.addr_width);
  check("--node-cache-lines", ov.node_cache_lines, c.node_cache_lines);
  check("--list-cache-lines", ov.list_cache_lines, c.list_cache_lines);
  check("--tri-cache-lines", ov.tri_cache_lines, c.tri_cache_lines);
}

int Run(const SimArgs& args) {
  CheckSimArgs(args);
  const CoreConfig config = CompiledConfig();
  const fp::Format format = fp::ParseFormat(args.format);
  if (format.e != config.e || format.m != config.m) {
    throw InputError("--format " + args.format + ": this model computes in " +
                     fp::MakeFormat(config.e, config.m).Name() + "; run it through `kdrt sim`");
  }
  CheckOverridesMatch(config, args.overrides);
#ifndef KDRT_SIM_SYSTEMC
  if (args.systemc) throw InputError("--systemc: this model was built without SystemC");
#endif

  cli::PreparedScene p = cli::PrepareScene(args.scene);
  const ImageView image(p.image);
  const SceneRequirements req = DeriveRequirements(image);
  const uint64_t mem_size = args.overrides.mem_size ? args.overrides.mem_size : uint64_t{1} << config.addr_width;
  CheckConfigCovers(config, req, mem_size, args.overrides.allow_overflow);

  const cli::RaySet ray_set = cli::MakeRays(p.scene, args.rays, args.camera, args.res);
  const std::vector<Ray>& rays = ray_set.rays;
  const int width = ray_set.width, height = ray_set.height;
  if (args.trace_ray >= static_cast<int64_t>(rays.size())) {
    throw InputError("--trace-ray " + std::to_string(args.trace_ray) + ": there are only " +
                     std::to_string(rays.size()) + " rays");
  }

  TraceOptions to;
  to.format = format;
  TraceStats ts;
  std::vector<RayCounters> per_ray;
  std::vector<Hit> reference = TraceRays(image, rays, to, &ts, &per_ray);
  if (args.corrupt_reference >= 0 && args.corrupt_reference < static_cast<int64_t>(rays.size())) {
    Hit& h = reference[args.corrupt_reference];
    if (h.IsHit()) {
      h.t = fp::FloatOf(fp::BitsOf(h.t) ^ 1u);
    } else {
      h = Hit{1.0f, 0, 0.0f, 0.0f};
    }
  }

  RunSpec spec;
  spec.image = &image;
  spec.rays = &rays;
  spec.reference = &reference;
  spec.memory.size_bytes = mem_size;
  spec.memory.latency = args.mem_latency;
  spec.memory.bytes_per_cycle = args.mem_bw;
  spec.options.reference = to;
  spec.options.timeout = args.timeout;
  spec.options.trace_ray = args.trace_ray;
  spec.options.progress = args.progress || (!args.quiet && isatty(STDERR_FILENO));
  spec.trace_path = args.trace;

  // The waveform is written in place by Verilator; give it a temporary name
  // and let the OutputSet publish it with the other files.
  OutputSet outputs;
  std::string trace_tmp;
  if (!args.trace.empty()) {
    outputs.Add(args.trace, [&](const std::string& tmp) { trace_tmp = tmp; });
    spec.trace_path = trace_tmp;
  }

  RunOutcome run;
  try {
#ifdef KDRT_SIM_SYSTEMC
    run = args.systemc ? RunSystemC(spec) : RunVerilator(spec);
#else
    run = RunVerilator(spec);
#endif
  } catch (const SimFailure& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "\nkdrt sim: %s\n", e.what());
    // The waveform is what one debugs a failure with: keep it.
    if (!trace_tmp.empty() && std::rename(trace_tmp.c_str(), args.trace.c_str()) == 0) {
      std::fprintf(stderr, "kdrt sim: waveform up to the failure in %s\n", args.trace.c_str());
    }
    return 3;
  }

  ReportInputs ri;
  ri.scene = p.scene.source;
  ri.format = format.Name();
  ri.loop = args.systemc ? "systemc" : "verilator";
  ri.width = width;
  ri.height = height;
  ri.config = config;
  ri.requirements = req;
  ri.memory = spec.memory;
  ri.reference_totals = ts.totals;
  ri.run = &run;
  ri.rays = rays.size();
  ri.tree_nodes = p.tree.stats.nodes;
  ri.tree_depth = p.tree.stats.max_depth;
  ri.triangles = p.scene.triangles.size();
  const nlohmann::json report = ReportJson(ri);

  const std::vector<Hit>& hits = run.result.hits;
  const std::string out =
      args.out.empty() ? cli::DefaultImageName(args.scene.scene, !args.rays.empty()) : args.out;
  cli::AddTraceOutputs(outputs, p.scene, ray_set, hits, out, args.hits, args.json, report);
  outputs.Commit();

  if (!args.quiet) {
    PrintReport(report, stdout);
    if (!out.empty()) std::printf("image          %s\n", out.c_str());
    if (!args.hits.empty()) std::printf("hit buffer     %s\n", args.hits.c_str());
    if (!args.json.empty()) std::printf("stats          %s\n", args.json.c_str());
    if (!args.trace.empty()) std::printf("waveform       %s\n", args.trace.c_str());
  }
  if (run.result.overflows > 0) {
    std::fprintf(stderr, "kdrt sim: %llu rays overflowed the traversal stack (StackDepth %d, the tree needs %d); "
                         "their records are not valid answers\n",
                 static_cast<unsigned long long>(run.result.overflows), config.stack_depth, req.stack_depth);
  }
  return 0;
}

}  // namespace
}  // namespace kdrt::sim

#ifdef KDRT_SIM_SYSTEMC
// libsystemc provides main() and calls this (declared extern "C" there).
extern "C" int sc_main(int argc, char** argv) {
#else
int main(int argc, char** argv) {
#endif
  CLI::App app{"kdrt simulation model (normally started by `kdrt sim`)"};
  kdrt::sim::SimArgs args;
  kdrt::sim::AddSimOptions(app, args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return kdrt::sim::Run(args);
  } catch (const kdrt::InputError& e) {
    std::fprintf(stderr, "kdrt: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kdrt: internal error: %s\n", e.what());
    return 2;
  }
}
