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
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/ray.h"
#include "sim/core_params.h"
#include "sim/memory_model.h"
#include "sim/ray_queue.h"
#include "sim/run_result.h"
#include "trace/memory_image.h"
#include "trace/tracer.h"

class Vrt_core;

namespace kdrt::sim {

template <class Top>
class SimCtrl;

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
  // The issue order (position -> ray id; sim/ray_queue.h), or null/empty:
  // the list's order.
  const std::vector<uint32_t>* order = nullptr;
};

class CoreHarness {
 public:
  // `reference` holds the model's hit for every ray (TraceRays with the same
  // format). The harness keeps references to every argument. Without a
  // `queue` it sends every ray in order; with one it sends what `queue` gives
  // core `core` (hits and overflow flags stay indexed by ray id; the other
  // cores' entries stay empty).
  CoreHarness(Vrt_core& top, const ImageView& image, const std::vector<Ray>& rays,
              const std::vector<Hit>& reference, MemoryPort& memory, const HarnessOptions& options,
              RayQueue* queue = nullptr, int core = 0);

  // The start of every run, whatever loop drives the clock: static inputs
  // (bases, bounds), idle streams, the waveform (if `trace_path` is set), reset.
  void Start(SimCtrl<Vrt_core>& ctrl, const std::string& trace_path);
  // One clock cycle: drive the inputs, evaluate with the clock low, sample the
  // handshakes and check what left the core, rising edge. Throws SimFailure on
  // a mismatch, a protocol violation or a timeout.
  void Cycle(SimCtrl<Vrt_core>& ctrl);
  bool Done() const { return !has_pending_ && in_flight_ == 0 && queue_->Exhausted(core_); }
  uint64_t rays_returned() const { return received_; }
  // After the last cycle: the counters, the cycles, the memory's figures.
  RunOutcome Finish(SimCtrl<Vrt_core>& ctrl, const MemoryModel& memory);

 private:
  void Configure();
  // Drives ray, memory-response and hit-ready inputs for cycle `cycle`;
  // whether any of them differs from what the model last evaluated.
  bool BeginCycle(uint64_t cycle);
  // The inputs BeginCycle drives, as words.
  std::array<uint32_t, 19> DrivenInputs() const;
  // After evaluating with the clock low: handshakes, perf events, checks.
  void EndCycle(uint64_t cycle);
  void CheckHit(uint64_t cycle, uint32_t id, const Hit& got, bool overflow);
  void Progress(uint64_t cycle, bool final_line);

  Vrt_core& top_;
  const ImageView& image_;
  const std::vector<Ray>& rays_;
  const std::vector<Hit>& reference_;
  MemoryPort& memory_;
  HarnessOptions options_;
  HarnessResult result_;
  std::vector<uint8_t> received_flag_, sent_flag_;
  std::unique_ptr<RayQueue> own_queue_;
  RayQueue* queue_;
  int core_;
  bool has_pending_ = false;  // pending_ray_ is offered on ray_valid_i until taken
  size_t pending_ray_ = 0;
  size_t sent_ = 0;
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

// The plain Verilator loop (sim/sim_ctrl.h) until every hit record is back.
RunOutcome RunVerilator(const RunSpec& spec);

// The parameters the Verilated core of this executable was built with
// (rt_core's parameters are /*verilator public*/), and whether it is a quick
// build (KDRT_QUICK_MODELS). Defined beside the harness, the one file of a
// model executable besides sc_top.cpp that sees the Verilated classes, so
// that sim_main.cpp is compiled once for every model.
CoreConfig CompiledConfig();
bool QuickBuild();

}  // namespace kdrt::sim
