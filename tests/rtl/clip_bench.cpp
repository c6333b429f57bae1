// Verilator bench of rtl/rt_clip_unit.sv against the model's ClipToBox
// (sw/trace/traversal.h), per preset: t0, t1, miss and tag, with random input
// bubbles and output backpressure. Cases include rays parallel to slabs (inf
// and NaN distances), origins on box faces, flat boxes, then random.
#include <cstdio>
#include <deque>
#include <random>

#include "Vrt_clip_unit_bf16.h"
#include "Vrt_clip_unit_fp16.h"
#include "Vrt_clip_unit_fp24.h"
#include "Vrt_clip_unit_fp32.h"
#include "tests/rtl/isect_bench_util.h"
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
  uint32_t tag, t0, t1;
  bool miss;
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
  Dut dut;
  std::mt19937 rng(99);
  std::bernoulli_distribution bubble(0.2), stall(0.3);
  dut.clk_i = 0;
  dut.rst_ni = 0;
  dut.in_valid_i = 0;
  dut.out_ready_i = 0;
  dut.eval();
  dut.clk_i = 1;
  dut.eval();
  dut.rst_ni = 1;
  std::deque<Out> expected;
  uint64_t sent = 0, checked = 0;
  In pending{};
  bool have_pending = false;
  for (uint64_t cycle = 0; checked < count; ++cycle) {
    if (cycle > 20 * count + 1000) {
      std::printf("rt_clip_unit %s: FAIL (timeout)\n", f.Name().c_str());
      return false;
    }
    dut.clk_i = 0;
    if (!have_pending && sent < count && !bubble(rng)) {
      pending = RandomInput(a, rng, sent);
      have_pending = true;
    }
    dut.in_valid_i = have_pending;
    dut.in_tag_i = pending.tag;
    for (int k = 0; k < 3; ++k) {
      PutBits(dut.bounds_min_i, 32 * k, 32, fp::BitsOf(pending.bmin[k]));
      PutBits(dut.bounds_max_i, 32 * k, 32, fp::BitsOf(pending.bmax[k]));
      PutBits(dut.in_o_i, w * k, w, pending.o[k]);
      PutBits(dut.in_inv_i, w * k, w, pending.inv[k]);
    }
    dut.in_tmin_i = pending.tmin;
    dut.in_tmax_i = pending.tmax;
    dut.out_ready_i = !stall(rng);
    dut.eval();
    const bool in_fire = dut.in_valid_i && dut.in_ready_o;
    if (dut.out_valid_o && dut.out_ready_i) {
      const Out got{dut.out_tag_o, static_cast<uint32_t>(dut.out_t0_o), static_cast<uint32_t>(dut.out_t1_o),
                    dut.out_miss_o != 0};
      if (expected.empty() || !(got == expected.front())) {
        std::printf("rt_clip_unit %s: FAIL at result %llu\n", f.Name().c_str(),
                    static_cast<unsigned long long>(checked));
        if (!expected.empty()) {
          const Out& e = expected.front();
          std::printf("  model: t0 %s t1 %s miss %d tag %u\n", Fmt(f, e.t0).c_str(), Fmt(f, e.t1).c_str(), e.miss,
                      e.tag);
        }
        std::printf("  rtl:   t0 %s t1 %s miss %d tag %u\n", Fmt(f, got.t0).c_str(), Fmt(f, got.t1).c_str(),
                    got.miss, got.tag);
        return false;
      }
      expected.pop_front();
      ++checked;
    }
    if (in_fire) {
      expected.push_back(Model(a, pending));
      have_pending = false;
      ++sent;
    }
    dut.clk_i = 1;
    dut.eval();
  }
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
