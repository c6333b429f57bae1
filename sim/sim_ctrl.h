// Simulation control for a Verilated top with a clk_i / rst_ni pair, in the
// manner of ZipCPU's TESTB and ibex's VerilatorSimCtrl: it owns the model,
// drives the clock and the reset, counts cycles and writes an FST waveform
// on request (all of it or only the cycles the caller enables).
//
// One cycle is split in two so the caller sees a settled design before the
// edge: Settle() (evaluate with the inputs the caller has just set, clock
// low; outputs and handshakes of this cycle are then valid), then Tick()
// (rising edge, falling edge).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <verilated.h>
#include <verilated_fst_c.h>

namespace kdrt::sim {

template <class Top>
class SimCtrl {
 public:
  SimCtrl() : context_(std::make_unique<VerilatedContext>()) {
    context_->traceEverOn(true);
    top_ = std::make_unique<Top>(context_.get(), "top");
    top_->clk_i = 0;
    top_->rst_ni = 0;
  }
  ~SimCtrl() { CloseTrace(); top_->final(); }
  SimCtrl(const SimCtrl&) = delete;
  SimCtrl& operator=(const SimCtrl&) = delete;

  Top& top() { return *top_; }
  uint64_t cycle() const { return cycle_; }

  // Starts an FST waveform; nothing is dumped while dumping is disabled.
  void OpenTrace(const std::string& path) {
    fst_ = std::make_unique<VerilatedFstC>();
    top_->trace(fst_.get(), 99);
    fst_->open(path.c_str());
    if (!fst_->isOpen()) throw std::runtime_error("cannot open waveform file " + path);
  }
  void CloseTrace() {
    if (fst_) {
      fst_->close();
      fst_.reset();
    }
  }
  bool tracing() const { return fst_ != nullptr; }
  void EnableDump(bool on) { dump_ = on; }

  // Holds rst_ni low for `cycles` cycles (the cycle counter does not run).
  void Reset(int cycles = 4) {
    top_->rst_ni = 0;
    for (int i = 0; i < cycles; ++i) {
      Settle();
      Edge();
    }
    top_->rst_ni = 1;
    cycle_ = 0;
  }

  // Evaluates the design with the current inputs before the rising edge.
  void Settle() {
    top_->clk_i = 0;
    top_->eval();
    Dump(0);
  }

  // The rising and falling edges; the cycle counter advances.
  void Tick() {
    Edge();
    ++cycle_;
  }

 private:
  void Edge() {
    top_->clk_i = 1;
    top_->eval();
    Dump(1);
    top_->clk_i = 0;
    top_->eval();
    ++phase_time_;
  }
  void Dump(int half) {
    if (fst_ && dump_) fst_->dump(phase_time_ * 10 + half * 5);
  }

  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Top> top_;
  std::unique_ptr<VerilatedFstC> fst_;
  bool dump_ = true;
  uint64_t cycle_ = 0;
  uint64_t phase_time_ = 0;  // cycles including reset, for waveform times
};

}  // namespace kdrt::sim
