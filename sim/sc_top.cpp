#include "sim/sc_top.h"

#include <cstdlib>
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
  const MemoryModel& model() const { return model_; }

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
  ScCore(sc_core::sc_module_name name, const RunSpec& spec) : sc_core::sc_module(name), spec_(spec) {
    SC_METHOD(OnClock);
    sensitive << clk.pos();
    dont_initialize();
  }

  void start_of_simulation() override {
    harness_ = std::make_unique<CoreHarness>(ctrl_.top(), *spec_.image, *spec_.rays, *spec_.reference, *mem[0],
                                             spec_.options);
    harness_->Start(ctrl_, spec_.trace_path);
  }

  CoreHarness& harness() { return *harness_; }
  SimCtrl<Vrt_core>& ctrl() { return ctrl_; }
  std::exception_ptr failure() const { return failure_; }

 private:
  void OnClock() {
    if (harness_->Done()) {
      sc_core::sc_stop();
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
  SimCtrl<Vrt_core> ctrl_;
  std::unique_ptr<CoreHarness> harness_;
  std::exception_ptr failure_;
};

}  // namespace

RunOutcome RunSystemC(const RunSpec& spec) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  const std::vector<uint8_t> image(spec.image->data(), spec.image->data() + spec.image->size());
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
