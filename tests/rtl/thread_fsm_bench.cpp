// Verilator bench of rtl/rt_thread_fsm.sv against a C++ model of the threads'
// states and leaf-test counters, cycle by cycle: state_o, free_o, fetch_o, exit_o,
// done_o, alloc_idx_o (the lowest free thread) and exit_next_o (the threads in
// EXIT after the cycle's events) every cycle, so every
// transition is checked in the cycle after its event, and a thread in LEAF
// must go to EXIT in the cycle after its last test is issued and its last
// result is back, not before. Each cycle every kind of event comes with some
// chance for a random thread in the event's state, as rt_core makes them: a
// new ray's setup before its clip result, tests issued while the leaf has
// some left, results only for tests issued in an earlier cycle (an issue and
// a result for one thread in one cycle happen); misses, overflows, inner
// nodes, leaves with and without tests, pops and finished rays at random, in
// regimes of slow and fast traffic. --assert checks that every event is for a
// thread in its state.
#include <array>
#include <cstdio>
#include <utility>
#include <vector>

#include "Vrt_thread_fsm_t1.h"
#include "Vrt_thread_fsm_t3.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using sim::SimCtrl;

enum State : unsigned { kFree, kSetup, kFetch, kWaitNode, kTrav, kLeaf, kExit, kDone, kStates };
const char* const kNames[kStates] = {"FREE", "SETUP", "FETCH", "WAIT_NODE", "TRAV", "LEAF", "EXIT", "DONE"};

struct Thread {
  State state = kFree;
  bool setup = false;  // SETUP: the ray's constants are written
  uint32_t remaining = 0, outstanding = 0;
};

// A random thread among those that `ok` accepts, or -1.
template <class F>
int Pick(Rng& rng, const std::vector<Thread>& th, F ok) {
  std::vector<unsigned> c;
  for (unsigned t = 0; t < th.size(); ++t) {
    if (ok(th[t])) c.push_back(t);
  }
  return c.empty() ? -1 : static_cast<int>(c[rng.Below(static_cast<uint32_t>(c.size()))]);
}

// Threads and CountWidth as verilated (tests/rtl/CMakeLists.txt).
template <class Dut>
bool Run(const char* name, unsigned threads, unsigned count_width, uint64_t cycles) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  dut.alloc_i = dut.setup_i = dut.clip_i = dut.fetch_i = dut.node_i = dut.trav_i = 0;
  dut.issue_i = dut.retire_i = dut.exit_i = dut.out_i = 0;
  sim.Reset();
  Rng rng(5 + threads);
  std::vector<Thread> th(threads);
  const uint32_t max_tests = (1u << count_width) - 1;
  double p = 0.5;
  // Transitions seen: [from][to], and issues with results in one cycle.
  std::array<std::array<uint64_t, kStates>, kStates> seen{};
  uint64_t both = 0, both_fetches = 0;
  for (uint64_t cycle = 0; cycle < cycles; ++cycle) {
    if (cycle % 300 == 0) p = std::array<double, 3>{0.15, 0.5, 0.9}[rng.Below(3)];
    // The events of this cycle, each for a random thread in its state.
    const bool any_free = Pick(rng, th, [](const Thread& x) { return x.state == kFree; }) >= 0;
    const bool alloc = any_free && rng.Chance(p);
    const int su = rng.Chance(p) ? Pick(rng, th, [](const Thread& x) { return x.state == kSetup && !x.setup; }) : -1;
    const int cl = rng.Chance(p) ? Pick(rng, th, [](const Thread& x) { return x.state == kSetup && x.setup; }) : -1;
    const int fe = rng.Chance(p) ? Pick(rng, th, [](const Thread& x) { return x.state == kFetch; }) : -1;
    // The second fetch port (rt_core's miss-only node port): another thread in FETCH.
    int fe2 = rng.Chance(p) ? Pick(rng, th, [](const Thread& x) { return x.state == kFetch; }) : -1;
    if (fe2 == fe) fe2 = -1;
    const int no = rng.Chance(p) ? Pick(rng, th, [](const Thread& x) { return x.state == kWaitNode; }) : -1;
    const int tr = rng.Chance(p) ? Pick(rng, th, [](const Thread& x) { return x.state == kTrav; }) : -1;
    const int is = rng.Chance(p) ? Pick(rng, th, [](const Thread& x) { return x.state == kLeaf && x.remaining; }) : -1;
    const int re = rng.Chance(p) ? Pick(rng, th, [](const Thread& x) { return x.state == kLeaf && x.outstanding; })
                                 : -1;
    const int ex = rng.Chance(p) ? Pick(rng, th, [](const Thread& x) { return x.state == kExit; }) : -1;
    const int ou = rng.Chance(p) ? Pick(rng, th, [](const Thread& x) { return x.state == kDone; }) : -1;
    const bool clip_miss = rng.Chance(0.2), node_leaf = rng.Chance(0.4), node_job = rng.Chance(0.8);
    const uint32_t tests = rng.Chance(0.05) ? 0 : 1 + rng.Below(rng.Chance(0.1) ? max_tests : 3);
    const bool overflow = rng.Chance(0.1), exit_done = rng.Chance(0.4);
    // The next node an empty leaf: after a step (unless it overflowed) or a pop.
    const bool trav_exit = rng.Chance(0.3), exit_again = rng.Chance(0.3);
    // Idle indices and payloads are random too.
    auto idx = [&](int t) { return t >= 0 ? static_cast<unsigned>(t) : rng.Below(threads); };
    dut.alloc_i = alloc;
    dut.setup_i = su >= 0;
    dut.setup_idx_i = idx(su);
    dut.clip_i = cl >= 0;
    dut.clip_idx_i = idx(cl);
    dut.clip_miss_i = clip_miss;
    dut.fetch_i = fe >= 0;
    dut.fetch_idx_i = idx(fe);
    dut.fetch2_i = fe2 >= 0;
    dut.fetch2_idx_i = idx(fe2);
    dut.node_i = no >= 0;
    dut.node_idx_i = idx(no);
    dut.node_leaf_i = node_leaf;
    dut.node_job_i = node_job;
    dut.node_tests_i = tests;
    dut.trav_i = tr >= 0;
    dut.trav_idx_i = idx(tr);
    dut.trav_overflow_i = overflow;
    dut.trav_exit_i = trav_exit;
    dut.issue_i = is >= 0;
    dut.issue_idx_i = idx(is);
    dut.retire_i = re >= 0;
    dut.retire_idx_i = idx(re);
    dut.exit_i = ex >= 0;
    dut.exit_idx_i = idx(ex);
    dut.exit_done_i = exit_done;
    dut.exit_again_i = exit_again;
    dut.out_i = ou >= 0;
    dut.out_idx_i = idx(ou);
    sim.Settle();

    unsigned free = 0, fetch = 0, exit = 0, done = 0, lowest_free = 0, states = 0;
    for (unsigned t = threads; t-- > 0;) {
      states |= static_cast<unsigned>(th[t].state) << (3 * t);
      free |= (th[t].state == kFree) << t;
      fetch |= (th[t].state == kFetch) << t;
      exit |= (th[t].state == kExit) << t;
      done |= (th[t].state == kDone) << t;
      if (th[t].state == kFree) lowest_free = t;
    }
    if (dut.free_o != free || dut.fetch_o != fetch || dut.exit_o != exit || dut.done_o != done ||
        dut.alloc_idx_o != lowest_free || dut.state_o != states) {
      std::printf("rt_thread_fsm %s: FAIL at cycle %llu: free 0x%x fetch 0x%x exit 0x%x done 0x%x alloc %u state_o "
                  "0x%x; model 0x%x 0x%x 0x%x 0x%x %u 0x%x\n  model states:",
                  name, static_cast<unsigned long long>(cycle), dut.free_o, dut.fetch_o, dut.exit_o, dut.done_o,
                  dut.alloc_idx_o, static_cast<unsigned>(dut.state_o), free, fetch, exit, done, lowest_free, states);
      for (const Thread& x : th) std::printf(" %s (%u left, %u out)", kNames[x.state], x.remaining, x.outstanding);
      std::printf("\n");
      return false;
    }
    const unsigned exit_next_rtl = dut.exit_next_o;  // the threads in EXIT after this cycle's events
    sim.Tick();

    // The model's next state: transitions from this cycle's states and counters.
    std::vector<Thread> next = th;
    auto go = [&](unsigned t, State s) {
      ++seen[th[t].state][s];
      next[t].state = s;
    };
    if (alloc) {
      go(lowest_free, kSetup);
      next[lowest_free].setup = false;
    }
    if (su >= 0) next[su] = Thread{kSetup, true, 0, 0};
    if (cl >= 0) go(cl, clip_miss ? kDone : kFetch);
    if (fe >= 0) go(fe, kWaitNode);
    if (fe2 >= 0) go(fe2, kWaitNode);
    both_fetches += fe >= 0 && fe2 >= 0;
    if (no >= 0) {
      go(no, !node_leaf ? kTrav : node_job ? kLeaf : kExit);
      if (node_leaf && node_job) next[no].remaining = tests;
    }
    if (tr >= 0) go(tr, overflow ? kDone : trav_exit ? kExit : kFetch);
    for (unsigned t = 0; t < threads; ++t) {
      if (th[t].state == kLeaf && th[t].remaining == 0 && th[t].outstanding == 0) go(t, kExit);
    }
    if (is >= 0) {
      --next[is].remaining;
      ++next[is].outstanding;
    }
    if (re >= 0) --next[re].outstanding;
    both += is >= 0 && is == re;
    if (ex >= 0) go(ex, exit_done ? kDone : exit_again ? kExit : kFetch);
    if (ou >= 0) go(ou, kFree);
    th = next;
    unsigned exit_next = 0;
    for (unsigned t = 0; t < threads; ++t) exit_next |= (th[t].state == kExit) << t;
    if (exit_next_rtl != exit_next) {
      std::printf("rt_thread_fsm %s: FAIL at cycle %llu: exit_next_o 0x%x, model 0x%x\n", name,
                  static_cast<unsigned long long>(cycle), exit_next_rtl, exit_next);
      return false;
    }
  }
  const std::array<std::pair<State, State>, 14> must = {{{kFree, kSetup},
                                                         {kSetup, kFetch},
                                                         {kSetup, kDone},
                                                         {kFetch, kWaitNode},
                                                         {kWaitNode, kTrav},
                                                         {kWaitNode, kLeaf},
                                                         {kWaitNode, kExit},
                                                         {kTrav, kFetch},
                                                         {kTrav, kDone},
                                                         {kTrav, kExit},
                                                         {kLeaf, kExit},
                                                         {kExit, kFetch},
                                                         {kExit, kExit},
                                                         {kExit, kDone}}};
  bool covered = both > 0 && (threads == 1 || both_fetches > 0) && seen[kDone][kFree] > 0;
  for (const auto& [a, b] : must) covered = covered && seen[a][b] > 0;
  std::printf("rt_thread_fsm %s: %s (%llu cycles; rays %llu; leaves with tests %llu; issue and result in one "
              "cycle %llu)\n",
              name, covered ? "PASS" : "FAIL: the traffic missed a transition", static_cast<unsigned long long>(cycles),
              static_cast<unsigned long long>(seen[kFree][kSetup]), static_cast<unsigned long long>(seen[kLeaf][kExit]),
              static_cast<unsigned long long>(both));
  return covered;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t cycles = LongRun() ? 10000000 : 1000000;
  bool ok = Run<Vrt_thread_fsm_t3>("Threads=3", 3, 4, cycles);
  ok = Run<Vrt_thread_fsm_t1>("Threads=1", 1, 3, cycles) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
