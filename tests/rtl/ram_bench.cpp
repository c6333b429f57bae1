// Verilator bench of rtl/rt_ram_banked.sv (and through it rt_ram_1r1w.sv)
// against a C++ array, cycle by cycle: a read gives the word from the next
// cycle on and holds it until the next read, a read of the address written in
// the same cycle gives the word before the write, writes and reads of any
// banks in any cycle. One bank (Words <= BankWords: rt_ram_1r1w alone), four
// banks of 4 words, and 15 words in banks of 4 (the last of 3). Random reads
// and writes in regimes (mostly reads, mostly writes, sparse), and reads of
// the address being written.
#include <array>
#include <cstdio>
#include <vector>

#include "Vrt_ram_banked_b4.h"
#include "Vrt_ram_banked_b4r.h"
#include "Vrt_ram_banked_one.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using sim::SimCtrl;

constexpr uint32_t kMask = 0xFFF;  // Width = 12, as verilated

template <class Dut>
bool Run(const char* name, unsigned words, uint64_t cycles) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  dut.we_i = 0;
  dut.re_i = 0;
  sim.Reset();
  Rng rng(23 + words);
  std::vector<uint32_t> model(words, 0);
  // Every word written once first: the array has no reset.
  for (unsigned a = 0; a < words; ++a) {
    model[a] = rng.Bits32() & kMask;
    dut.we_i = 1;
    dut.waddr_i = a;
    dut.wdata_i = model[a];
    sim.Tick();
  }
  dut.we_i = 0;
  bool shown = false;  // a read happened: rdata_o is defined
  uint32_t expect = 0;
  double p_read = 0.5, p_write = 0.5;
  uint64_t reads = 0, writes = 0, same = 0, held = 0;
  for (uint64_t cycle = 0; cycle < cycles; ++cycle) {
    if (cycle % 128 == 0) {
      p_read = std::array<double, 3>{0.9, 0.5, 0.1}[rng.Below(3)];
      p_write = std::array<double, 3>{0.9, 0.5, 0.1}[rng.Below(3)];
    }
    const bool re = rng.Chance(p_read), we = rng.Chance(p_write);
    const unsigned waddr = rng.Below(words);
    const unsigned raddr = (we && rng.Chance(0.2)) ? waddr : rng.Below(words);
    const uint32_t wdata = rng.Bits32() & kMask;
    dut.re_i = re;
    dut.raddr_i = raddr;
    dut.we_i = we;
    dut.waddr_i = waddr;
    dut.wdata_i = wdata;
    sim.Settle();
    if (shown && dut.rdata_o != expect) {
      std::printf("rt_ram_banked (%s): FAIL at cycle %llu: rdata_o 0x%03x, the model 0x%03x\n", name,
                  static_cast<unsigned long long>(cycle), dut.rdata_o, expect);
      return false;
    }
    held += shown && !re;
    sim.Tick();
    if (re) {
      expect = model[raddr];  // read-first: the word before this cycle's write
      shown = true;
      ++reads;
      same += we && raddr == waddr;
    }
    if (we) {
      model[waddr] = wdata;
      ++writes;
    }
  }
  if (reads == 0 || writes == 0 || same == 0 || held == 0) {
    std::printf("rt_ram_banked (%s): FAIL: the traffic never read, wrote, read a word as it was written, or held\n",
                name);
    return false;
  }
  std::printf("rt_ram_banked (%s): PASS (%llu cycles, %llu reads, %llu writes, %llu reads of the word written, "
              "%llu cycles holding)\n",
              name, static_cast<unsigned long long>(cycles), static_cast<unsigned long long>(reads),
              static_cast<unsigned long long>(writes), static_cast<unsigned long long>(same),
              static_cast<unsigned long long>(held));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t cycles = LongRun() ? 10000000 : 1000000;
  // Words must match the verilated parameters (tests/rtl/CMakeLists.txt).
  bool ok = Run<Vrt_ram_banked_one>("16 words, one bank", 16, cycles);
  ok = Run<Vrt_ram_banked_b4>("16 words, banks of 4", 16, cycles) && ok;
  ok = Run<Vrt_ram_banked_b4r>("15 words, banks of 4", 15, cycles) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
