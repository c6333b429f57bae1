// One driver for the Verilator benches of the pipelined units with one
// valid/ready stream in and one out (in_valid_i / in_ready_o, out_valid_o /
// out_ready_i: rt_trav_unit, rt_clip_unit, rt_ray_setup, rt_isect_unit):
// inputs from a source with random bubbles, random output backpressure,
// results compared in order against the model, and picorv32's rule checked
// on the output (valid and payload hold while out_ready_i is low). The clock
// and reset are sim/sim_ctrl.h's.
#pragma once

#include <cstdint>
#include <cstdio>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {

using sim::SimCtrl;

// Backpressure comes in regimes: every `regime_cycles` cycles the chance of
// out_ready_i and the chance of a bubble before an input are drawn anew from
// these lists (one entry each: fixed chances).
struct StreamTraffic {
  std::vector<double> ready = {0.7};
  std::vector<double> gap = {0.2};
  uint64_t regime_cycles = 512;
  double garbage = 0.0;            // chance per idle cycle of calling `idle` (payload is don't-care)
  size_t max_in_flight = 1000;     // more inputs in flight than this: the unit is stuck
  uint64_t max_quiet_cycles = 100000;  // cycles without any handshake: the unit is stuck
};

// The unit-specific parts. In and Out are the bench's own records (Out with
// operator==); the tag, when the unit has one, belongs in both.
template <class Top, class In, class Out>
struct StreamUnit {
  std::string name;                                      // for messages: "rt_trav_unit fp32"
  std::function<bool(In&)> next;                         // the next input; false when there is none
  std::function<void(Top&, const In&)> drive;            // sets the input payload ports
  std::function<void(Top&)> idle;                        // optional: random payload while in_valid_i is low
  std::function<Out(const Top&)> read;                   // the output payload ports
  std::function<Out(const In&)> model;                   // what the unit must return for an input
  std::function<void(const In&, const Out&)> on_result;  // optional: each checked result
  // Prints the first mismatch (`index` results were right before it).
  std::function<void(const In&, const Out& want, const Out& got, uint64_t index)> report;
};

struct StreamStats {
  uint64_t results = 0;
  uint64_t cycles = 0;
};

// Streams every input of `unit.next` through the unit (reset and idle or
// mid-stream, as the caller left it) until all results are back; false at
// the first failure, with a message.
template <class Top, class In, class Out>
bool RunStream(SimCtrl<Top>& sim, Rng& rng, const StreamTraffic& traffic, const StreamUnit<Top, In, Out>& unit,
               StreamStats* stats) {
  Top& top = sim.top();
  struct InFlight {
    In in;
    Out want;
  };
  std::deque<InFlight> flight;
  In cur{};
  Out last{};
  bool have = false, offering = false, exhausted = false, waiting_out = false;
  double p_ready = traffic.ready[0], p_gap = traffic.gap[0];
  uint64_t quiet = 0;
  for (uint64_t cycle = 0;; ++cycle) {
    if (cycle % traffic.regime_cycles == 0) {
      p_ready = traffic.ready[rng.Below(static_cast<uint32_t>(traffic.ready.size()))];
      p_gap = traffic.gap[rng.Below(static_cast<uint32_t>(traffic.gap.size()))];
    }
    if (!have && !exhausted) {
      have = unit.next(cur);
      exhausted = !have;
    }
    if (!have && flight.empty()) break;
    if (!offering && have && !rng.Chance(p_gap)) {
      offering = true;
      unit.drive(top, cur);
    } else if (!offering && unit.idle && rng.Chance(traffic.garbage)) {
      unit.idle(top);
    }
    top.in_valid_i = offering;
    top.out_ready_i = rng.Chance(p_ready);
    sim.Settle();

    const Out got = unit.read(top);
    if (waiting_out && (!top.out_valid_o || !(got == last))) {
      std::printf("FAIL %s: output changed while out_ready_i was low\n", unit.name.c_str());
      return false;
    }
    waiting_out = top.out_valid_o && !top.out_ready_i;
    last = got;
    const bool in_fire = offering && top.in_ready_o;
    const bool out_fire = top.out_valid_o && top.out_ready_i;
    if (out_fire) {
      if (flight.empty()) {
        std::printf("FAIL %s: a result with no input in flight\n", unit.name.c_str());
        return false;
      }
      const InFlight& x = flight.front();
      if (!(got == x.want)) {
        unit.report(x.in, x.want, got, stats->results);
        return false;
      }
      if (unit.on_result) unit.on_result(x.in, got);
      ++stats->results;
      flight.pop_front();
    }
    sim.Tick();
    ++stats->cycles;
    if (in_fire) {
      flight.push_back({cur, unit.model(cur)});
      have = offering = false;
    }
    if (flight.size() > traffic.max_in_flight) {
      std::printf("FAIL %s: %zu inputs in flight, nothing comes out\n", unit.name.c_str(), flight.size());
      return false;
    }
    quiet = (in_fire || out_fire) ? 0 : quiet + 1;
    if (quiet > traffic.max_quiet_cycles) {
      std::printf("FAIL %s: no handshake for %llu cycles\n", unit.name.c_str(),
                  static_cast<unsigned long long>(quiet));
      return false;
    }
  }
  return true;
}

// Enabled cycles from taking one input to its result, on an idle unit that
// is never stalled; the result is consumed.
template <class Top, class In, class Out>
unsigned MeasureLatency(SimCtrl<Top>& sim, const StreamUnit<Top, In, Out>& unit, const In& in) {
  Top& top = sim.top();
  unit.drive(top, in);
  top.in_valid_i = 1;
  top.out_ready_i = 1;
  sim.Step();
  top.in_valid_i = 0;
  unsigned cycles = 1;
  sim.Settle();
  while (!top.out_valid_o && cycles < 1000) {
    sim.Tick();
    sim.Settle();
    ++cycles;
  }
  sim.Tick();
  return cycles;
}

}  // namespace kdrt::rtlbench
