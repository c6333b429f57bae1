// Verilator bench of rtl/rt_trav_unit.sv against the model's StepInnerNode
// (sw/trace/traversal.h), per preset: action, near/far children, t_split and
// the carried t0/t1/tag, with random input bubbles and output backpressure.
// Cases: splits exactly at the origin, zero and negative-zero directions
// (NaN and infinite t_split), empty and infinite intervals, t_split around
// the test format's smallest normal (flushing to zero there) and beyond its
// largest finite value, then random.
// With a traversal wider than the test (TravE, TravM; the configurations
// name:E:M:TE:TM in tests/rtl/CMakeLists.txt) the model is
// StepInnerNodeMixed: o, d, t0, t1 are test-format values, inv and t_split
// the traversal format's, the children's ends test-format values again
// (rounded outwards, fp_round_out). Those runs also count that the rounding
// went inwards (the extra step fired) for both ends, and that t_split
// flushed to zero or overflowed in the test format.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "Vrt_trav_unit_bf16.h"
#include "Vrt_trav_unit_bf16t32.h"
#include "Vrt_trav_unit_fp16.h"
#include "Vrt_trav_unit_fp16t24.h"
#include "Vrt_trav_unit_fp16t32.h"
#include "Vrt_trav_unit_fp24.h"
#include "Vrt_trav_unit_fp32.h"
#include "sim/unit_latency.h"
#include "tests/rtl/isect_bench_util.h"
#include "tests/rtl/stream_bench.h"
#include "trace/traversal.h"

namespace kdrt::rtlbench {
namespace {

using fp::Format;
using fp::SoftArith;

struct In {
  uint32_t tag, below, above;  // bit 24: the child's empty mark
  float split;
  uint32_t o, d, t0, t1;  // test-format bits
  uint32_t inv;           // traversal-format bits
};

struct Out {
  uint32_t tag = 0, action = 0, first = 0, second = 0, ts = 0, lo = 0, hi = 0, t0 = 0, t1 = 0;
  bool operator==(const Out& x) const {
    return tag == x.tag && action == x.action && first == x.first && second == x.second && ts == x.ts &&
           lo == x.lo && hi == x.hi && t0 == x.t0 && t1 == x.t1;
  }
};

// How often the mixed runs reach the cases the wider traversal adds.
struct Coverage {
  uint64_t ts_nan = 0, ts_inf = 0, d_zero = 0, d_neg_zero = 0, t1_inf = 0;
  uint64_t lo_inwards = 0, hi_inwards = 0;  // WidenForTest's extra step
  uint64_t ts_flushed = 0;   // finite non-zero t_split that is a zero in the test format
  uint64_t ts_overflow = 0;  // finite t_split that is an infinity in the test format
  uint64_t lo_zero = 0;      // positive t_split whose far child starts at +0
};

// Whether WidenForTest (sw/trace/traversal.h) takes its extra step for x
// and that step moves the value (x rounded to nearest went inwards, and is
// positive: the nudges move only positive values).
bool RoundsInwards(const SoftArith& at, const SoftArith& ai, uint32_t x, bool up) {
  const uint32_t r = ai.Load(at.Store(x));
  const uint32_t back = Widen(at, ai, r);
  const bool inwards = up ? at.Lt(back, x) : at.Lt(x, back);
  return inwards && (up ? ai.NudgeUp(r, 1) : ai.NudgeDown(r, 1)) != r;
}

// The unit's outputs for a step of the model; lo and hi as they are given.
Out StepOut(const TraversalStep<SoftArith>& s, const In& in) {
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

Out Model(const SoftArith& a, const In& in) {
  return StepOut(StepInnerNode(a, in.split, in.o, in.d, in.inv, in.t0, in.t1), in);
}

Out ModelMixed(const SoftArith& at, const SoftArith& ai, const In& in, Coverage* cov) {
  const fp::Format ft = at.format(), fi = ai.format();
  const TraversalStep<SoftArith> s = StepInnerNodeMixed(at, ai, in.split, Widen(at, ai, in.o), Widen(at, ai, in.d),
                                                        in.inv, Widen(at, ai, in.t0), Widen(at, ai, in.t1));
  Out o = StepOut(s, in);
  // The ends are test-format values (WidenForTest): the unit gives them in that format.
  o.lo = ai.Load(at.Store(s.t_lo));
  o.hi = ai.Load(at.Store(s.t_hi));

  const uint32_t ts = s.t_split;
  const uint32_t ts_test = ai.Load(at.Store(ts));
  cov->ts_nan += fp::IsNaN(ft, ts);
  cov->ts_inf += fp::IsInf(ft, ts);
  cov->d_zero += in.d == fi.Zero(false);
  cov->d_neg_zero += in.d == fi.Zero(true);
  cov->t1_inf += fp::IsInf(fi, in.t1);
  const uint32_t lo_nudged = at.NudgeDown(ts, kTraversalSlackUlps);
  const uint32_t hi_nudged = at.NudgeUp(ts, kTraversalSlackUlps);
  cov->lo_inwards += RoundsInwards(at, ai, lo_nudged, false);
  cov->hi_inwards += RoundsInwards(at, ai, hi_nudged, true);
  const bool ts_finite = !fp::IsNaN(ft, ts) && !fp::IsInf(ft, ts);
  cov->ts_flushed += ts_finite && !fp::IsZero(ft, ts) && fp::IsZero(fi, ts_test);
  cov->ts_overflow += ts_finite && fp::IsInf(fi, ts_test);
  cov->lo_zero += ts_finite && !fp::IsZero(ft, ts) && !fp::SignBit(ft, ts) && o.lo == fi.Zero(false);
  return o;
}

// A random significand in [1, 2) times 2^e.
float RandomSig(std::mt19937& rng, int e) {
  std::uniform_real_distribution<double> sig(1.0, 2.0);
  return static_cast<float>(std::ldexp(sig(rng), e));
}

In RandomInput(const SoftArith& at, const SoftArith& ai, std::mt19937& rng, uint64_t i) {
  const SoftArith& a = ai;
  const bool mixed = at.format() != ai.format();
  const Format f = ai.format();
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  In in;
  in.tag = rng() & 0xF;
  in.below = rng() & 0x1FFFFFF;
  in.above = rng() & 0x1FFFFFF;
  float o = u(rng);
  float d = u(rng);
  switch (i % 8) {
    case 0: d = 0.0f; break;
    case 1: d = -0.0f; break;
    default: break;
  }
  // Splits at, near and away from the origin.
  float split = (i % 5 == 0) ? a.Store(a.Load(o)) : o + u(rng) * ((i % 3 == 0) ? 1e-3f : 1.0f);
  // t_split at the test format's edges: exactly a power of two times a few
  // ulps around its smallest normal (o = +-0, d = +-2^p: every operation
  // exact in a wide traversal), log-uniform around that smallest normal,
  // and beyond its largest finite value.
  const int emin = 1 - f.Bias(), emax = f.Bias();
  std::uniform_int_distribution<int> coin(0, 1);
  switch (i % 23) {
    case 4: {
      const int p = std::uniform_int_distribution<int>(2, 10)(rng);
      const int q = std::uniform_int_distribution<int>(-2, 3)(rng);
      const int k = std::uniform_int_distribution<int>(0, 3)(rng);
      o = coin(rng) ? 0.0f : -0.0f;
      d = static_cast<float>(std::ldexp(coin(rng) ? 1.0 : -1.0, p));
      split = static_cast<float>(std::ldexp(1.0 + std::ldexp(k, -f.m), emin + p + q)) * (coin(rng) ? 1.0f : -1.0f);
      break;
    }
    case 9: {
      const int p = std::uniform_int_distribution<int>(0, 12)(rng);
      const int q = std::uniform_int_distribution<int>(-6, 6)(rng);
      o = coin(rng) ? 0.0f : RandomSig(rng, emin + p + q - 8);
      d = RandomSig(rng, p);
      if (coin(rng)) d = -d;
      const double ts = std::ldexp(std::uniform_real_distribution<double>(1, 2)(rng), emin + q);
      split = static_cast<float>(o + ts * d);
      break;
    }
    case 14: {
      const int p = std::uniform_int_distribution<int>(1, 8)(rng);
      const int q = std::uniform_int_distribution<int>(-2, 3)(rng);
      o = u(rng) * 0.01f;
      d = RandomSig(rng, -p);
      if (coin(rng)) d = -d;
      const double ts = std::ldexp(1.0 + 0.5 * std::uniform_real_distribution<double>(0, 1)(rng), emax + q);
      split = static_cast<float>(o + ts * d * (coin(rng) ? 1.0 : -1.0));
      break;
    }
    default: break;
  }
  in.o = a.Load(o);
  in.d = a.Load(d);
  in.inv = mixed ? at.Div(at.One(), Widen(at, ai, in.d)) : a.Div(a.One(), in.d);
  in.split = split;
  float t0 = std::fabs(u(rng)), t1 = t0 + std::fabs(u(rng));
  if (i % 11 == 0) t1 = INFINITY;
  if (i % 13 == 0) t1 = t0;
  if (i % 17 == 0) std::swap(t0, t1);
  // Intervals of the t_split cases' scale, so that the decision varies.
  if (i % 23 == 4 || i % 23 == 9) {
    t0 = static_cast<float>(std::ldexp(std::fabs(u(rng)) * 0.1, emin));
    t1 = i % 2 ? INFINITY : t0 + static_cast<float>(std::ldexp(std::fabs(u(rng)), emin));
  }
  in.t0 = a.Load(t0);
  in.t1 = a.Load(t1);
  return in;
}

unsigned DocumentedLatency(Format f, Format trav) { return sim::latency::Trav(f, trav); }

template <class Dut>
bool RunPreset(Format f, Format trav, uint64_t count) {
  const SoftArith ai(f), at(trav);
  const bool mixed = f != trav;
  const std::string name = f.Name() + (mixed ? " (traversal " + trav.Name() + ")" : "");
  SimCtrl<Dut> sim;
  sim.top().in_valid_i = 0;
  sim.top().out_ready_i = 0;
  sim.Reset();
  std::mt19937 stimulus(1234);
  Rng traffic_rng(99);
  uint64_t sent = 0;
  Coverage cov;
  StreamUnit<Dut, In, Out> unit;
  unit.name = "rt_trav_unit " + name;
  unit.next = [&](In& in) {
    if (sent >= count) return false;
    in = RandomInput(at, ai, stimulus, sent++);
    return true;
  };
  unit.drive = [](Dut& dut, const In& in) {
    dut.in_tag_i = in.tag;
    dut.in_split_i = fp::BitsOf(in.split);
    dut.in_below_i = in.below & 0xFFFFFF;
    dut.in_above_i = in.above & 0xFFFFFF;
    dut.in_below_empty_i = in.below >> 24;
    dut.in_above_empty_i = in.above >> 24;
    dut.in_o_i = in.o;
    dut.in_d_i = in.d;
    dut.in_inv_i = in.inv;
    dut.in_t0_i = in.t0;
    dut.in_t1_i = in.t1;
  };
  unit.read = [](const Dut& dut) {
    return Out{dut.out_tag_o, dut.out_action_o, dut.out_first_o | uint32_t{dut.out_first_empty_o} << 24,
               dut.out_second_o | uint32_t{dut.out_second_empty_o} << 24,
               static_cast<uint32_t>(dut.out_ts_o), static_cast<uint32_t>(dut.out_ts_lo_o),
               static_cast<uint32_t>(dut.out_ts_hi_o), static_cast<uint32_t>(dut.out_t0_o),
               static_cast<uint32_t>(dut.out_t1_o)};
  };
  unit.model = [&](const In& in) { return mixed ? ModelMixed(at, ai, in, &cov) : Model(ai, in); };
  unit.report = [&](const In& in, const Out& e, const Out& got, uint64_t index) {
    std::printf("rt_trav_unit %s: FAIL at result %llu\n", name.c_str(), static_cast<unsigned long long>(index));
    std::printf("  in: split %s o %s d %s inv %s t0 %s t1 %s\n", F32(in.split).c_str(), Fmt(f, in.o).c_str(),
                Fmt(f, in.d).c_str(), Fmt(trav, in.inv).c_str(), Fmt(f, in.t0).c_str(), Fmt(f, in.t1).c_str());
    std::printf("  model: action %u first %u second %u ts %s lo %s hi %s tag %u\n", e.action, e.first, e.second,
                Fmt(trav, e.ts).c_str(), Fmt(f, e.lo).c_str(), Fmt(f, e.hi).c_str(), e.tag);
    std::printf("  rtl:   action %u first %u second %u ts %s lo %s hi %s tag %u\n", got.action, got.first,
                got.second, Fmt(trav, got.ts).c_str(), Fmt(f, got.lo).c_str(), Fmt(f, got.hi).c_str(), got.tag);
  };

  const unsigned latency = MeasureLatency(sim, unit, RandomInput(at, ai, stimulus, 2));
  if (latency != DocumentedLatency(f, trav)) {
    std::printf("rt_trav_unit %s: FAIL: latency %u cycles, documented %u\n", name.c_str(), latency,
                DocumentedLatency(f, trav));
    return false;
  }

  StreamTraffic traffic;
  traffic.ready = {0.7};
  traffic.gap = {0.2};
  StreamStats stats;
  if (!RunStream(sim, traffic_rng, traffic, unit, &stats) || stats.results != count) return false;
  std::printf("rt_trav_unit %s: PASS (%llu node steps, latency %u)\n", name.c_str(),
              static_cast<unsigned long long>(count), latency);
  if (mixed) {
    std::printf("  covered: ts NaN %llu, inf %llu, flushed in %s %llu, overflowing it %llu; d +0 %llu, -0 %llu; "
                "t1 inf %llu; rounded inwards lo %llu, hi %llu; positive ts with lo +0 %llu\n",
                static_cast<unsigned long long>(cov.ts_nan), static_cast<unsigned long long>(cov.ts_inf),
                f.Name().c_str(), static_cast<unsigned long long>(cov.ts_flushed),
                static_cast<unsigned long long>(cov.ts_overflow), static_cast<unsigned long long>(cov.d_zero),
                static_cast<unsigned long long>(cov.d_neg_zero), static_cast<unsigned long long>(cov.t1_inf),
                static_cast<unsigned long long>(cov.lo_inwards), static_cast<unsigned long long>(cov.hi_inwards),
                static_cast<unsigned long long>(cov.lo_zero));
    // A t_split can flush in the test format only if the traversal's range
    // reaches below the test's smallest normal (not bf16 beside fp32).
    const bool can_flush = trav.e > f.e;
    if (cov.ts_nan == 0 || cov.ts_inf == 0 || cov.d_zero == 0 || cov.d_neg_zero == 0 || cov.t1_inf == 0 ||
        cov.lo_inwards == 0 || cov.hi_inwards == 0 || cov.lo_zero == 0 || (can_flush && cov.ts_flushed == 0)) {
      std::printf("rt_trav_unit %s: FAIL: a required case was not reached\n", name.c_str());
      return false;
    }
  }
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  using kdrt::fp::kBf16;
  using kdrt::fp::kFp16;
  using kdrt::fp::kFp24;
  using kdrt::fp::kFp32;
  Verilated::commandArgs(argc, argv);
  const uint64_t count = LongRun() ? 10000000 : 1000000;
  bool ok = RunPreset<Vrt_trav_unit_fp32>(kFp32, kFp32, count);
  ok = RunPreset<Vrt_trav_unit_fp24>(kFp24, kFp24, count) && ok;
  ok = RunPreset<Vrt_trav_unit_bf16>(kBf16, kBf16, count) && ok;
  ok = RunPreset<Vrt_trav_unit_fp16>(kFp16, kFp16, count) && ok;
  // A traversal wider than the test (tests/rtl/CMakeLists.txt, KDRT_TRAV_MIXED_FORMATS).
  ok = RunPreset<Vrt_trav_unit_fp16t32>(kFp16, kFp32, count) && ok;
  ok = RunPreset<Vrt_trav_unit_bf16t32>(kBf16, kFp32, count) && ok;
  ok = RunPreset<Vrt_trav_unit_fp16t24>(kFp16, kFp24, count) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
