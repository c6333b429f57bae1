#include "sim/sim_args.h"

#include <cmath>
#include <sstream>

#include "common/error.h"
#include "scene/camera.h"
#include "trace/rays_file.h"

namespace kdrt::sim {
void AddSimOptions(CLI::App& cmd, SimArgs& a) {
  cli::AddSceneOptions(cmd, a.scene);
  cmd.add_option("--res", a.res, "Image resolution WxH (default: the scene's, else 512x512)");
  cmd.add_option("-o,--output", a.out, "Image file (.png, .ppm, .exr; default: <scene>.png)");
  cmd.add_option("--hits", a.hits, "EXR hit buffer with channels t, prim, u, v");
  cmd.add_option("--json", a.json, "Machine-readable statistics");
  cmd.add_option("--format", a.format, "Number format of the core: fp32, fp24, bf16, fp16 or eXmY")
      ->capture_default_str();
  cmd.add_option("--rays", a.rays, "Trace this ray file (KDRTRAYS) instead of the camera");
  cmd.add_option("--camera", a.camera, "Override the camera: \"fx fy fz ax ay az ux uy uz angle\"");
  cmd.add_option("--trace", a.trace, "Write an FST waveform of the core");
  cmd.add_option("--trace-ray", a.trace_ray, "With --trace: dump only while ray K (its index) is in flight");
  cmd.add_option("--mem-latency", a.mem_latency, "Memory latency in cycles (>= 1)")->capture_default_str();
  cmd.add_option("--mem-bw", a.mem_bw, "Memory bandwidth in bytes per cycle (fractions allowed; the port "
                                       "carries at most 16)")
      ->capture_default_str();
  cmd.add_option("--mem-size", a.overrides.mem_size, "Modelled memory in bytes (default: 2^address width)");
  cmd.add_option("--timeout", a.timeout, "Fail after this many cycles without a hit record")->capture_default_str();
  cmd.add_option("--threads,--core-threads", a.overrides.threads, "Rays in flight in the core (Threads; default 16)");
  cmd.add_option("--stack-depth", a.overrides.stack_depth, "Traversal stack entries per thread (default: 32, or "
                                                           "what the scene needs)");
  cmd.add_option("--node-idx-width", a.overrides.node_idx_width, "Bits of a node index");
  cmd.add_option("--tri-idx-width", a.overrides.tri_idx_width, "Bits of a triangle id / list index");
  cmd.add_option("--addr-width", a.overrides.addr_width, "Bits of a byte address");
  cmd.add_option("--node-cache-lines", a.overrides.node_cache_lines, "Node cache lines (power of two; default 64)");
  cmd.add_option("--list-cache-lines", a.overrides.list_cache_lines, "List cache lines (power of two; default 64)");
  cmd.add_option("--tri-cache-lines", a.overrides.tri_cache_lines, "Triangle cache lines (power of two; default 64)");
  cmd.add_flag("--allow-overflow", a.overrides.allow_overflow,
               "Accept a --stack-depth below the tree depth (overflowing rays are counted and reported)");
  cmd.add_flag("--progress", a.progress, "Progress line on stderr (default: when stderr is a terminal)");
  cmd.add_flag("-q,--quiet", a.quiet, "No report on stdout");
  cmd.add_flag("--systemc", a.systemc, "Run the core inside the SystemC top");
  // Hidden: lets the tests see the co-simulation checker fire.
  cmd.add_option("--corrupt-reference", a.corrupt_reference,
                 "Test hook: change the expected record of ray K so the checker must report it")
      ->group("");
  cmd.add_flag("--which-model", a.which_model, "Print the model the scene needs and whether it is built; run nothing");
}

void CheckSimArgs(const SimArgs& a) {
  if (a.trace_ray >= 0 && a.trace.empty()) throw InputError("--trace-ray needs --trace FILE");
  if (a.mem_latency < 1) throw InputError("--mem-latency must be at least 1 cycle");
  if (!(a.mem_bw > 0) || !std::isfinite(a.mem_bw)) throw InputError("--mem-bw must be a positive number");
  if (a.timeout < 1) throw InputError("--timeout must be at least 1 cycle");
}

}  // namespace kdrt::sim
