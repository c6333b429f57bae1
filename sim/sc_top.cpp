#include "sim/sc_top.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <exception>
#include <memory>

// Verilator's headers first: seeing SystemC, they would expect a
// sc_time_stamp() of their own (this model is plain C++, not --sc).
#include "Vrt_core.h"
#include "sim/sim_ctrl.h"

#include <systemc>

namespace kdrt::sim {
namespace {

// The memory as a SystemC channel interface.
class MemoryIf : virtual public sc_core::sc_interface, public MemoryPort {};

// The memory module: the plain memory model behind a SystemC interface.
class ScMemory : public sc_core::sc_module, public MemoryIf {
 public:
  ScMemory(sc_core::sc_module_name name, const MemoryConfig& config, const std::vector<uint8_t>& image)
      : sc_core::sc_module(name), model_(config) {
    model_.LoadImage(image);
  }
  void Request(uint64_t addr, uint16_t tag, uint64_t cycle) override { model_.Request(addr, tag, cycle); }
  bool Respond(uint64_t cycle, MemoryResponse* out) override { return model_.Respond(cycle, out); }
  size_t outstanding() const override { return model_.outstanding(); }
  MemoryModel& model() { return model_; }

 private:
  MemoryModel model_;
};

// The core module: the Verilated rt_core and its harness, one cycle per
// rising edge of `clk`.
class ScCore : public sc_core::sc_module {
 public:
  sc_core::sc_in<bool> clk;
  sc_core::sc_port<MemoryIf> mem;

  SC_HAS_PROCESS(ScCore);
  // With a `queue`, the core takes its rays from it as core `index` and stops
  // the simulation only when all `*running` cores are done.
  ScCore(sc_core::sc_module_name name, const RunSpec& spec, RayQueue* queue = nullptr, int index = 0,
         int* running = nullptr)
      : sc_core::sc_module(name), spec_(spec), queue_(queue), index_(index), running_(running) {
    SC_METHOD(OnClock);
    sensitive << clk.pos();
    dont_initialize();
  }

  void start_of_simulation() override {
    HarnessOptions options = spec_.options;
    if (index_ > 0) options.progress = false;  // one progress line, core 0's (it counts every core's rays)
    harness_ = std::make_unique<CoreHarness>(ctrl_.top(), *spec_.image, *spec_.rays, *spec_.reference, *mem[0],
                                             options, queue_, index_);
    harness_->Start(ctrl_, index_ == 0 ? spec_.trace_path : std::string());
  }

  CoreHarness& harness() { return *harness_; }
  SimCtrl<Vrt_core>& ctrl() { return ctrl_; }
  std::exception_ptr failure() const { return failure_; }

 private:
  void OnClock() {
    if (finished_) return;
    if (harness_->Done()) {
      finished_ = true;
      if (running_ == nullptr || --*running_ == 0) sc_core::sc_stop();
      return;
    }
    try {
      harness_->Cycle(ctrl_);
    } catch (...) {
      // Exceptions must not cross the SystemC kernel: stop, rethrow later.
      failure_ = std::current_exception();
      sc_core::sc_stop();
    }
  }

  const RunSpec& spec_;
  RayQueue* queue_;
  int index_;
  int* running_;
  bool finished_ = false;
  SimCtrl<Vrt_core> ctrl_;
  std::unique_ptr<CoreHarness> harness_;
  std::exception_ptr failure_;
};

// The shared L2 as a SystemC module: one MemoryIf channel per core, each
// forwarding to the plain SharedL2's port for that core.
class ScL2 : public sc_core::sc_module {
 public:
  ScL2(sc_core::sc_module_name name, const L2Config& config, MemoryModel& memory, const std::vector<uint8_t>& image,
       int cores)
      : sc_core::sc_module(name), l2_(config, memory, image, cores) {
    for (int k = 0; k < cores; ++k) ports_.push_back(std::make_unique<CorePort>(l2_.port(k)));
  }
  MemoryIf& port(int core) { return *ports_[core]; }
  const SharedL2& l2() const { return l2_; }

 private:
  class CorePort : public MemoryIf {
   public:
    explicit CorePort(MemoryPort& p) : p_(p) {}
    void Request(uint64_t addr, uint16_t tag, uint64_t cycle) override { p_.Request(addr, tag, cycle); }
    bool Respond(uint64_t cycle, MemoryResponse* out) override { return p_.Respond(cycle, out); }
    size_t outstanding() const override { return p_.outstanding(); }

   private:
    MemoryPort& p_;
  };
  SharedL2 l2_;
  std::vector<std::unique_ptr<CorePort>> ports_;
};

// What every SystemC run starts with: no banner or info messages from the
// kernel, and the memory image as the memory module loads it.
std::vector<uint8_t> QuietKernelAndImage(const RunSpec& spec) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  return std::vector<uint8_t>(spec.image->data(), spec.image->data() + spec.image->size());
}

}  // namespace

SystemOutcome RunSystemCCores(const RunSpec& spec, int cores, const L2Config& l2_config, size_t chunk) {
  const std::vector<uint8_t> image = QuietKernelAndImage(spec);
  sc_core::sc_clock clock("clock", 10, sc_core::SC_NS);
  ScMemory memory("memory", spec.memory, image);
  ScL2 l2("l2", l2_config, memory.model(), image, cores);
  RayQueue queue(spec.rays->size(), cores, chunk, spec.options.order);
  int running = cores;
  std::vector<std::unique_ptr<ScCore>> core;
  for (int k = 0; k < cores; ++k) {
    core.push_back(std::make_unique<ScCore>(("core" + std::to_string(k)).c_str(), spec, &queue, k, &running));
    core[k]->clk(clock);
    core[k]->mem(l2.port(k));
  }
  const auto start = std::chrono::steady_clock::now();
  sc_core::sc_start();
  SystemOutcome out;
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (int k = 0; k < cores; ++k) {
    if (core[k]->failure()) std::rethrow_exception(core[k]->failure());
  }
  for (int k = 0; k < cores; ++k) {
    out.cores.push_back(core[k]->harness().Finish(core[k]->ctrl(), memory.model()));
    out.cycles = std::max(out.cycles, out.cores.back().result.cycles);
  }
  out.mem_bytes_read = memory.model().bytes_read();
  out.mem_requests = memory.model().requests();
  out.mem_max_outstanding = memory.model().max_outstanding();
  out.l2 = l2.l2().stats();
  out.l2_config = l2_config;
  return out;
}

RunOutcome RunSystemC(const RunSpec& spec) {
  const std::vector<uint8_t> image = QuietKernelAndImage(spec);
  sc_core::sc_clock clock("clock", 10, sc_core::SC_NS);
  ScMemory memory("memory", spec.memory, image);
  ScCore core("core", spec);
  core.clk(clock);
  core.mem(memory);

  sc_core::sc_start();
  if (core.failure()) std::rethrow_exception(core.failure());
  return core.harness().Finish(core.ctrl(), memory.model());
}

}  // namespace kdrt::sim
