// Verilator bench of rtl/rt_hit_merge.sv against a C++ model of the threads'
// closest hits, per preset, cycle by cycle: a new ray's init (no hit, t =
// tmax, u = v = 0, id all ones), and the merge of a test result with
// TraceRay's rule (sw/trace/traversal.h) on the model's comparisons
// (fp::Lt, fp::Eq):
//   take = hit && (t < best.t || (t == best.t && (no hit yet || id < best.id)))
// checked on cand_take_o in the cycle of the result and on the three read
// ports (random threads) every cycle: hit, t and id as they are, u and v
// (a memory's registered read) in the cycle after a read, of a thread that
// had a hit when it was read, held while no read follows; an init and a result for the same
// thread in one cycle: the init wins. Values come from a small pool of random
// encodings of the format (with zeros, infinities and NaNs) and ids from a
// small range, so that ties in t and in the id are frequent; inits and
// results are random in regimes (many inits, many results, mixed).
#include <array>
#include <cstdio>

#include "Vrt_hit_merge_bf16.h"
#include "Vrt_hit_merge_fp16.h"
#include "Vrt_hit_merge_fp24.h"
#include "Vrt_hit_merge_fp32.h"
#include "fp/format.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using fp::Format;
using sim::SimCtrl;

// As verilated (tests/rtl/CMakeLists.txt): Threads 3 (not a power of two),
// PrimWidth 8.
constexpr unsigned kThreads = 3;
constexpr uint32_t kPrimMask = 0xFF;

struct Best {
  bool hit = false;
  uint32_t t = 0, u = 0, v = 0, prim = kPrimMask;
};

uint32_t RandomValue(Format f, Rng& rng) {
  const uint32_t exp_ones = ((1u << f.e) - 1) << f.m;
  switch (rng.Below(10)) {
    case 0: return 0;
    case 1: return 1u << (f.e + f.m);                                   // -0
    case 2: return exp_ones;                                            // +inf
    case 3: return exp_ones | (rng.Bits32() & ((1u << f.m) - 1)) | 1u;  // NaN
    default: return rng.Bits32() & f.WidthMask() & ~(1u << (f.e + f.m));  // mostly positive
  }
}

template <class Dut>
bool Run(Format f, uint64_t cycles) {
  SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  dut.init_i = 0;
  dut.cand_valid_i = 0;
  sim.Reset();
  Rng rng(47 + f.m);
  std::array<Best, kThreads> model;
  std::array<bool, kThreads> known{};  // the thread has had an init since reset
  std::array<uint32_t, 5> pool{};
  bool uv_shown = false;  // out_u_o, out_v_o show a read of a thread with a hit
  Best uv_read;
  uint64_t uv_checked = 0;
  double p_init = 0.1, p_cand = 0.5, p_hit = 0.7;
  uint64_t results = 0, by_lt = 0, by_id = 0, by_first = 0, kept = 0, collisions = 0;
  for (uint64_t cycle = 0; cycle < cycles; ++cycle) {
    if (cycle % 200 == 0) {
      const unsigned regime = rng.Below(3);  // many inits, many results, mixed
      p_init = regime == 0 ? 0.6 : regime == 1 ? 0.02 : 0.1;
      p_cand = regime == 0 ? 0.3 : regime == 1 ? 0.9 : 0.5;
      p_hit = std::array<double, 3>{0.2, 0.7, 1.0}[rng.Below(3)];
      for (uint32_t& v : pool) v = RandomValue(f, rng);
    }
    auto value = [&] { return rng.Chance(0.8) ? pool[rng.Below(pool.size())] : RandomValue(f, rng); };
    // Until every thread is known, inits go round the threads.
    const bool init = cycle < kThreads || rng.Chance(p_init);
    const unsigned ii = cycle < kThreads ? static_cast<unsigned>(cycle) : rng.Below(kThreads);
    const uint32_t init_t = value();
    const bool cand = rng.Chance(p_cand), cand_hit = rng.Chance(p_hit);
    const unsigned ci = rng.Below(kThreads);
    Best c;
    c.hit = true;
    c.t = value();
    c.u = RandomValue(f, rng);
    c.v = RandomValue(f, rng);
    c.prim = rng.Chance(0.5) ? rng.Below(4) : rng.Bits32() & kPrimMask;
    const unsigned li = rng.Below(kThreads), ei = rng.Below(kThreads), oi = rng.Below(kThreads);
    dut.init_i = init;
    dut.init_idx_i = ii;
    dut.init_t_i = init_t;
    dut.cand_valid_i = cand;
    dut.cand_idx_i = ci;
    dut.cand_hit_i = cand_hit;
    dut.cand_prim_i = c.prim;
    dut.cand_t_i = c.t;
    dut.cand_u_i = c.u;
    dut.cand_v_i = c.v;
    dut.leaf_idx_i = li;
    dut.exit_idx_i = ei;
    dut.out_idx_i = oi;
    // rt_core never reads a thread's u, v in the cycle a result updates them.
    const bool out_re = rng.Chance(0.5) && !(cand && ci == oi);
    dut.out_re_i = out_re;
    sim.Settle();

    bool take = false;
    if (cand && known[ci]) {
      const Best& b = model[ci];
      const bool lt = fp::Lt(f, c.t, b.t), eq = fp::Eq(f, c.t, b.t);
      take = cand_hit && (lt || (eq && (!b.hit || c.prim < b.prim)));
      if (cand_hit) {
        ++results;
        by_lt += lt;
        by_id += !lt && take && b.hit;
        by_first += !lt && take && !b.hit;
        kept += !take;
      }
    }
    bool bad = cand && known[ci] && static_cast<bool>(dut.cand_take_o) != take;
    if (known[li]) bad = bad || dut.leaf_t_o != model[li].t;
    if (known[ei]) bad = bad || static_cast<bool>(dut.exit_hit_o) != model[ei].hit || dut.exit_t_o != model[ei].t;
    if (known[oi]) {
      const Best& b = model[oi];
      bad = bad || static_cast<bool>(dut.out_hit_o) != b.hit || dut.out_prim_o != b.prim || dut.out_t_o != b.t;
    }
    if (uv_shown) {
      bad = bad || dut.out_u_o != uv_read.u || dut.out_v_o != uv_read.v;
      ++uv_checked;
    }
    if (bad) {
      std::printf("rt_hit_merge %s: FAIL at cycle %llu\n", f.Name().c_str(), static_cast<unsigned long long>(cycle));
      if (cand && known[ci]) {
        std::printf("  result for thread %u: hit %d t 0x%08x id 0x%02x; best hit %d t 0x%08x id 0x%02x: take %d, "
                    "model %d\n",
                    ci, cand_hit, c.t, c.prim, model[ci].hit, model[ci].t, model[ci].prim, dut.cand_take_o, take);
      }
      std::printf("  leaf port thread %u: t 0x%08x (model 0x%08x)\n", li, dut.leaf_t_o, model[li].t);
      std::printf("  exit port thread %u: hit %d t 0x%08x (model %d 0x%08x)\n", ei, dut.exit_hit_o, dut.exit_t_o,
                  model[ei].hit, model[ei].t);
      std::printf("  out port thread %u: hit %d id 0x%02x t 0x%08x u 0x%08x v 0x%08x (model %d 0x%02x 0x%08x "
                  "0x%08x 0x%08x)\n",
                  oi, dut.out_hit_o, dut.out_prim_o, dut.out_t_o, dut.out_u_o, dut.out_v_o, model[oi].hit,
                  model[oi].prim, model[oi].t, uv_read.u, uv_read.v);
      return false;
    }
    sim.Tick();
    if (out_re) {
      uv_shown = known[oi] && model[oi].hit;
      uv_read = model[oi];
    }
    if (init) {
      model[ii] = Best{false, init_t, 0, 0, kPrimMask};
      known[ii] = true;
      collisions += take && ci == ii;
    }
    if (take && !(init && ci == ii)) model[ci] = c;
  }
  if (by_lt == 0 || by_id == 0 || by_first == 0 || kept == 0 || collisions == 0 || uv_checked == 0) {
    std::printf("rt_hit_merge %s: FAIL: the traffic missed a case (taken by t %llu, by id %llu, first hit at "
                "equal t %llu; kept %llu; init and take on one thread %llu; u, v read %llu)\n",
                f.Name().c_str(), static_cast<unsigned long long>(by_lt), static_cast<unsigned long long>(by_id),
                static_cast<unsigned long long>(by_first), static_cast<unsigned long long>(kept),
                static_cast<unsigned long long>(collisions), static_cast<unsigned long long>(uv_checked));
    return false;
  }
  std::printf("rt_hit_merge %s: PASS (%llu cycles, %llu hit results: taken by t %llu, by id %llu, first hit at "
              "equal t %llu; kept %llu; init and take on one thread %llu)\n",
              f.Name().c_str(), static_cast<unsigned long long>(cycles), static_cast<unsigned long long>(results),
              static_cast<unsigned long long>(by_lt), static_cast<unsigned long long>(by_id),
              static_cast<unsigned long long>(by_first), static_cast<unsigned long long>(kept),
              static_cast<unsigned long long>(collisions));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  using namespace kdrt::fp;
  Verilated::commandArgs(argc, argv);
  const uint64_t cycles = LongRun() ? 10000000 : 1000000;
  bool ok = Run<Vrt_hit_merge_fp32>(kFp32, cycles);
  ok = Run<Vrt_hit_merge_fp24>(kFp24, cycles) && ok;
  ok = Run<Vrt_hit_merge_bf16>(kBf16, cycles) && ok;
  ok = Run<Vrt_hit_merge_fp16>(kFp16, cycles) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
