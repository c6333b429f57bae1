// Verilator bench of rtl/rt_perf_events.sv (combinational) against a C++
// model of rt_core's performance events: every bit of perf_o, found by its
// name in the layout generated from kdrt_pkg::perf_t (sim/perf_layout.h), for
// random handshakes and waits. Each input is set with a chance drawn per
// regime (rare, even, frequent), so that cycles without any progress (the
// stall_mem case) and every single event alone are common; exit requests are
// a random set of threads, and the exit taken and the one chosen next each
// one of them or any thread.
#include <array>
#include <cstdio>
#include <cstring>

#include "Vrt_perf_events.h"
#include "sim/perf_layout.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using sim::SimCtrl;

// As verilated (tests/rtl/CMakeLists.txt): Threads 5.
constexpr unsigned kThreads = 5;

int BitOf(const char* name) {
  for (int k = 0; k < sim::kPerfBits; ++k) {
    if (std::strcmp(sim::kPerfFields[k].name, name) == 0) return k;
  }
  std::printf("rt_perf_events: no field %s in perf_t\n", name);
  return -1;
}

bool Run(uint64_t vectors) {
  SimCtrl<Vrt_perf_events> sim;  // no clock: every check is one Settle()
  Vrt_perf_events& dut = sim.top();
  Rng rng(3);
  const char* const names[] = {"trav_busy", "list_busy",  "isect_busy",         "node_hit", "node_miss", "list_hit",
                               "list_miss", "tri_hit",    "tri_miss",           "stall_mem", "stall_stack",
                               "stall_backpressure",      "ray_in",             "ray_out",  "overflow",  "trav_leaf",
                               "busy", "node_wait", "list_wait", "tri_wait", "node_wait_inflight",
                               "list_wait_inflight", "tri_wait_inflight", "node_wait_mshr", "list_wait_mshr",
                               "tri_wait_mshr", "node_merge", "list_merge", "tri_merge", "trav_stall",
                               "isect_stall", "hit_stall", "list_prefetch"};
  constexpr int kNames = 33;
  static_assert(sizeof(names) / sizeof(names[0]) == kNames);
  if (sim::kPerfBits != kNames) {
    std::printf("rt_perf_events: FAIL: perf_t has %d fields, the bench checks %d\n", sim::kPerfBits, kNames);
    return false;
  }
  std::array<int, kNames> bit{};
  for (int i = 0; i < kNames; ++i) {
    bit[i] = BitOf(names[i]);
    if (bit[i] < 0) return false;
  }
  std::array<uint64_t, kNames> ones{};
  double p = 0.1;
  for (uint64_t n = 0; n < vectors; ++n) {
    if (n % 1000 == 0) p = std::array<double, 3>{0.03, 0.1, 0.5}[rng.Below(3)];
    auto b = [&] { return rng.Chance(p); };
    const bool busy = rng.Chance(0.8), ray_in = b(), clip = b(), node = b(), node_leaf = rng.Chance(0.5);
    const bool node_stall = b(), trav = b(), overflow = b(), list_req = b(), list_entry = b(), isect_in = b();
    const bool isect_stall = b(), isect_out = b(), out = b(), hit_valid = rng.Chance(0.5), hit_ready = b();
    const bool mem_wait = rng.Chance(0.5), node_wait = b(), list_wait = b(), tri_wait = b(), prefetch = b();
    unsigned exit_req = 0, cache_hit = 0, cache_miss = 0, merge = 0, wait_inflight = 0, wait_mshr = 0;
    for (unsigned t = 0; t < kThreads; ++t) exit_req |= static_cast<unsigned>(rng.Chance(p)) << t;
    for (unsigned c = 0; c < 3; ++c) {
      cache_hit |= static_cast<unsigned>(b()) << c;
      cache_miss |= static_cast<unsigned>(b()) << c;
      merge |= static_cast<unsigned>(b()) << c;
      wait_inflight |= static_cast<unsigned>(b()) << c;
      wait_mshr |= static_cast<unsigned>(b()) << c;
    }
    // The exit taken: as rt_core's arbiter, one of the requesters; or any thread.
    bool exit = exit_req != 0 && rng.Chance(0.9);
    unsigned exit_idx = rng.Below(kThreads);
    if (exit && rng.Chance(0.8)) {
      while (!(exit_req >> exit_idx & 1)) exit_idx = rng.Below(kThreads);
    }
    if (rng.Chance(0.02)) exit = b();
    // The thread chosen to exit next: another requester, or any thread.
    bool sel = exit_req != 0 && rng.Chance(0.7);
    unsigned sel_idx = rng.Below(kThreads);
    if (sel && rng.Chance(0.8)) {
      while (!(exit_req >> sel_idx & 1)) sel_idx = rng.Below(kThreads);
    }
    dut.busy_i = busy;
    dut.ray_in_i = ray_in;
    dut.clip_i = clip;
    dut.node_i = node;
    dut.node_leaf_i = node_leaf;
    dut.node_stall_i = node_stall;
    dut.trav_i = trav;
    dut.overflow_i = overflow;
    dut.list_req_i = list_req;
    dut.list_entry_i = list_entry;
    dut.isect_in_i = isect_in;
    dut.isect_stall_i = isect_stall;
    dut.isect_out_i = isect_out;
    dut.exit_req_i = exit_req;
    dut.exit_i = exit;
    dut.exit_idx_i = exit_idx;
    dut.exit_sel_i = sel;
    dut.exit_sel_idx_i = sel_idx;
    dut.out_i = out;
    dut.hit_valid_i = hit_valid;
    dut.hit_ready_i = hit_ready;
    dut.cache_hit_i = cache_hit;
    dut.cache_miss_i = cache_miss;
    dut.mem_wait_i = mem_wait;
    dut.node_wait_i = node_wait;
    dut.list_wait_i = list_wait;
    dut.tri_wait_i = tri_wait;
    dut.cache_merge_i = merge;
    dut.cache_wait_inflight_i = wait_inflight;
    dut.cache_wait_mshr_i = wait_mshr;
    dut.list_prefetch_i = prefetch;
    sim.Settle();

    const bool trav_in = node && !node_leaf, list_busy = list_req || list_entry;
    const bool progress =
        trav_in || list_busy || isect_in || exit || out || ray_in || clip || trav || isect_out;
    const unsigned taken = (exit ? 1u << exit_idx : 0) | (sel ? 1u << sel_idx : 0);
    const std::array<bool, kNames> want = {trav_in,
                                       list_busy,
                                       isect_in,
                                       (cache_hit & 1) != 0,
                                       (cache_miss & 1) != 0,
                                       (cache_hit & 2) != 0,
                                       (cache_miss & 2) != 0,
                                       (cache_hit & 4) != 0,
                                       (cache_miss & 4) != 0,
                                       busy && !progress && mem_wait,
                                       (exit_req & ~taken) != 0,
                                       (hit_valid && !hit_ready) || isect_stall || node_stall,
                                       ray_in,
                                       hit_valid && hit_ready,
                                       overflow,
                                       node && node_leaf,
                                       busy,
                                       node_wait,
                                       list_wait,
                                       tri_wait,
                                       (wait_inflight & 1) != 0,
                                       (wait_inflight & 2) != 0,
                                       (wait_inflight & 4) != 0,
                                       (wait_mshr & 1) != 0,
                                       (wait_mshr & 2) != 0,
                                       (wait_mshr & 4) != 0,
                                       (merge & 1) != 0,
                                       (merge & 2) != 0,
                                       (merge & 4) != 0,
                                       node_stall,
                                       isect_stall,
                                       hit_valid && !hit_ready,
                                       prefetch};
    for (int i = 0; i < kNames; ++i) {
      const bool got = (dut.perf_o >> bit[i] & 1) != 0;
      if (got != want[i]) {
        std::printf("rt_perf_events: FAIL at vector %llu: %s (bit %d) is %d, the model says %d (perf_o 0x%09llx)\n",
                    static_cast<unsigned long long>(n), names[i], bit[i], got, want[i],
                    static_cast<unsigned long long>(dut.perf_o));
        return false;
      }
      ones[i] += want[i];
    }
  }
  for (int i = 0; i < kNames; ++i) {
    if (ones[i] == 0 || ones[i] == vectors) {
      std::printf("rt_perf_events: FAIL: %s was always %d\n", names[i], ones[i] != 0);
      return false;
    }
  }
  std::printf("rt_perf_events: PASS (%llu vectors; stall_mem in %llu, stall_stack in %llu)\n",
              static_cast<unsigned long long>(vectors), static_cast<unsigned long long>(ones[9]),
              static_cast<unsigned long long>(ones[10]));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const bool ok = Run(LongRun() ? 10000000 : 1000000);
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
