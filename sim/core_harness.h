// The harness around one Verilated rt_core (docs/core-interface.md): the
// configuration from the image header, a ray feeder (ray id = index in the
// ray list), a hit collector (any order), the memory model on the memory
// port, perf_o event counters, and an ibex-style co-simulation checker that
// compares every hit record, as it leaves the RTL, with the reference model.
//
// The harness does not own the clock: a cycle is BeginCycle() (drive the
// inputs), evaluate with the clock low, EndCycle() (sample the outputs and
// the handshakes of this cycle), rising edge. The plain Verilator loop
// (Run) and the SystemC top both drive it this way, so both give the same
// cycles.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/ray.h"
#include "sim/memory_model.h"
#include "trace/memory_image.h"
#include "trace/tracer.h"

class Vrt_core;

namespace kdrt::sim {

inline constexpr int kPerfBits = 16;

// The run cannot go on: a co-simulation mismatch, a timeout or a protocol
// violation. The message is the whole report.
class SimFailure : public std::runtime_error {
 public:
  explicit SimFailure(const std::string& what) : std::runtime_error(what) {}
};

struct HarnessOptions {
  TraceOptions reference;       // format of the model the RTL is compared with
  uint64_t timeout = 1000000;   // cycles without a hit record
  int64_t trace_ray = -1;       // waveform only while this ray is in flight
  bool progress = false;
};

struct HarnessResult {
  uint64_t cycles = 0;
  std::array<uint64_t, kPerfBits> perf{};  // cycles in which each perf_o bit was set
  std::vector<Hit> hits;                   // by ray id, as the RTL returned them
  std::vector<uint8_t> overflow;           // by ray id: the record had hit_overflow_o
  uint64_t overflows = 0;
  uint64_t hit_count = 0;
  uint64_t max_in_flight = 0;
  double wall_seconds = 0;
};

class CoreHarness {
 public:
  // `reference` holds the model's hit for every ray (TraceRays with the same
  // format). The harness keeps references to every argument.
  CoreHarness(Vrt_core& top, const ImageView& image, const std::vector<Ray>& rays,
              const std::vector<Hit>& reference, MemoryPort& memory, const HarnessOptions& options);

  // Static inputs (bases, bounds) and idle streams; call before reset.
  void Configure();

  // Drives ray, memory-response and hit-ready inputs for cycle `cycle`.
  void BeginCycle(uint64_t cycle);
  // After evaluating with the clock low: handshakes, perf events, checks.
  // Throws SimFailure on a mismatch, a protocol violation or a timeout.
  void EndCycle(uint64_t cycle);

  bool Done() const { return received_ == rays_.size(); }
  // Whether the waveform should be dumped this cycle (see --trace-ray).
  bool DumpWanted() const { return dump_wanted_; }

  // Counters so far; `cycles` is set by the caller.
  HarnessResult& result() { return result_; }

 private:
  void CheckHit(uint64_t cycle, uint32_t id, const Hit& got, bool overflow);
  void Progress(uint64_t cycle, bool final_line);

  Vrt_core& top_;
  const ImageView& image_;
  const std::vector<Ray>& rays_;
  const std::vector<Hit>& reference_;
  MemoryPort& memory_;
  HarnessOptions options_;
  HarnessResult result_;
  std::vector<uint8_t> received_flag_;
  size_t next_ray_ = 0;
  size_t received_ = 0;
  uint64_t in_flight_ = 0;
  uint64_t last_hit_cycle_ = 0;
  bool resp_driven_ = false;
  bool dump_wanted_ = true;
  std::chrono::steady_clock::time_point start_, last_progress_;
};

// Everything one run needs; the pointers must outlive the run.
struct RunSpec {
  const ImageView* image = nullptr;
  const std::vector<Ray>* rays = nullptr;
  const std::vector<Hit>* reference = nullptr;
  MemoryConfig memory;
  HarnessOptions options;
  std::string trace_path;  // FST waveform, or empty
};

struct RunOutcome {
  HarnessResult result;
  uint64_t mem_bytes_read = 0;
  uint64_t mem_requests = 0;
  uint64_t mem_max_outstanding = 0;
};

// The plain Verilator loop (sim/sim_ctrl.h) until every hit record is back.
RunOutcome RunVerilator(const RunSpec& spec);

}  // namespace kdrt::sim
