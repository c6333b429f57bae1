// Simulation control for a Verilated top with a clk_i / rst_ni pair, in the
// manner of ZipCPU's TESTB and ibex's VerilatorSimCtrl: it owns the model,
// drives the clock and the reset, counts cycles and writes an FST waveform
// on request (all of it or only the cycles the caller enables).
//
// One cycle is split in two so the caller sees a settled design before the
// edge: Settle() (evaluate with the inputs the caller has just set, clock
// low; outputs and handshakes of this cycle are then valid), then Tick()
// (rising edge, falling edge); Step() is both.
//
// Also used by the unit benches (tests/rtl/): a top without clk_i / rst_ni
// (a combinational unit) is only evaluated. Waveforms need a model verilated
// with --trace-fst (verilate(... TRACE_FST), which defines VM_TRACE_FST=1);
// in a target whose models are not traced (VM_TRACE_FST=0) OpenTrace()
// throws and nothing of the FST writer is linked.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include <verilated.h>
#if !defined(VM_TRACE_FST) || VM_TRACE_FST
#define KDRT_SIM_CTRL_FST 1
#include <verilated_fst_c.h>
#else
#define KDRT_SIM_CTRL_FST 0
#endif

namespace kdrt::sim {

namespace detail {
template <class T, class = void>
struct HasClock : std::false_type {};
template <class T>
struct HasClock<T, std::void_t<decltype(std::declval<T&>().clk_i)>> : std::true_type {};
template <class T, class = void>
struct HasReset : std::false_type {};
template <class T>
struct HasReset<T, std::void_t<decltype(std::declval<T&>().rst_ni)>> : std::true_type {};
}  // namespace detail

template <class Top>
class SimCtrl {
 public:
  static constexpr bool kClocked = detail::HasClock<Top>::value;
  // A clocked top without rst_ni (a memory) has nothing to reset.
  static constexpr bool kResettable = kClocked && detail::HasReset<Top>::value;

  SimCtrl() : context_(std::make_unique<VerilatedContext>()) {
    context_->traceEverOn(true);
    top_ = std::make_unique<Top>(context_.get(), "top");
    if constexpr (kClocked) top_->clk_i = 0;
    if constexpr (kResettable) top_->rst_ni = 0;
  }
  ~SimCtrl() { CloseTrace(); top_->final(); }
  SimCtrl(const SimCtrl&) = delete;
  SimCtrl& operator=(const SimCtrl&) = delete;

  Top& top() { return *top_; }
  uint64_t cycle() const { return cycle_; }

  // Starts an FST waveform; nothing is dumped while dumping is disabled.
  void OpenTrace(const std::string& path) {
#if KDRT_SIM_CTRL_FST
    fst_ = std::make_unique<VerilatedFstC>();
    top_->trace(fst_.get(), 99);
    fst_->open(path.c_str());
    if (!fst_->isOpen()) throw std::runtime_error("cannot open waveform file " + path);
#else
#if defined(KDRT_SIM_QUICK_BUILD)
    throw std::runtime_error("cannot write " + path +
                             ": a quick model build (KDRT_QUICK_MODELS) has no waveforms; unset KDRT_QUICK_MODELS");
#else
    throw std::runtime_error("cannot write " + path + ": the model was verilated without --trace-fst");
#endif
#endif
  }
  void CloseTrace() {
#if KDRT_SIM_CTRL_FST
    if (fst_) {
      fst_->close();
      fst_.reset();
    }
#endif
  }
#if KDRT_SIM_CTRL_FST
  bool tracing() const { return fst_ != nullptr; }
#else
  bool tracing() const { return false; }
#endif
  void EnableDump(bool on) { dump_ = on; }

  // Holds rst_ni low for `cycles` cycles (the cycle counter does not run); a
  // top without rst_ni is left as it is.
  void Reset(int cycles = 4) {
    if constexpr (kResettable) {
      top_->rst_ni = 0;
      for (int i = 0; i < cycles; ++i) {
        Settle();
        Edge();
      }
      top_->rst_ni = 1;
      after_rising_edge_ = false;  // rst_ni rose unevaluated: the next Settle() evaluates
    }
    cycle_ = 0;
  }

  // Evaluates the design with the current inputs before the rising edge.
  void Settle() {
    if constexpr (kClocked) top_->clk_i = 0;
    top_->eval();
    clock_low_evaluated_ = true;
    after_rising_edge_ = false;
    Dump(0);
  }

  // Settle() for a cycle whose inputs are those the model last evaluated:
  // the rising edge's evaluation settled the design on them already, so
  // nothing is evaluated; `clock_fell(top)` tells the model that its clock
  // is low (Verilator compares the clock with its value at the last
  // evaluation to find the next rising edge). While a waveform is written,
  // or before the first edge, this is Settle().
  template <class ClockFell>
  void SettleUnchanged(ClockFell clock_fell) {
    if constexpr (kClocked) {
      if (after_rising_edge_ && !tracing()) {
        top_->clk_i = 0;
        clock_fell(*top_);
        clock_low_evaluated_ = true;
        return;
      }
    }
    Settle();
  }

  // The rising and falling edges; the cycle counter advances.
  void Tick() {
    Edge();
    ++cycle_;
  }

  // One whole cycle: Settle(), then Tick().
  void Step() {
    Settle();
    Tick();
  }

 private:
  // The falling edge is evaluated by the next Settle() (clock low, the new
  // inputs), not here as well: every eval() runs Verilator's logic from the
  // inputs again, which on the core is a large part of a cycle. Only a
  // Tick() that follows a Tick() without a Settle() between evaluates the
  // clock low first, so that the model sees the rising edge.
  void Edge() {
    if constexpr (kClocked) {
      if (!clock_low_evaluated_) {
        top_->clk_i = 0;
        top_->eval();
      }
      top_->clk_i = 1;
      top_->eval();
      clock_low_evaluated_ = false;
      after_rising_edge_ = true;
      Dump(1);
      top_->clk_i = 0;
    } else {
      top_->eval();
    }
    ++phase_time_;
  }
  void Dump([[maybe_unused]] int half) {
#if KDRT_SIM_CTRL_FST
    if (fst_ && dump_) fst_->dump(phase_time_ * 10 + half * 5);
#endif
  }

  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Top> top_;
#if KDRT_SIM_CTRL_FST
  std::unique_ptr<VerilatedFstC> fst_;
#endif
  bool dump_ = true;
  bool clock_low_evaluated_ = false;  // eval() has seen clk_i low since the last rising edge
  bool after_rising_edge_ = false;    // the last evaluation was a rising edge
  uint64_t cycle_ = 0;
  uint64_t phase_time_ = 0;  // cycles including reset, for waveform times
};

}  // namespace kdrt::sim
