// Verilator bench of rtl/rt_hit_out.sv against a C++ model of the hit record
// register, per preset, cycle by cycle: in_ready_o (the register is empty or
// leaves this cycle), hit_valid_o, and the record: ray id, hit, overflow and,
// on a hit, the triangle id, t widened to fp32 by the model's fp::ToFloat
// and taken back to world units by DistanceToWorld (sw/trace/frame.h) with
// the ray's distance scale k, and u, v widened; on a miss 0xFFFFFFFF, +inf,
// 0, 0. The offered record changes at random while it is not taken (the
// core's arbiter may switch rays); hit_ready_i is random in regimes. Values
// are random encodings of the format, with zeros, infinities and NaNs mixed
// in; k covers the whole range a ray can have (|k| <= 383) and beyond to the
// port's limits. The ray id, u and v come from rt_core's memories, read in
// the cycle a record is taken and shown from the next cycle until the next
// read: the bench drives them so.
#include <array>
#include <cstdio>

#include "Vrt_hit_out_bf16.h"
#include "Vrt_hit_out_fp16.h"
#include "Vrt_hit_out_fp24.h"
#include "Vrt_hit_out_fp32.h"
#include "fp/format.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"
#include "trace/frame.h"

namespace kdrt::rtlbench {
namespace {

using fp::Format;
using sim::SimCtrl;

constexpr uint32_t kPrimMask = 0xFFFFFF;  // PrimWidth = 24, the default
constexpr int kTScaleWidth = 10;          // kdrt_pkg::TScaleWidth

int RandomTScale(Rng& rng) {
  switch (rng.Below(4)) {
    case 0: return static_cast<int>(rng.Below(41)) - 20;  // ordinary scenes
    case 1: return static_cast<int>(rng.Below(1u << kTScaleWidth)) - (1 << (kTScaleWidth - 1));  // any 10-bit value
    default: return static_cast<int>(rng.Below(767)) - 383;  // what a ray can have: |m - s| <= 383
  }
}

struct Record {
  uint32_t ray_id = 0, prim = 0, t = 0, u = 0, v = 0;
  bool hit = false, overflow = false;
  int t_scale = 0;  // input only
  bool operator==(const Record& o) const {
    return ray_id == o.ray_id && prim == o.prim && t == o.t && u == o.u && v == o.v && hit == o.hit &&
           overflow == o.overflow;
  }
};

uint32_t RandomValue(Format f, Rng& rng) {
  const uint32_t exp_ones = ((1u << f.e) - 1) << f.m;
  switch (rng.Below(8)) {
    case 0: return 0;
    case 1: return exp_ones;                                  // +inf
    case 2: return exp_ones | (rng.Bits32() & ((1u << f.m) - 1)) | 1u;  // NaN
    default: return rng.Bits32() & f.WidthMask();
  }
}

// What the register holds after taking `in` (datapath-format t, u, v).
Record Widen(Format f, const Record& in) {
  Record r = in;
  r.prim = in.hit ? in.prim : 0xFFFFFFFFu;
  r.t = in.hit ? fp::BitsOf(DistanceToWorld(fp::ToFloat(f, in.t), in.t_scale)) : 0x7F800000u;
  r.u = in.hit ? fp::BitsOf(fp::ToFloat(f, in.u)) : 0u;
  r.v = in.hit ? fp::BitsOf(fp::ToFloat(f, in.v)) : 0u;
  return r;
}

template <class Dut>
bool Run(Format f, uint64_t cycles) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  dut.in_valid_i = 0;
  dut.hit_ready_i = 0;
  sim.Reset();
  Rng rng(23 + f.m);
  bool held = false;  // the model's register
  Record reg, offer;
  bool offering = false;
  double p_offer = 0.5, p_ready = 0.5;
  uint64_t taken = 0, delivered = 0;
  for (uint64_t cycle = 0; cycle < cycles; ++cycle) {
    if (cycle % 256 == 0) {
      p_offer = std::array<double, 3>{0.9, 0.5, 0.1}[rng.Below(3)];
      p_ready = std::array<double, 4>{1.0, 0.9, 0.5, 0.1}[rng.Below(4)];
    }
    if (!offering || rng.Chance(0.2)) {  // a new offer, or the offer changes while not taken
      offering = rng.Chance(p_offer);
      offer = Record{rng.Bits32(), rng.Bits32() & kPrimMask, RandomValue(f, rng), RandomValue(f, rng),
                     RandomValue(f, rng), rng.Chance(0.6), rng.Chance(0.05), RandomTScale(rng)};
    }
    dut.in_valid_i = offering;
    dut.in_hit_i = offer.hit;
    dut.in_prim_i = offer.prim;
    dut.in_t_i = offer.t;
    dut.in_t_scale_i = static_cast<uint32_t>(offer.t_scale) & ((1u << kTScaleWidth) - 1);
    dut.in_overflow_i = offer.overflow;
    dut.hit_ready_i = rng.Chance(p_ready);
    sim.Settle();
    const Record got{dut.hit_ray_id_o, dut.hit_prim_o, dut.hit_t_o, dut.hit_u_o, dut.hit_v_o, dut.hit_o != 0,
                     dut.hit_overflow_o != 0};
    const bool ready = !held || dut.hit_ready_i;
    if (static_cast<bool>(dut.in_ready_o) != ready || static_cast<bool>(dut.hit_valid_o) != held ||
        (held && !(got == reg))) {
      std::printf("rt_hit_out %s: FAIL at cycle %llu: in_ready %d (model %d), hit_valid %d (model %d)\n",
                  f.Name().c_str(), static_cast<unsigned long long>(cycle), dut.in_ready_o, ready,
                  dut.hit_valid_o, held);
      std::printf("  model: id %u hit %d prim 0x%08x t 0x%08x (k %d) u 0x%08x v 0x%08x ovf %d\n", reg.ray_id,
                  reg.hit, reg.prim, reg.t, reg.t_scale, reg.u, reg.v, reg.overflow);
      std::printf("  rtl:   id %u hit %d prim 0x%08x t 0x%08x u 0x%08x v 0x%08x ovf %d\n", got.ray_id, got.hit,
                  got.prim, got.t, got.u, got.v, got.overflow);
      return false;
    }
    const bool out_fire = held && dut.hit_ready_i;
    const bool in_fire = offering && ready;
    sim.Tick();
    delivered += out_fire;
    if (out_fire) held = false;
    if (in_fire) {
      dut.rd_ray_id_i = offer.ray_id;  // the memories' read of the taken ray
      dut.rd_u_i = offer.u;
      dut.rd_v_i = offer.v;
      reg = Widen(f, offer);
      held = true;
      offering = false;
      ++taken;
    }
  }
  std::printf("rt_hit_out %s: PASS (%llu cycles, %llu records taken, %llu delivered)\n", f.Name().c_str(),
              static_cast<unsigned long long>(cycles), static_cast<unsigned long long>(taken),
              static_cast<unsigned long long>(delivered));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  using namespace kdrt::fp;
  Verilated::commandArgs(argc, argv);
  const uint64_t cycles = LongRun() ? 10000000 : 1000000;
  bool ok = Run<Vrt_hit_out_fp32>(kFp32, cycles);
  ok = Run<Vrt_hit_out_fp24>(kFp24, cycles) && ok;
  ok = Run<Vrt_hit_out_bf16>(kBf16, cycles) && ok;
  ok = Run<Vrt_hit_out_fp16>(kFp16, cycles) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
