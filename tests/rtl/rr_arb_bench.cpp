// Verilator bench of rtl/rt_rr_arb.sv against a C++ model of the round-robin
// rule, in lock-step: each cycle the grant (valid_o, idx_o) is the first
// requester after the last acknowledged grant, searching last + 1, last + 2,
// ... modulo N and ending at last itself (the pointer starts at N - 1, so
// the first search starts at 0); idx_o is 0 when nothing is requested. An
// acknowledged grant moves the pointer, an unacknowledged one leaves it.
// Requests and acknowledgements are random, in regimes of densities (one
// requester in a hundred to all, acknowledged always to rarely), with a reset
// in the middle of the run. N = 1, 2, 3, 5 (not powers of two), 32 and 128;
// every requester must be granted, and at 2 and more a grant must wrap past
// the last index. The fast model's arbiter (sim/fast_units.h: fast::RrArb
// over a fast::ThreadSet) runs beside it on the same requests and
// acknowledgements and must grant the same requester every cycle.
#include <cstdio>
#include <vector>

#include "Vrt_rr_arb_n1.h"
#include "Vrt_rr_arb_n128.h"
#include "Vrt_rr_arb_n2.h"
#include "Vrt_rr_arb_n3.h"
#include "Vrt_rr_arb_n32.h"
#include "Vrt_rr_arb_n5.h"
#include "sim/fast_units.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using sim::SimCtrl;

template <class Dut>
bool Run(unsigned n, uint64_t cycles) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  dut.ack_i = 0;
  for (unsigned i = 0; i < n; ++i) PutBits(dut.req_i, static_cast<int>(i), 1, 0);
  sim.Reset();
  Rng rng(11 + n);
  unsigned last = n - 1;
  sim::fast::RrArb fast(static_cast<int>(n));
  std::vector<bool> req(n);
  std::vector<uint64_t> granted(n);
  uint64_t wraps = 0, held = 0;
  const double densities[] = {0.01, 0.05, 0.2, 0.5, 0.9, 1.0};
  const double acks[] = {1.0, 0.7, 0.2};
  double p_req = 0.5, p_ack = 1.0;
  for (uint64_t cycle = 0; cycle < cycles; ++cycle) {
    if (cycle % 200 == 0) {
      p_req = densities[rng.Below(6)];
      p_ack = acks[rng.Below(3)];
    }
    if (cycle == cycles / 2) {
      sim.Reset();
      last = n - 1;
      fast = sim::fast::RrArb(static_cast<int>(n));
    }
    sim::fast::ThreadSet fast_req(static_cast<int>(n));
    for (unsigned i = 0; i < n; ++i) {
      req[i] = rng.Chance(p_req);
      PutBits(dut.req_i, static_cast<int>(i), 1, req[i]);
      if (req[i]) fast_req.Set(static_cast<int>(i));
    }
    const bool ack = rng.Chance(p_ack);
    dut.ack_i = ack;
    sim.Settle();

    bool valid = false;
    unsigned idx = 0;
    for (unsigned k = 1; k <= n && !valid; ++k) {
      const unsigned i = (last + k) % n;
      if (req[i]) {
        valid = true;
        idx = i;
      }
    }
    if (dut.valid_o != valid || dut.idx_o != idx) {
      std::printf("rt_rr_arb N=%u: FAIL at cycle %llu: last grant %u, requests", n,
                  static_cast<unsigned long long>(cycle), last);
      for (unsigned i = 0; i < n; ++i) {
        if (req[i]) std::printf(" %u", i);
      }
      std::printf(": valid_o %u idx_o %u, expected %u %u\n", static_cast<unsigned>(dut.valid_o),
                  static_cast<unsigned>(dut.idx_o), valid, idx);
      return false;
    }
    const int fast_idx = fast.Pick(fast_req);
    if (fast_idx != (dut.valid_o ? static_cast<int>(dut.idx_o) : -1)) {
      std::printf("rt_rr_arb N=%u: FAIL at cycle %llu: the fast model's arbiter grants %d, the RTL %d\n", n,
                  static_cast<unsigned long long>(cycle), fast_idx, dut.valid_o ? static_cast<int>(dut.idx_o) : -1);
      return false;
    }
    if (ack) fast.Ack(fast_idx);
    sim.Tick();
    if (valid && ack) {
      ++granted[idx];
      wraps += idx <= last && n > 1;
      last = idx;
    } else {
      held += valid;
    }
  }
  bool covered = held > 0 && (n == 1 || wraps > 0);
  for (unsigned i = 0; i < n; ++i) covered = covered && granted[i] > 0;
  std::printf("rt_rr_arb N=%u: %s (%llu cycles, %llu grants that wrapped, %llu grants not acknowledged)\n", n,
              covered ? "PASS" : "FAIL: the traffic missed a requester or a wrap",
              static_cast<unsigned long long>(cycles), static_cast<unsigned long long>(wraps),
              static_cast<unsigned long long>(held));
  return covered;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t cycles = LongRun() ? 10000000 : 300000;
  // N must match the verilated parameters (tests/rtl/CMakeLists.txt).
  bool ok = Run<Vrt_rr_arb_n1>(1, cycles);
  ok = Run<Vrt_rr_arb_n2>(2, cycles) && ok;
  ok = Run<Vrt_rr_arb_n3>(3, cycles) && ok;
  ok = Run<Vrt_rr_arb_n5>(5, cycles) && ok;
  ok = Run<Vrt_rr_arb_n32>(32, cycles) && ok;
  ok = Run<Vrt_rr_arb_n128>(128, cycles) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
