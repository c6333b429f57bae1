// Verilator bench of rtl/rt_thread_stack.sv against per-thread C++ stacks,
// cycle by cycle: push_full_o of the pushed thread, top_empty_o and top_o
// (the top of the stack of the thread read_idx_i named two cycles before,
// when it has one, whatever the two cycles did to it), a push onto a full stack
// dropped, a pop of an empty stack ignored, and when a clear, a push and a
// pop name the same thread in one cycle: the pop wins over the push, the push
// over the clear. A thread read in two cycles in a row is not popped after
// the first read (rt_thread_stack's rule). Random reads, clears, pushes and
// pops with idle cycles, in regimes
// that fill the stacks, drain them, or mix. The memory in one bank and in
// banks of 4 words (BankWords = 4: 15 words in 4 banks, the last of 3).
#include <array>
#include <cstdio>
#include <vector>

#include "Vrt_thread_stack.h"
#include "Vrt_thread_stack_banks.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using sim::SimCtrl;

// As verilated (tests/rtl/CMakeLists.txt): Threads 3 (not a power of two),
// StackDepth 5, Width 20.
constexpr unsigned kThreads = 3;
constexpr size_t kDepth = 5;
constexpr uint32_t kMask = 0xFFFFF;

template <class Dut>
bool Run(const char* name, uint64_t cycles) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  dut.clear_i = 0;
  dut.push_i = 0;
  dut.pop_i = 0;
  dut.read_i = 0;
  dut.read_idx_i = 0;
  sim.Reset();
  // The reads of the previous cycle (r1) and the one before (oi, oi_valid:
  // the thread top_o shows and pop_i pops).
  unsigned oi = 0, r1 = 0;
  bool oi_valid = false, r1_valid = false;
  Rng rng(11);
  std::array<std::vector<uint32_t>, kThreads> model;
  double p_push = 0.5, p_pop = 0.5, p_clear = 0.05;
  uint64_t pushes = 0, pops = 0, dropped = 0, full_seen = 0, collisions = 0, read_changed = 0, reread = 0;
  for (uint64_t cycle = 0; cycle < cycles; ++cycle) {
    if (cycle % 200 == 0) {
      const unsigned regime = rng.Below(3);  // fill, drain, mix
      p_push = regime == 0 ? 0.8 : regime == 1 ? 0.1 : 0.5;
      p_pop = regime == 0 ? 0.1 : regime == 1 ? 0.8 : 0.5;
      p_clear = rng.Chance(0.5) ? 0.0 : 0.05;
    }
    const bool clear = rng.Chance(p_clear), push = rng.Chance(p_push), read = rng.Chance(0.9);
    const bool pop = oi_valid && !(r1_valid && r1 == oi) && rng.Chance(p_pop);
    const unsigned ci = rng.Below(kThreads), ui = rng.Below(kThreads), ri = rng.Below(kThreads);
    const uint32_t data = rng.Bits32() & kMask;
    dut.clear_i = clear;
    dut.clear_idx_i = ci;
    dut.push_i = push;
    dut.push_idx_i = ui;
    dut.push_data_i = data;
    dut.pop_i = pop;
    dut.read_i = read;
    dut.read_idx_i = ri;
    sim.Settle();
    const bool full = model[ui].size() == kDepth, empty = model[oi].empty();
    if (static_cast<bool>(dut.push_full_o) != full || (oi_valid && static_cast<bool>(dut.top_empty_o) != empty) ||
        (oi_valid && !empty && dut.top_o != model[oi].back())) {
      std::printf("rt_thread_stack (%s): FAIL at cycle %llu: push thread %u (%zu entries): full %d; pop thread %u "
                  "(%zu entries): empty %d top 0x%05x, model 0x%05x\n",
                  name, static_cast<unsigned long long>(cycle), ui, model[ui].size(), dut.push_full_o, oi,
                  model[oi].size(), dut.top_empty_o, dut.top_o, empty ? 0 : model[oi].back());
      return false;
    }
    sim.Tick();
    full_seen += full;
    const bool pop_ok = pop && !empty, push_ok = push && !full;
    collisions += (pop_ok && push_ok && ui == oi) || (push_ok && clear && ci == ui);
    dropped += push && full;
    // One stack pointer change per thread: pop, else push, else clear. The
    // pushed entry is written even when the pop wins: it lies above the top.
    for (unsigned t = 0; t < kThreads; ++t) {
      if (pop_ok && oi == t) {
        model[t].pop_back();
        ++pops;
      } else if (push_ok && ui == t) {
        model[t].push_back(data);
        ++pushes;
      } else if (clear && ci == t) {
        model[t].clear();
      }
    }
    // A stack changed between its read and its top's cycle.
    read_changed += r1_valid && ((pop_ok && oi == r1) || (push_ok && ui == r1) || (clear && ci == r1));
    read_changed += read && ((pop_ok && oi == ri) || (push_ok && ui == ri) || (clear && ci == ri));
    reread += read && r1_valid && ri == r1;
    oi = r1;
    oi_valid = r1_valid;
    r1 = ri;
    r1_valid = read;
  }
  if (full_seen == 0 || dropped == 0 || collisions == 0 || read_changed == 0 || reread == 0) {
    std::printf("rt_thread_stack (%s): FAIL: the traffic never filled a stack, never collided, never changed a "
                "stack while it was read or never read a thread twice in a row\n",
                name);
    return false;
  }
  std::printf("rt_thread_stack (%s): PASS (%llu cycles, %llu pushes, %llu pops, %llu pushes onto full stacks, "
              "%llu same-thread collisions, %llu stacks changed as they were read, %llu reads twice in a row)\n",
              name, static_cast<unsigned long long>(cycles), static_cast<unsigned long long>(pushes),
              static_cast<unsigned long long>(pops), static_cast<unsigned long long>(dropped),
              static_cast<unsigned long long>(collisions), static_cast<unsigned long long>(read_changed),
              static_cast<unsigned long long>(reread));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t cycles = LongRun() ? 10000000 : 1000000;
  bool ok = Run<Vrt_thread_stack>("one bank", cycles);
  ok = Run<Vrt_thread_stack_banks>("BankWords 4", cycles) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
