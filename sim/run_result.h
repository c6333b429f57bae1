// What one run of the core returns: plain data, no Verilator types, so the
// report (sim/sim_report.h) builds without a model.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "common/ray.h"
#include "sim/l2_cache.h"
#include "sim/perf_layout.h"  // generated from perf_t in rtl/kdrt_pkg.sv

namespace kdrt::sim {

// The bit of perf_o named `name`; in a constant expression, a name that is
// not a perf_t field of rtl/kdrt_pkg.sv is a compile-time error.
constexpr int PerfBit(std::string_view name) {
  for (int b = 0; b < kPerfBits; ++b) {
    if (name == kPerfFields[b].name) return b;
  }
  throw "no such perf_t field in rtl/kdrt_pkg.sv";
}

// rt_thread_fsm's states in the order of its state_e encoding (state_o).
inline constexpr const char* kThreadStateNames[8] = {"free", "setup", "fetch", "wait_node",
                                                     "trav", "leaf",  "exit",  "done"};

struct HarnessResult {
  uint64_t cycles = 0;
  std::array<uint64_t, kPerfBits> perf{};  // cycles in which each perf_o bit was set
  // thread-cycles spent in each rt_thread_fsm state (kThreadStateNames order)
  std::array<uint64_t, 8> thread_states{};
  std::vector<Hit> hits;                   // by ray id, as the RTL returned them
  std::vector<uint8_t> overflow;           // by ray id: the record had hit_overflow_o
  uint64_t overflows = 0;
  uint64_t hit_count = 0;
  uint64_t max_in_flight = 0;
  uint64_t mem_requests = 0;       // 16-byte reads this core issued
  std::vector<uint32_t> ray_ids;   // the rays this core returned, in return order
  double wall_seconds = 0;
};

struct RunOutcome {
  HarnessResult result;
  uint64_t mem_bytes_read = 0;
  uint64_t mem_requests = 0;
  uint64_t mem_max_outstanding = 0;
};

// Several cores sharing an L2 (sim/sc_top.h, RunSystemCCores).
struct SystemOutcome {
  std::vector<RunOutcome> cores;  // cycles: when the core returned its last ray
  uint64_t cycles = 0;            // the last core's
  uint64_t mem_bytes_read = 0, mem_requests = 0, mem_max_outstanding = 0;
  L2Config l2_config;
  L2Stats l2;
  double wall_seconds = 0;
};

}  // namespace kdrt::sim
