// One simulation model (kdrt-sim-<format>, or a scene-sized model under
// build/sim-models/): one Verilated rt_core configuration around the harness.
// It reads what the `kdrt sim` front end has built, the memory image and the
// ray file, traces the reference hits itself (the model of its own format),
// runs the core ray by ray against them, and writes the RTL's hit records and
// the report of the run. It never loads a scene (docs/simulator.md).
// Compiled once for every model: what depends on the Verilated core comes
// from core_harness.cpp and sc_top.cpp (CompiledConfig, RunVerilator, ...).
#include <cstdio>
#include <fstream>
#include <iterator>

#include <CLI/CLI.hpp>

#include "common/error.h"
#include "sim/core_harness.h"
#include "sim/run_options.h"
#include "sim/sim_report.h"
#include "trace/images.h"
#include "trace/output_file.h"
#include "trace/rays_file.h"
#include "trace/tracer.h"

#ifdef KDRT_SIM_SYSTEMC
#include "sim/sc_top.h"
#endif

namespace kdrt::sim {
namespace {

struct ModelArgs {
  std::string image;
  std::string rays;
  std::string hits_out;
  std::string report_out;
  std::string expect_key;
  bool print_config = false;
  RunOptions run;
};

std::vector<uint8_t> ReadFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, 0, "cannot open");
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

int Run(const ModelArgs& args) {
  const CoreConfig config = CompiledConfig();
  if (args.print_config) {
    std::printf("%s\n", config.Json().dump(2).c_str());
    return 0;
  }
  if (!args.expect_key.empty() && args.expect_key != config.Key()) {
    throw InputError("this model was built as " + config.Key() + ", not " + args.expect_key +
                     "; rebuild it (cmake --build build)");
  }
  if (args.image.empty() || args.rays.empty()) throw InputError("--image and --rays are required");
  CheckRunOptions(args.run);
#ifndef KDRT_SIM_SYSTEMC
  if (args.run.systemc) throw InputError("--systemc: this model was built without SystemC");
#endif

  const std::vector<uint8_t> bytes = ReadFile(args.image);
  const ImageView image(bytes, args.image);
  if (image.layout().e != config.ImageFormat().e || image.layout().m != config.ImageFormat().m) {
    throw InputError(args.image, 0,
                     "an e" + std::to_string(image.layout().e) + "m" + std::to_string(image.layout().m) +
                         " image, but this core computes in " + config.Format().Name() + " and reads an image of " +
                         config.ImageFormat().Name() + " (kdrt info --format F --image FILE writes it)");
  }
  const SceneRequirements req = DeriveRequirements(image);
  const uint64_t mem_size = args.run.mem_size ? args.run.mem_size : uint64_t{1} << config[kAddrWidth];
  CheckConfigCovers(config, req, mem_size, args.run.allow_overflow);
  Query query = Query::kClosest;
  const std::vector<Ray> rays = ReadRaysFile(args.rays, &query);
  if (args.run.trace_ray >= static_cast<int64_t>(rays.size())) {
    throw InputError("--trace-ray " + std::to_string(args.run.trace_ray) + ": there are only " +
                     std::to_string(rays.size()) + " rays");
  }

  TraceOptions to;
  to.format = config.Format();
  to.trav_format = config.TravFormat();
  to.query = query;
  // The reference with the core's stack: a ray whose push meets a full stack
  // ends there in both (--allow-overflow), so its record is compared too.
  to.stack_depth = config[kStackDepth];
  TraceStats ts;
  std::vector<RayCounters> per_ray;
  std::vector<Hit> reference = TraceRays(image, rays, to, &ts, &per_ray);
  const int64_t corrupt = args.run.corrupt_reference;
  if (corrupt >= 0 && corrupt < static_cast<int64_t>(rays.size())) {
    Hit& h = reference[corrupt];
    h = h.IsHit() ? Hit{fp::FloatOf(fp::BitsOf(h.t) ^ 1u), h.prim, h.u, h.v} : Hit{1.0f, 0, 0.0f, 0.0f};
  }

  RunSpec spec;
  spec.image = &image;
  spec.rays = &rays;
  spec.reference = &reference;
  spec.memory.size_bytes = mem_size;
  spec.memory.latency = args.run.mem_latency;
  spec.memory.bytes_per_cycle = args.run.mem_bw;
  spec.options.reference = to;
  spec.options.timeout = args.run.timeout;
  spec.options.trace_ray = args.run.trace_ray;
  spec.options.progress = args.run.progress;
  const std::vector<uint32_t> order = IssueOrder(args.run.ray_order, args.run.frame_width, rays.size());
  spec.options.order = &order;
  spec.trace_path = args.run.trace;

  ReportInputs ri;
  ri.loop = args.run.systemc || args.run.cores > 0 ? "systemc" : "verilator";
  ri.config = config;
  ri.requirements = req;
  ri.memory = spec.memory;
  ri.reference_totals = ts.totals;
  SetWindowBound(per_ray, &order, config[kThreads], args.run.cores, &ri);
  ri.rays = rays.size();
  ri.query = query;

  RunOutcome run;
  nlohmann::json report;
  try {
    if (args.run.cores > 0) {
#ifdef KDRT_SIM_SYSTEMC
      L2Config l2;
      l2.size_bytes = args.run.l2_kb * 1024u;
      l2.ways = args.run.l2_ways;
      l2.latency = args.run.l2_latency;
      const SystemOutcome sys = RunSystemCCores(spec, args.run.cores, l2, args.run.ray_chunk);
      // The records as a single core would hold them: each ray's from its core.
      run.result.hits.assign(rays.size(), Hit{});
      run.result.overflow.assign(rays.size(), 0);
      for (const RunOutcome& c : sys.cores) {
        for (uint32_t id : c.result.ray_ids) {
          run.result.hits[id] = c.result.hits[id];
          run.result.overflow[id] = c.result.overflow[id];
        }
        run.result.overflows += c.result.overflows;
      }
      report = SystemReportJson(ri, sys, per_ray);
#else
      throw InputError("--cores: this model was built without SystemC (install libsystemc-dev and rebuild)");
#endif
    } else {
#ifdef KDRT_SIM_SYSTEMC
      run = args.run.systemc ? RunSystemC(spec) : RunVerilator(spec);
#else
      run = RunVerilator(spec);
#endif
      ri.run = &run;
      report = ReportJson(ri);
    }
    // A quick build is made for the tests (KDRT_QUICK_MODELS): its sim speed
    // is not the model's, and the report says so.
    report["model_build"] = QuickBuild() ? "quick" : "optimised";
  } catch (const SimFailure& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "\nkdrt sim: %s\n", e.what());
    return 3;
  }
  // The records matched the reference's; so must the rays whose stack
  // overflowed (the reference ends them at the same push).
  for (size_t i = 0; i < rays.size(); ++i) {
    const bool want = per_ray[i].overflows > 0;
    if ((run.result.overflow[i] != 0) != want) {
      std::fflush(stdout);
      std::fprintf(stderr, "\nkdrt sim: co-simulation mismatch: ray %zu %s its stack (StackDepth %d) in the RTL "
                           "but %s in the reference\n",
                   i, run.result.overflow[i] ? "overflowed" : "did not overflow", config[kStackDepth],
                   want ? "overflowed" : "not");
      return 3;
    }
  }

  OutputSet outputs;
  outputs.Add(args.hits_out, [&](const std::string& tmp) {
    WriteHitBuffer(tmp, static_cast<int>(rays.size()), 1, run.result.hits);
  });
  outputs.Add(args.report_out, [&](const std::string& tmp) {
    std::ofstream f(tmp);
    f << report.dump(2) << "\n";
    if (!f) throw InputError(args.report_out, 0, "cannot write the report");
  });
  outputs.Commit();
  if (run.result.overflows > 0) {
    std::fprintf(stderr, "kdrt sim: %llu rays overflowed the traversal stack (StackDepth %d, the tree needs %d); "
                         "their records end at the overflowing push, as the reference's with the same stack do, "
                         "and are not valid answers\n",
                 static_cast<unsigned long long>(run.result.overflows), config[kStackDepth], req.stack_depth);
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
  CLI::App app{"kdrt simulation model: runs the Verilated rt_core on a memory image and a ray file (started by "
               "`kdrt sim`, which builds both; see docs/simulator.md)"};
  kdrt::sim::ModelArgs args;
  app.add_option("--image", args.image, "Memory image (docs/memory-image.md), as `kdrt info --image` writes it");
  app.add_option("--rays", args.rays, "Ray file (KDRTRAYS)");
  app.add_option("--hits-out", args.hits_out, "EXR hit buffer of the RTL's records, one row in ray order")
      ->needs("--image");
  app.add_option("--report-out", args.report_out, "JSON report of the run")->needs("--image");
  app.add_option("--expect-model", args.expect_key, "Refuse to run unless this model's key is KEY");
  app.add_flag("--config", args.print_config, "Print the parameters this model was built with (JSON) and stop");
  kdrt::sim::AddRunOptions(app, args.run);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (!args.print_config && (args.hits_out.empty() || args.report_out.empty())) {
      throw kdrt::InputError("--hits-out and --report-out are required");
    }
    return kdrt::sim::Run(args);
  } catch (const kdrt::InputError& e) {
    std::fprintf(stderr, "kdrt: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kdrt: internal error: %s\n", e.what());
    return 2;
  }
}
