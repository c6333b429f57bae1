// Verilator bench of rtl/rt_clip_unit.sv against the model's ClipToBox
// (sw/trace/traversal.h), per preset: t0, t1, miss and tag, with random input
// bubbles and output backpressure. Cases include rays parallel to slabs (inf
// and NaN distances), origins on box faces, flat boxes, entry distances
// around the test format's smallest normal (flushing to zero there), then
// random.
// With a traversal wider than the test (TravE, TravM; the configurations
// name:E:M:TE:TM in tests/rtl/CMakeLists.txt) the model is ClipToBoxMixed:
// o, tmin, tmax are test-format values, inv the traversal format's, t0 and
// t1 test-format values again (rounded outwards, fp_round_out). Those runs
// also count that the rounding went inwards (the extra step fired) at both
// ends, and that t0 flushed to zero in the test format.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "Vrt_clip_unit_bf16.h"
#include "Vrt_clip_unit_bf16t32.h"
#include "Vrt_clip_unit_fp16.h"
#include "Vrt_clip_unit_fp16t24.h"
#include "Vrt_clip_unit_fp16t32.h"
#include "Vrt_clip_unit_fp24.h"
#include "Vrt_clip_unit_fp32.h"
#include "sim/unit_latency.h"
#include "tests/rtl/isect_bench_util.h"
#include "tests/rtl/stream_bench.h"
#include "trace/traversal.h"

namespace kdrt::rtlbench {
namespace {

using fp::Format;
using fp::SoftArith;

struct In {
  uint32_t tag;
  float bmin[3], bmax[3];
  uint32_t o[3], tmin, tmax;  // test-format bits
  uint32_t inv[3];            // traversal-format bits
};

struct Out {
  uint32_t tag = 0, t0 = 0, t1 = 0;
  bool miss = false;
  bool operator==(const Out& x) const { return tag == x.tag && t0 == x.t0 && t1 == x.t1 && miss == x.miss; }
};

Out Model(const SoftArith& a, const In& in) {
  RaySetup<SoftArith> r{};
  for (int i = 0; i < 3; ++i) {
    r.o[i] = in.o[i];
    r.inv_d[i] = in.inv[i];
  }
  r.tmin = in.tmin;
  r.tmax = in.tmax;
  const BoxClip<SoftArith> c = ClipToBox(a, r, in.bmin, in.bmax);
  return Out{in.tag, c.t0, c.t1, c.miss};
}

// How often the mixed runs reach the cases the wider traversal adds.
struct Coverage {
  uint64_t d_zero = 0, d_neg_zero = 0, dist_nan = 0, tmax_inf = 0;
  uint64_t t0_inwards = 0, t1_inwards = 0;  // WidenForTest's extra step
  uint64_t t0_flushed = 0;  // a finite non-zero t0 that is a zero in the test format
  uint64_t t0_zero = 0;     // a positive t0 that leaves as +0
  uint64_t miss = 0;
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

Out ModelMixed(const SoftArith& at, const SoftArith& ai, const In& in, Coverage* cov) {
  const Format ft = at.format(), fi = ai.format();
  RaySetup<SoftArith> r{};
  for (int i = 0; i < 3; ++i) {
    r.o[i] = Widen(at, ai, in.o[i]);
    r.inv_d[i] = in.inv[i];
  }
  r.tmin = Widen(at, ai, in.tmin);
  r.tmax = Widen(at, ai, in.tmax);
  const BoxClip<SoftArith> c = ClipToBoxMixed(at, ai, r, in.bmin, in.bmax);
  // The ends are test-format values (WidenForTest): the unit gives them in that format.
  const Out out{in.tag, ai.Load(at.Store(c.t0)), ai.Load(at.Store(c.t1)), c.miss};

  // The same clip without the rounding into the test format: its ends
  // before WidenForTest.
  float bmin[3], bmax[3];
  for (int i = 0; i < 3; ++i) {
    bmin[i] = ai.Store(ai.Load(in.bmin[i]));
    bmax[i] = ai.Store(ai.Load(in.bmax[i]));
    cov->d_zero += fp::IsInf(ft, in.inv[i]) && !fp::SignBit(ft, in.inv[i]);
    cov->d_neg_zero += fp::IsInf(ft, in.inv[i]) && fp::SignBit(ft, in.inv[i]);
  }
  const BoxClip<SoftArith> w = ClipToBox(at, r, bmin, bmax);
  for (int i = 0; i < 3; ++i) {
    // A NaN distance: an origin on a face of a slab it is parallel to.
    const uint32_t near_plane = at.Load(fp::SignBit(ft, in.inv[i]) ? bmax[i] : bmin[i]);
    cov->dist_nan += fp::IsNaN(ft, at.Mul(at.Sub(near_plane, r.o[i]), in.inv[i]));
  }
  cov->tmax_inf += fp::IsInf(fi, in.tmax);
  cov->t0_inwards += RoundsInwards(at, ai, w.t0, false);
  cov->t1_inwards += RoundsInwards(at, ai, w.t1, true);
  const uint32_t t0_test = ai.Load(at.Store(w.t0));
  const bool t0_finite = !fp::IsNaN(ft, w.t0) && !fp::IsInf(ft, w.t0);
  cov->t0_flushed += t0_finite && !fp::IsZero(ft, w.t0) && fp::IsZero(fi, t0_test);
  cov->t0_zero += t0_finite && !fp::IsZero(ft, w.t0) && !fp::SignBit(ft, w.t0) && out.t0 == fi.Zero(false);
  cov->miss += c.miss;
  return out;
}

In RandomInput(const SoftArith& at, const SoftArith& ai, std::mt19937& rng, uint64_t i) {
  const SoftArith& a = ai;
  const bool mixed = at.format() != ai.format();
  const Format f = ai.format();
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  In in;
  in.tag = rng() & 0xF;
  float d[3];
  for (int k = 0; k < 3; ++k) {
    float lo = u(rng), hi = u(rng);
    if (lo > hi) std::swap(lo, hi);
    if ((i + k) % 9 == 0) hi = lo;  // flat box
    in.bmin[k] = lo;
    in.bmax[k] = hi;
    float o = u(rng);
    if ((i + k) % 7 == 0) o = lo;  // on a face
    d[k] = u(rng);
    // Parallel, with either zero (i is even here: the sign alternates with i / 6).
    if ((i + 2 * k) % 6 == 0) d[k] = (i / 6) % 2 ? 0.0f : -0.0f;
    in.o[k] = a.Load(o);
  }
  float tmin = i % 4 == 0 ? 0.0f : std::fabs(u(rng)) * 0.1f;
  const float tmax = i % 3 == 0 ? INFINITY : std::fabs(u(rng)) * 3.0f;
  // The ray enters the box at about the test format's smallest normal times
  // 2^q: the origin at 0 just outside the x slab, whose near face is at
  // s = 2^(emin + p + q) (a few ulps above), d.x = 2^p (every operation
  // exact in a wide traversal) or any d.x of that size; inside the other
  // slabs.
  if (i % 19 == 5 || i % 19 == 12) {
    const int emin = 1 - f.Bias();
    std::uniform_int_distribution<int> coin(0, 1);
    const int p = std::uniform_int_distribution<int>(2, 10)(rng);
    const int q = std::uniform_int_distribution<int>(-3, 3)(rng);
    const int ulps = std::uniform_int_distribution<int>(0, 3)(rng);
    double dx = std::ldexp(1.0, p);
    if (i % 19 == 12) dx *= std::uniform_real_distribution<double>(1.0, 2.0)(rng);
    const double s = std::ldexp(1.0 + std::ldexp(ulps, -f.m), emin + p + q);
    const bool neg = coin(rng) != 0;  // the ray goes down x: the box lies below 0
    in.bmin[0] = static_cast<float>(neg ? -8.0 : s);
    in.bmax[0] = static_cast<float>(neg ? -s : 8.0);
    in.o[0] = a.Load(coin(rng) ? 0.0f : -0.0f);
    d[0] = static_cast<float>(neg ? -dx : dx);
    for (int k = 1; k < 3; ++k) {
      in.bmin[k] = -8.0f;
      in.bmax[k] = 8.0f;
      in.o[k] = a.Load(u(rng) * 0.1f);
    }
    tmin = 0.0f;
  }
  for (int k = 0; k < 3; ++k) {
    const uint32_t dk = a.Load(d[k]);
    in.inv[k] = mixed ? at.Div(at.One(), Widen(at, ai, dk)) : a.Div(a.One(), dk);
  }
  in.tmin = a.Load(tmin);
  in.tmax = a.Load(tmax);
  return in;
}

unsigned DocumentedLatency(Format f, Format trav) { return sim::latency::Clip(f, trav); }

template <class Dut>
bool RunPreset(Format f, Format trav, uint64_t count) {
  const SoftArith ai(f), at(trav);
  const SoftArith& a = ai;
  const bool mixed = f != trav;
  const std::string name = f.Name() + (mixed ? " (traversal " + trav.Name() + ")" : "");
  const int w = f.Width(), tw = trav.Width();
  SimCtrl<Dut> sim;
  sim.top().in_valid_i = 0;
  sim.top().out_ready_i = 0;
  sim.Reset();
  std::mt19937 stimulus(99);
  Rng traffic_rng(7);
  uint64_t sent = 0;
  StreamUnit<Dut, In, Out> unit;
  Coverage cov;
  unit.name = "rt_clip_unit " + name;
  unit.next = [&](In& in) {
    if (sent >= count) return false;
    in = RandomInput(at, ai, stimulus, sent++);
    return true;
  };
  unit.drive = [w, tw](Dut& dut, const In& in) {
    dut.in_tag_i = in.tag;
    for (int k = 0; k < 3; ++k) {
      PutBits(dut.bounds_min_i, 32 * k, 32, fp::BitsOf(in.bmin[k]));
      PutBits(dut.bounds_max_i, 32 * k, 32, fp::BitsOf(in.bmax[k]));
      PutBits(dut.in_o_i, w * k, w, in.o[k]);
      PutBits(dut.in_inv_i, tw * k, tw, in.inv[k]);
    }
    dut.in_tmin_i = in.tmin;
    dut.in_tmax_i = in.tmax;
  };
  unit.read = [](const Dut& dut) {
    return Out{dut.out_tag_o, static_cast<uint32_t>(dut.out_t0_o), static_cast<uint32_t>(dut.out_t1_o),
               dut.out_miss_o != 0};
  };
  unit.model = [&](const In& in) { return mixed ? ModelMixed(at, ai, in, &cov) : Model(a, in); };
  unit.report = [&](const In& in, const Out& e, const Out& got, uint64_t index) {
    std::printf("rt_clip_unit %s: FAIL at result %llu\n", name.c_str(), static_cast<unsigned long long>(index));
    for (int k = 0; k < 3; ++k) {
      std::printf("  axis %d: box [%s, %s] o %s inv %s\n", k, F32(in.bmin[k]).c_str(), F32(in.bmax[k]).c_str(),
                  Fmt(f, in.o[k]).c_str(), Fmt(trav, in.inv[k]).c_str());
    }
    std::printf("  tmin %s tmax %s\n", Fmt(f, in.tmin).c_str(), Fmt(f, in.tmax).c_str());
    std::printf("  model: t0 %s t1 %s miss %d tag %u\n", Fmt(f, e.t0).c_str(), Fmt(f, e.t1).c_str(), e.miss, e.tag);
    std::printf("  rtl:   t0 %s t1 %s miss %d tag %u\n", Fmt(f, got.t0).c_str(), Fmt(f, got.t1).c_str(), got.miss,
                got.tag);
  };
  const unsigned latency = MeasureLatency(sim, unit, RandomInput(at, ai, stimulus, 1));
  if (latency != DocumentedLatency(f, trav)) {
    std::printf("rt_clip_unit %s: FAIL: latency %u cycles, documented %u\n", name.c_str(), latency,
                DocumentedLatency(f, trav));
    return false;
  }

  StreamTraffic traffic;
  traffic.ready = {0.7};
  traffic.gap = {0.2};
  StreamStats stats;
  if (!RunStream(sim, traffic_rng, traffic, unit, &stats) || stats.results != count) return false;
  std::printf("rt_clip_unit %s: PASS (%llu rays, latency %u)\n", name.c_str(), static_cast<unsigned long long>(count),
              latency);
  if (mixed) {
    std::printf("  covered: d +0 %llu, -0 %llu; NaN distances %llu; tmax inf %llu; rounded inwards t0 %llu, "
                "t1 %llu; t0 flushed in %s %llu; positive t0 leaving as +0 %llu; misses %llu\n",
                static_cast<unsigned long long>(cov.d_zero), static_cast<unsigned long long>(cov.d_neg_zero),
                static_cast<unsigned long long>(cov.dist_nan), static_cast<unsigned long long>(cov.tmax_inf),
                static_cast<unsigned long long>(cov.t0_inwards), static_cast<unsigned long long>(cov.t1_inwards),
                f.Name().c_str(), static_cast<unsigned long long>(cov.t0_flushed),
                static_cast<unsigned long long>(cov.t0_zero), static_cast<unsigned long long>(cov.miss));
    // t0 can flush in the test format only if the traversal's range reaches
    // below the test's smallest normal (not bf16 beside fp32).
    const bool can_flush = trav.e > f.e;
    if (cov.d_zero == 0 || cov.d_neg_zero == 0 || cov.dist_nan == 0 || cov.tmax_inf == 0 || cov.t0_inwards == 0 ||
        cov.t1_inwards == 0 || cov.t0_zero == 0 || cov.miss == 0 || (can_flush && cov.t0_flushed == 0)) {
      std::printf("rt_clip_unit %s: FAIL: a required case was not reached\n", name.c_str());
      return false;
    }
  }
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t count = LongRun() ? 10000000 : 300000;
  using kdrt::fp::kBf16;
  using kdrt::fp::kFp16;
  using kdrt::fp::kFp24;
  using kdrt::fp::kFp32;
  bool ok = RunPreset<Vrt_clip_unit_fp32>(kFp32, kFp32, count);
  ok = RunPreset<Vrt_clip_unit_fp24>(kFp24, kFp24, count) && ok;
  ok = RunPreset<Vrt_clip_unit_bf16>(kBf16, kBf16, count) && ok;
  ok = RunPreset<Vrt_clip_unit_fp16>(kFp16, kFp16, count) && ok;
  // A traversal wider than the test (tests/rtl/CMakeLists.txt, KDRT_TRAV_MIXED_FORMATS).
  ok = RunPreset<Vrt_clip_unit_fp16t32>(kFp16, kFp32, count) && ok;
  ok = RunPreset<Vrt_clip_unit_bf16t32>(kBf16, kFp32, count) && ok;
  ok = RunPreset<Vrt_clip_unit_fp16t24>(kFp16, kFp24, count) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
