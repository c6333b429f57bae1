// Verilator bench of rtl/rt_trav_unit.sv against the model's StepInnerNode
// (sw/trace/traversal.h), per preset: action, near/far children, t_split and
// the carried t0/t1/tag, with random input bubbles and output backpressure.
// Cases: splits exactly at the origin, zero and negative-zero directions
// (NaN and infinite t_split), empty and infinite intervals, then random.
#include <cstdio>
#include <random>

#include "Vrt_trav_unit_bf16.h"
#include "Vrt_trav_unit_fp16.h"
#include "Vrt_trav_unit_fp24.h"
#include "Vrt_trav_unit_fp32.h"
#include "tests/rtl/isect_bench_util.h"
#include "tests/rtl/stream_bench.h"
#include "trace/traversal.h"

namespace kdrt::rtlbench {
namespace {

using fp::Format;
using fp::SoftArith;

struct In {
  uint32_t tag, below, above;
  float split;
  uint32_t o, d, inv, t0, t1;  // format bits
};

struct Out {
  uint32_t tag = 0, action = 0, first = 0, second = 0, ts = 0, lo = 0, hi = 0, t0 = 0, t1 = 0;
  bool operator==(const Out& x) const {
    return tag == x.tag && action == x.action && first == x.first && second == x.second && ts == x.ts &&
           lo == x.lo && hi == x.hi && t0 == x.t0 && t1 == x.t1;
  }
};

Out Model(const SoftArith& a, const In& in) {
  const TraversalStep<SoftArith> s = StepInnerNode(a, in.split, in.o, in.d, in.inv, in.t0, in.t1);
  Out o;
  o.tag = in.tag;
  o.action = static_cast<uint32_t>(s.action);
  o.first = s.below_first ? in.below : in.above;
  o.second = s.below_first ? in.above : in.below;
  o.ts = s.t_split;
  o.lo = s.t_lo;
  o.hi = s.t_hi;
  o.t0 = in.t0;
  o.t1 = in.t1;
  return o;
}

In RandomInput(const SoftArith& a, std::mt19937& rng, uint64_t i) {
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  In in;
  in.tag = rng() & 0xF;
  in.below = rng() & 0xFFFFFF;
  in.above = rng() & 0xFFFFFF;
  const float o = u(rng);
  float d = u(rng);
  switch (i % 8) {
    case 0: d = 0.0f; break;
    case 1: d = -0.0f; break;
    default: break;
  }
  in.o = a.Load(o);
  in.d = a.Load(d);
  in.inv = a.Div(a.One(), in.d);
  // Splits at, near and away from the origin.
  in.split = (i % 5 == 0) ? a.Store(in.o) : o + u(rng) * ((i % 3 == 0) ? 1e-3f : 1.0f);
  float t0 = std::fabs(u(rng)), t1 = t0 + std::fabs(u(rng));
  if (i % 11 == 0) t1 = INFINITY;
  if (i % 13 == 0) t1 = t0;
  if (i % 17 == 0) std::swap(t0, t1);
  in.t0 = a.Load(t0);
  in.t1 = a.Load(t1);
  return in;
}

template <class Dut>
bool RunPreset(Format f, uint64_t count) {
  const SoftArith a(f);
  SimCtrl<Dut> sim;
  sim.top().in_valid_i = 0;
  sim.top().out_ready_i = 0;
  sim.Reset();
  std::mt19937 stimulus(1234);
  Rng traffic_rng(99);
  uint64_t sent = 0;
  StreamUnit<Dut, In, Out> unit;
  unit.name = "rt_trav_unit " + f.Name();
  unit.next = [&](In& in) {
    if (sent >= count) return false;
    in = RandomInput(a, stimulus, sent++);
    return true;
  };
  unit.drive = [](Dut& dut, const In& in) {
    dut.in_tag_i = in.tag;
    dut.in_split_i = fp::BitsOf(in.split);
    dut.in_below_i = in.below;
    dut.in_above_i = in.above;
    dut.in_o_i = in.o;
    dut.in_d_i = in.d;
    dut.in_inv_i = in.inv;
    dut.in_t0_i = in.t0;
    dut.in_t1_i = in.t1;
  };
  unit.read = [](const Dut& dut) {
    return Out{dut.out_tag_o, dut.out_action_o, dut.out_first_o, dut.out_second_o,
               static_cast<uint32_t>(dut.out_ts_o), static_cast<uint32_t>(dut.out_ts_lo_o),
               static_cast<uint32_t>(dut.out_ts_hi_o), static_cast<uint32_t>(dut.out_t0_o),
               static_cast<uint32_t>(dut.out_t1_o)};
  };
  unit.model = [&](const In& in) { return Model(a, in); };
  unit.report = [&](const In&, const Out& e, const Out& got, uint64_t index) {
    std::printf("rt_trav_unit %s: FAIL at result %llu\n", f.Name().c_str(), static_cast<unsigned long long>(index));
    std::printf("  model: action %u first %u second %u ts %s tag %u\n", e.action, e.first, e.second,
                Fmt(f, e.ts).c_str(), e.tag);
    std::printf("  rtl:   action %u first %u second %u ts %s tag %u\n", got.action, got.first, got.second,
                Fmt(f, got.ts).c_str(), got.tag);
  };
  StreamTraffic traffic;
  traffic.ready = {0.7};
  traffic.gap = {0.2};
  StreamStats stats;
  if (!RunStream(sim, traffic_rng, traffic, unit, &stats) || stats.results != count) return false;
  std::printf("rt_trav_unit %s: PASS (%llu node steps)\n", f.Name().c_str(), static_cast<unsigned long long>(count));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t count = LongRun() ? 10000000 : 1000000;
  bool ok = RunPreset<Vrt_trav_unit_fp32>(kdrt::fp::kFp32, count);
  ok = RunPreset<Vrt_trav_unit_fp24>(kdrt::fp::kFp24, count) && ok;
  ok = RunPreset<Vrt_trav_unit_bf16>(kdrt::fp::kBf16, count) && ok;
  ok = RunPreset<Vrt_trav_unit_fp16>(kdrt::fp::kFp16, count) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
