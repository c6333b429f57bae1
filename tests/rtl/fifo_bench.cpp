// Verilator bench of rtl/rt_fifo.sv against a C++ queue of the same depth,
// cycle by cycle, with its entries in flip-flops (Ram = 0) and in a memory
// (Ram = 1), each driven by the same traffic (the same seed): in_ready_o is high
// exactly when the queue has room, out_valid_o exactly when it holds an entry
// written in an earlier cycle, out_data_o is the oldest entry, and a push and
// a pop may share a cycle. The producer offers in random bursts and holds
// each entry until it is taken (picorv32's rule); the consumer applies random
// backpressure in regimes (always ready, mostly ready, mostly stalled).
// Depths 1, 3 (not a power of two) and 4.
#include <cstdio>
#include <deque>

#include "Vrt_fifo_d1.h"
#include "Vrt_fifo_d3.h"
#include "Vrt_fifo_d4.h"
#include "Vrt_fifo_ram_d1.h"
#include "Vrt_fifo_ram_d3.h"
#include "Vrt_fifo_ram_d4.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using sim::SimCtrl;

constexpr uint32_t kMask = 0xFFFF;  // Width = 16, as verilated

template <class Dut>
bool Run(const char* unit, unsigned depth, uint64_t cycles) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  dut.in_valid_i = 0;
  dut.out_ready_i = 0;
  sim.Reset();
  Rng rng(17 + depth);
  std::deque<uint32_t> model;
  uint32_t pending = 0;
  bool offering = false;
  double p_offer = 0.5, p_ready = 0.5;
  uint64_t pushes = 0, pops = 0, full_cycles = 0;
  auto fail = [&](const char* what, uint64_t cycle) {
    std::printf("%s depth %u: FAIL at cycle %llu: %s (model holds %zu)\n", unit, depth,
                static_cast<unsigned long long>(cycle), what, model.size());
    return false;
  };
  for (uint64_t cycle = 0; cycle < cycles; ++cycle) {
    if (cycle % 256 == 0) {
      p_offer = std::array<double, 3>{0.9, 0.5, 0.1}[rng.Below(3)];
      p_ready = std::array<double, 4>{1.0, 0.9, 0.5, 0.1}[rng.Below(4)];
    }
    if (!offering && rng.Chance(p_offer)) {
      offering = true;
      pending = rng.Bits32() & kMask;
    }
    dut.in_valid_i = offering;
    dut.in_data_i = offering ? pending : (rng.Bits32() & kMask);  // don't-care while not valid
    dut.out_ready_i = rng.Chance(p_ready);
    sim.Settle();
    if (static_cast<bool>(dut.in_ready_o) != (model.size() < depth)) return fail("in_ready_o", cycle);
    if (static_cast<bool>(dut.out_valid_o) != !model.empty()) return fail("out_valid_o", cycle);
    if (!model.empty() && dut.out_data_o != model.front()) return fail("out_data_o is not the oldest entry", cycle);
    full_cycles += model.size() == depth;
    const bool push = dut.in_valid_i && dut.in_ready_o;
    const bool pop = dut.out_valid_o && dut.out_ready_i;
    sim.Tick();
    if (pop) {
      model.pop_front();
      ++pops;
    }
    if (push) {
      model.push_back(pending);
      offering = false;
      ++pushes;
    }
  }
  if (full_cycles == 0 || pops == 0) {
    std::printf("%s depth %u: FAIL: the traffic never filled the queue or never emptied it\n", unit, depth);
    return false;
  }
  std::printf("%s depth %u: PASS (%llu cycles, %llu pushes, %llu pops, full in %llu cycles)\n", unit, depth,
              static_cast<unsigned long long>(cycles), static_cast<unsigned long long>(pushes),
              static_cast<unsigned long long>(pops), static_cast<unsigned long long>(full_cycles));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t cycles = LongRun() ? 10000000 : 1000000;
  // Depths must match the verilated parameters (tests/rtl/CMakeLists.txt).
  const char* flops = "rt_fifo (flip-flops)";
  const char* ram = "rt_fifo (Ram = 1)";
  bool ok = Run<Vrt_fifo_d1>(flops, 1, cycles);
  ok = Run<Vrt_fifo_d3>(flops, 3, cycles) && ok;
  ok = Run<Vrt_fifo_d4>(flops, 4, cycles) && ok;
  ok = Run<Vrt_fifo_ram_d1>(ram, 1, cycles) && ok;
  ok = Run<Vrt_fifo_ram_d3>(ram, 3, cycles) && ok;
  ok = Run<Vrt_fifo_ram_d4>(ram, 4, cycles) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
