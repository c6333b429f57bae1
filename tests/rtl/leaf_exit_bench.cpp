// Verilator bench of rtl/rt_leaf_exit.sv against a C++ model, per preset,
// cycle by cycle: the round-robin choice among the threads asking to exit
// (asked a cycle ahead: req_next_i is the next cycle's requests) but the one
// chosen in the cycle before, announced in the next cycle (sel_valid_o) and
// exiting in the one after,
// per-thread stacks of (node, t0, t1) entries (push_full_o, a push onto a full
// stack dropped, the pop winning over the push and the push over the clear
// when they name the same thread), and the exit rule of TraceRay after a leaf
// (sw/trace/traversal.h) with the model's comparisons (fp::Le, fp::Lt):
//   done = (hit && any) || stack empty
//          || (hit && no entry with a NaN t0 on the stack && (best.t <= t1 || best.t < top.t0))
// (an entry with a NaN t0 is the far child of a ray lying in a split plane,
// InPlane in traversal.h) and, when the thread goes on, the popped entry. Values come from a small
// pool of random encodings of the format (with zeros, infinities and NaNs)
// so that ties are frequent; clears, pushes and exit requests are random in
// regimes that fill the stacks, drain them, or mix.
#include <algorithm>
#include <array>
#include <cstdio>
#include <vector>

#include "Vrt_leaf_exit_bf16.h"
#include "Vrt_leaf_exit_fp16.h"
#include "Vrt_leaf_exit_fp24.h"
#include "Vrt_leaf_exit_fp32.h"
#include "fp/format.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using fp::Format;
using sim::SimCtrl;

// As verilated (tests/rtl/CMakeLists.txt): Threads 3 (not a power of two),
// StackDepth 5, NodeIdxWidth 8.
constexpr unsigned kThreads = 3;
constexpr size_t kDepth = 5;
constexpr uint32_t kNodeMask = 0xFF;

struct Entry {
  uint32_t node, t0, t1;
  bool empty;  // the pushed node's empty-leaf mark
};

uint32_t RandomValue(Format f, Rng& rng) {
  const uint32_t exp_ones = ((1u << f.e) - 1) << f.m;
  switch (rng.Below(10)) {
    case 0: return 0;
    case 1: return 1u << (f.e + f.m);                        // -0
    case 2: return exp_ones;                                  // +inf
    case 3: return exp_ones | (rng.Bits32() & ((1u << f.m) - 1)) | 1u;  // NaN
    default: return rng.Bits32() & f.WidthMask() & ~(1u << (f.e + f.m));  // mostly positive
  }
}

template <class Dut>
bool Run(Format f, uint64_t cycles) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  dut.clear_i = 0;
  dut.push_i = 0;
  dut.req_next_i = 0;
  sim.Reset();
  unsigned req = 0;  // this cycle's requests, given as req_next_i in the previous cycle
  Rng rng(31 + f.m);
  std::array<std::vector<Entry>, kThreads> model;
  unsigned last = kThreads - 1;  // the arbiter's pointer after reset
  bool chosen = false;           // the thread chosen in the previous cycle: it exits in this one
  unsigned chosen_idx = 0;
  std::array<uint32_t, 6> pool{};
  double p_push = 0.5, p_req = 0.5, p_clear = 0.05, p_hit = 0.5;
  uint64_t exits = 0, masked = 0, by_any = 0, by_t1 = 0, by_empty = 0, by_pop_t0 = 0, held = 0, pops = 0, dropped = 0;
  for (uint64_t cycle = 0; cycle < cycles; ++cycle) {
    if (cycle % 200 == 0) {
      const unsigned regime = rng.Below(3);  // fill, drain, mix
      p_push = regime == 0 ? 0.8 : regime == 1 ? 0.1 : 0.5;
      p_req = regime == 0 ? 0.2 : regime == 1 ? 0.8 : 0.5;
      p_clear = rng.Chance(0.5) ? 0.0 : 0.05;
      p_hit = std::array<double, 3>{0.0, 0.5, 0.9}[rng.Below(3)];
      for (uint32_t& v : pool) v = RandomValue(f, rng);
    }
    auto value = [&] { return rng.Chance(0.9) ? pool[rng.Below(pool.size())] : RandomValue(f, rng); };
    const bool clear = rng.Chance(p_clear), push = rng.Chance(p_push);
    const unsigned ci = rng.Below(kThreads), ui = rng.Below(kThreads);
    unsigned req_next = 0;
    for (unsigned t = 0; t < kThreads; ++t) req_next |= static_cast<unsigned>(rng.Chance(p_req)) << t;
    const Entry data{rng.Bits32() & kNodeMask, value(), value(), rng.Chance(0.5)};
    const bool hit = rng.Chance(p_hit);
    const bool any = rng.Chance(0.25);
    const uint32_t best_t = value(), t1 = value();
    dut.clear_i = clear;
    dut.clear_idx_i = ci;
    dut.push_i = push;
    dut.push_idx_i = ui;
    dut.push_node_i = data.node;
    dut.push_t0_i = data.t0;
    dut.push_t1_i = data.t1;
    dut.push_empty_i = data.empty;
    dut.req_next_i = req_next;
    dut.exit_hit_i = hit;
    dut.exit_any_i = any;
    dut.exit_best_t_i = best_t;
    dut.exit_t1_i = t1;
    sim.Settle();
    // The model's choice: the first requester after `last`, wrapping around,
    // but the thread chosen in the cycle before; the exit: that thread.
    const unsigned req_open = req & ~(chosen ? 1u << chosen_idx : 0u);
    bool sel = false;
    unsigned sel_idx = 0;
    for (unsigned k = 1; k <= kThreads && !sel; ++k) {
      const unsigned i = (last + k) % kThreads;
      if (req_open >> i & 1) {
        sel = true;
        sel_idx = i;
      }
    }
    masked += req_open != req;
    const bool valid = chosen;
    const unsigned idx = chosen_idx;
    const bool full = model[ui].size() == kDepth;
    bool done = false;
    if (valid) {
      const std::vector<Entry>& s = model[idx];
      const bool empty = s.empty();
      const bool in_plane = std::any_of(s.begin(), s.end(), [&](const Entry& e) { return fp::IsNaN(f, e.t0); });
      const bool le_t1 = hit && fp::Le(f, best_t, t1);
      const bool lt_pop = hit && !empty && fp::Lt(f, best_t, s.back().t0);
      const bool by_any_hit = hit && any, by_rule = !in_plane && (le_t1 || lt_pop);
      done = by_any_hit || empty || by_rule;
      by_any += by_any_hit && !empty && !by_rule;
      by_t1 += !by_any_hit && !in_plane && le_t1;
      by_empty += !by_any_hit && empty && !le_t1;
      by_pop_t0 += !by_any_hit && !in_plane && !le_t1 && lt_pop;
      held += !done && (le_t1 || lt_pop);
    }
    bool bad = static_cast<bool>(dut.exit_valid_o) != valid || static_cast<bool>(dut.push_full_o) != full ||
               static_cast<bool>(dut.sel_valid_o) != sel || (sel && dut.sel_idx_o != sel_idx);
    if (valid) {
      bad = bad || dut.exit_idx_o != idx || static_cast<bool>(dut.exit_done_o) != done;
      if (!model[idx].empty()) {
        const Entry& top = model[idx].back();
        bad = bad || dut.pop_node_o != top.node || dut.pop_t0_o != top.t0 || dut.pop_t1_o != top.t1 ||
              static_cast<bool>(dut.pop_empty_o) != top.empty;
      }
    }
    if (bad) {
      std::printf("rt_leaf_exit %s: FAIL at cycle %llu: chosen %d %u; exit valid %d idx %u done %d full %d (model "
                  "%d %u; %d %u %d %d)\n",
                  f.Name().c_str(), static_cast<unsigned long long>(cycle), dut.sel_valid_o, dut.sel_idx_o,
                  dut.exit_valid_o, dut.exit_idx_o, dut.exit_done_o, dut.push_full_o, sel, sel_idx, valid, idx, done,
                  full);
      std::printf("  hit %d best_t 0x%08x t1 0x%08x; rtl top node 0x%02x t0 0x%08x t1 0x%08x (%zu entries)\n", hit,
                  best_t, t1, dut.pop_node_o, dut.pop_t0_o, dut.pop_t1_o, valid ? model[idx].size() : 0);
      return false;
    }
    sim.Tick();
    if (sel) last = sel_idx;
    exits += valid;
    chosen = sel;
    chosen_idx = sel_idx;
    const bool pop_ok = valid && !done, push_ok = push && !full;
    dropped += push && full;
    for (unsigned t = 0; t < kThreads; ++t) {
      if (pop_ok && idx == t) {
        model[t].pop_back();
        ++pops;
      } else if (push_ok && ui == t) {
        model[t].push_back(data);
      } else if (clear && ci == t) {
        model[t].clear();
      }
    }
    req = req_next;
  }
  auto u = [](uint64_t x) { return static_cast<unsigned long long>(x); };
  if (by_any == 0 || by_t1 == 0 || by_empty == 0 || by_pop_t0 == 0 || held == 0 || pops == 0 || dropped == 0 ||
      masked == 0) {
    std::printf("rt_leaf_exit %s: FAIL: the traffic missed a case (done by any-hit only %llu, by t1 %llu, empty %llu, "
                "popped t0 %llu; held by an in-plane entry %llu; pops %llu; pushes onto full stacks %llu; chosen "
                "threads asking again %llu)\n",
                f.Name().c_str(), u(by_any), u(by_t1), u(by_empty), u(by_pop_t0), u(held), u(pops), u(dropped),
                u(masked));
    return false;
  }
  std::printf("rt_leaf_exit %s: PASS (%llu cycles, %llu exits: done by any-hit only %llu, by t1 %llu, empty %llu, "
              "popped t0 %llu; held by an in-plane entry %llu; %llu pops; %llu pushes onto full stacks)\n",
              f.Name().c_str(), u(cycles), u(exits), u(by_any), u(by_t1), u(by_empty), u(by_pop_t0), u(held), u(pops),
              u(dropped));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  using namespace kdrt::fp;
  Verilated::commandArgs(argc, argv);
  const uint64_t cycles = LongRun() ? 10000000 : 1000000;
  bool ok = Run<Vrt_leaf_exit_fp32>(kFp32, cycles);
  ok = Run<Vrt_leaf_exit_fp24>(kFp24, cycles) && ok;
  ok = Run<Vrt_leaf_exit_bf16>(kBf16, cycles) && ok;
  ok = Run<Vrt_leaf_exit_fp16>(kFp16, cycles) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
