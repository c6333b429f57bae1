#include "sim/run_options.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "common/error.h"
#include "sim/memory_model.h"
#include "sim/ray_queue.h"

namespace kdrt::sim {

void AddRunOptions(CLI::App& cmd, RunOptions& o) {
  cmd.add_option("--mem-latency", o.mem_latency, "Memory latency in cycles (>= 1)")->capture_default_str();
  cmd.add_option("--mem-bw", o.mem_bw, "Memory bandwidth in bytes per cycle (fractions allowed; the port carries "
                                       "at most 16)")
      ->capture_default_str();
  cmd.add_option("--mem-size", o.mem_size, "Modelled memory in bytes (default: 2^address width)");
  cmd.add_flag("--allow-overflow", o.allow_overflow,
               "Accept a --stack-depth below the tree depth (overflowing rays are counted and reported)");
  cmd.add_option("--timeout", o.timeout, "Fail after this many cycles without a hit record")->capture_default_str();
  cmd.add_option("--trace", o.trace, "Write an FST waveform of the core");
  cmd.add_option("--trace-ray", o.trace_ray, "With --trace: dump only while ray K (its index) is in flight");
  cmd.add_flag("--progress", o.progress, "Progress line on stderr (default: when stderr is a terminal)");
  cmd.add_flag("--systemc", o.systemc, "Run the core inside the SystemC top");
  cmd.add_option("--cores", o.cores,
                 "Run N cores sharing an L2 cache and the memory (the RTL: SystemC system model; --model fast: "
                 "the fast model of it); rays from one shared queue (default: one core, no L2)")
      ->check(CLI::Range(1, 64));
  cmd.add_option("--l2-kb", o.l2_kb, "With --cores: L2 size in KiB (64-byte lines)")->capture_default_str();
  cmd.add_option("--l2-ways", o.l2_ways, "With --cores: L2 associativity (LRU)")->capture_default_str();
  cmd.add_option("--l2-latency", o.l2_latency, "With --cores: L2 hit latency in cycles")->capture_default_str();
  cmd.add_option("--ray-chunk", o.ray_chunk, "With --cores: consecutive rays a core takes from the queue at once")
      ->capture_default_str();
  cmd.add_option("--ray-order", o.ray_order,
                 "Order the camera's rays enter the core: linear (row by row), morton (along the Z-order "
                 "curve over the image, so the rays in flight are neighbours in 2D; --shade's passes by their "
                 "pixels) or morton:K (the Z-order cut into K runs, one ray of each in turn: the rays in flight "
                 "come from K regions; K from 1 to 256); a ray file is issued in its own order")
      ->check(CLI::Validator(
          [](std::string& v) {
            try {
              MortonStreams(v);
            } catch (const std::exception& e) {
              return std::string(e.what());
            }
            return std::string();
          },
          "linear|morton|morton:K"))
      ->capture_default_str();
  // Hidden: the frame's width for --ray-order morton (the front end passes
  // its camera's to the model).
  cmd.add_option("--frame-width", o.frame_width, "Width of the frame the rays are in, row by row")->group("");
  // Hidden: lets the tests see the co-simulation checker fire.
  cmd.add_option("--corrupt-reference", o.corrupt_reference,
                 "Test hook: change the expected record of ray K so the checker must report it")
      ->group("");
}

void CheckRunOptions(const RunOptions& o) {
  if (o.trace_ray >= 0 && o.trace.empty()) throw InputError("--trace-ray needs --trace FILE");
  if (o.mem_latency < 1) throw InputError("--mem-latency must be at least 1 cycle");
  if (!(o.mem_bw > 0) || !std::isfinite(o.mem_bw)) throw InputError("--mem-bw must be a positive number");
  if (o.timeout < 1) throw InputError("--timeout must be at least 1 cycle");
  if (o.cores > 0) {
    if (o.l2_ways < 1 || o.l2_kb < 1 || (o.l2_kb * 1024u) % (64u * o.l2_ways) != 0) {
      throw InputError("--l2-kb " + std::to_string(o.l2_kb) + " --l2-ways " + std::to_string(o.l2_ways) +
                       ": the L2 must hold a whole number of sets of 64-byte lines");
    }
    if (o.l2_latency < 1) throw InputError("--l2-latency must be at least 1 cycle");
    if (o.ray_chunk < 1) throw InputError("--ray-chunk must be at least 1");
  }
}

std::vector<std::string> RunOptionWarnings(const RunOptions& o) {
  std::vector<std::string> w;
  if (o.mem_bw > kBeatBytes) {
    char bw[32];
    std::snprintf(bw, sizeof bw, "%g", o.mem_bw);
    w.push_back(std::string("--mem-bw ") + bw + ": the memory answers one 16-byte beat a cycle, so this run has " +
                "16 bytes per cycle (and its memory bound is counted at 16)");
  }
  return w;
}

std::vector<std::string> RunOptionArgs(const RunOptions& o, const std::string& trace_path) {
  char bw[64];
  std::snprintf(bw, sizeof bw, "%.17g", o.mem_bw);
  std::vector<std::string> a = {"--mem-latency", std::to_string(o.mem_latency), "--mem-bw", bw,
                                "--timeout", std::to_string(o.timeout)};
  if (o.mem_size) a.insert(a.end(), {"--mem-size", std::to_string(o.mem_size)});
  if (o.allow_overflow) a.push_back("--allow-overflow");
  if (!trace_path.empty()) a.insert(a.end(), {"--trace", trace_path});
  if (o.trace_ray >= 0) a.insert(a.end(), {"--trace-ray", std::to_string(o.trace_ray)});
  if (o.progress) a.push_back("--progress");
  if (o.systemc) a.push_back("--systemc");
  if (o.cores > 0) {
    a.insert(a.end(), {"--cores", std::to_string(o.cores), "--l2-kb", std::to_string(o.l2_kb), "--l2-ways",
                       std::to_string(o.l2_ways), "--l2-latency", std::to_string(o.l2_latency), "--ray-chunk",
                       std::to_string(o.ray_chunk)});
  }
  if (o.ray_order != "linear") {
    a.insert(a.end(), {"--ray-order", o.ray_order, "--frame-width", std::to_string(o.frame_width)});
  }
  if (o.corrupt_reference >= 0) a.insert(a.end(), {"--corrupt-reference", std::to_string(o.corrupt_reference)});
  return a;
}

void AddParamOptions(CLI::App& cmd, ConfigOverrides& ov) {
  for (int i = 0; i < kParamCount; ++i) {
    const CoreParam& p = kCoreParams[i];
    if (p.flag[0] == '\0') continue;
    std::string help = std::string(1, static_cast<char>(std::toupper(p.what[0]))) + (p.what + 1) + " (" +
                       p.sv_name + "; default " + std::to_string(p.default_value);
    if (p.rule != SceneRule::kFixed) help += ", or what the scene needs";
    if (p.power_of_two) help += "; a power of two";
    cmd.add_option(p.flag, ov.value[i], help + ")");
  }
}

}  // namespace kdrt::sim
