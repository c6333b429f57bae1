// The options of one simulation run that the `kdrt sim` front end and the
// model executable share: the front end registers them on `kdrt sim`, checks
// them, and hands them to the model as command-line arguments; the model
// registers the very same options.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/core_params.h"

// Declared only: CLI11 is a heavy header, and most users of these options
// (the model runner, kdrt trade, the tests) never register them.
namespace CLI {
class App;
}  // namespace CLI

namespace kdrt::sim {

// The order `kdrt sim` and `kdrt trade` issue a camera's frame in: the
// Z-order cut into 8 runs, one ray of each in turn (sim/ray_queue.h,
// MortonStreams), so the rays in flight come from 8 regions of the frame
// and the traversal-heavy and test-heavy regions overlap (measured with
// the 256-line caches, 16 of 18 generator points at 90 % of the bound at
// 1024x1024 and latency 20, against 14 in plain Z-order; docs/core-efficiency.md).
inline constexpr const char* kFrameRayOrder = "morton:8";

struct RunOptions {
  uint32_t mem_latency = 20;
  double mem_bw = 16.0;
  uint64_t mem_size = 0;       // bytes of modelled memory; 0: 2^AddrWidth
  bool allow_overflow = false;  // accept a stack smaller than the tree needs
  uint64_t timeout = 1000000;  // cycles without a hit record
  std::string trace;           // FST waveform
  int64_t trace_ray = -1;      // dump only while this ray is in flight
  bool progress = false;
  bool systemc = false;
  // Several cores (the SystemC system model, or the fast model's): 0 = one core straight on the
  // memory (no L2); N >= 1 = N cores sharing an L2 in front of the memory.
  int cores = 0;
  uint32_t l2_kb = 256;
  uint32_t l2_ways = 8;
  uint32_t l2_latency = 10;
  uint32_t ray_chunk = 64;  // consecutive rays a core takes from the shared queue at once
  // The order the rays enter the core (sim/ray_queue.h, IssueOrder; the
  // front ends issue a camera's frame in kFrameRayOrder):
  // "linear", "morton" or "morton:K" over a row-major frame `frame_width`
  // pixels wide (the front end sets the width of its camera's frame).
  std::string ray_order = "linear";
  uint32_t frame_width = 0;
  int64_t corrupt_reference = -1;  // test hook: falsify the reference of this ray
};

void AddRunOptions(CLI::App& cmd, RunOptions& options);
// Throws InputError on inconsistent options (e.g. --trace-ray without --trace).
void CheckRunOptions(const RunOptions& options);

// What runs differently from what was asked (the run goes on): e.g. a
// --mem-bw above what the memory port carries.
std::vector<std::string> RunOptionWarnings(const RunOptions& options);
// The options as arguments for the model executable (trace: `trace_path`).
std::vector<std::string> RunOptionArgs(const RunOptions& options, const std::string& trace_path);

// One option per row of sim/core_params.def that has a flag (front end only:
// a model cannot change what it was built with).
void AddParamOptions(CLI::App& cmd, ConfigOverrides& overrides);

}  // namespace kdrt::sim
