// Verilator bench of rtl/rt_clip_unit.sv against the model's ClipToBox
// (sw/trace/traversal.h), per preset: t0, t1, miss and tag, with random input
// bubbles and output backpressure. Cases include rays parallel to slabs (inf
// and NaN distances), origins on box faces, flat boxes, then random.
#include <cstdio>
#include <random>

#include "Vrt_clip_unit_bf16.h"
#include "Vrt_clip_unit_fp16.h"
#include "Vrt_clip_unit_fp24.h"
#include "Vrt_clip_unit_fp32.h"
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
  uint32_t o[3], inv[3], tmin, tmax;
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

In RandomInput(const SoftArith& a, std::mt19937& rng, uint64_t i) {
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  In in;
  in.tag = rng() & 0xF;
  for (int k = 0; k < 3; ++k) {
    float lo = u(rng), hi = u(rng);
    if (lo > hi) std::swap(lo, hi);
    if ((i + k) % 9 == 0) hi = lo;  // flat box
    in.bmin[k] = lo;
    in.bmax[k] = hi;
    float o = u(rng);
    if ((i + k) % 7 == 0) o = lo;  // on a face
    float d = u(rng);
    if ((i + 2 * k) % 6 == 0) d = (i % 2) ? 0.0f : -0.0f;  // parallel
    in.o[k] = a.Load(o);
    in.inv[k] = a.Div(a.One(), a.Load(d));
  }
  in.tmin = a.Load(i % 4 == 0 ? 0.0f : std::fabs(u(rng)) * 0.1f);
  in.tmax = a.Load(i % 3 == 0 ? INFINITY : std::fabs(u(rng)) * 3.0f);
  return in;
}

template <class Dut>
bool RunPreset(Format f, uint64_t count) {
  const SoftArith a(f);
  const int w = f.Width();
  SimCtrl<Dut> sim;
  sim.top().in_valid_i = 0;
  sim.top().out_ready_i = 0;
  sim.Reset();
  std::mt19937 stimulus(99);
  Rng traffic_rng(7);
  uint64_t sent = 0;
  StreamUnit<Dut, In, Out> unit;
  unit.name = "rt_clip_unit " + f.Name();
  unit.next = [&](In& in) {
    if (sent >= count) return false;
    in = RandomInput(a, stimulus, sent++);
    return true;
  };
  unit.drive = [w](Dut& dut, const In& in) {
    dut.in_tag_i = in.tag;
    for (int k = 0; k < 3; ++k) {
      PutBits(dut.bounds_min_i, 32 * k, 32, fp::BitsOf(in.bmin[k]));
      PutBits(dut.bounds_max_i, 32 * k, 32, fp::BitsOf(in.bmax[k]));
      PutBits(dut.in_o_i, w * k, w, in.o[k]);
      PutBits(dut.in_inv_i, w * k, w, in.inv[k]);
    }
    dut.in_tmin_i = in.tmin;
    dut.in_tmax_i = in.tmax;
  };
  unit.read = [](const Dut& dut) {
    return Out{dut.out_tag_o, static_cast<uint32_t>(dut.out_t0_o), static_cast<uint32_t>(dut.out_t1_o),
               dut.out_miss_o != 0};
  };
  unit.model = [&](const In& in) { return Model(a, in); };
  unit.report = [&](const In&, const Out& e, const Out& got, uint64_t index) {
    std::printf("rt_clip_unit %s: FAIL at result %llu\n", f.Name().c_str(), static_cast<unsigned long long>(index));
    std::printf("  model: t0 %s t1 %s miss %d tag %u\n", Fmt(f, e.t0).c_str(), Fmt(f, e.t1).c_str(), e.miss, e.tag);
    std::printf("  rtl:   t0 %s t1 %s miss %d tag %u\n", Fmt(f, got.t0).c_str(), Fmt(f, got.t1).c_str(), got.miss,
                got.tag);
  };
  StreamTraffic traffic;
  traffic.ready = {0.7};
  traffic.gap = {0.2};
  StreamStats stats;
  if (!RunStream(sim, traffic_rng, traffic, unit, &stats) || stats.results != count) return false;
  std::printf("rt_clip_unit %s: PASS (%llu rays)\n", f.Name().c_str(), static_cast<unsigned long long>(count));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t count = LongRun() ? 10000000 : 1000000;
  bool ok = RunPreset<Vrt_clip_unit_fp32>(kdrt::fp::kFp32, count);
  ok = RunPreset<Vrt_clip_unit_fp24>(kdrt::fp::kFp24, count) && ok;
  ok = RunPreset<Vrt_clip_unit_bf16>(kdrt::fp::kBf16, count) && ok;
  ok = RunPreset<Vrt_clip_unit_fp16>(kdrt::fp::kFp16, count) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
