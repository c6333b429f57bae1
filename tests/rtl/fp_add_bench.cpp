// Verilator bench for rtl/fp_add.sv against kdrt::fp::Add/Sub: every pair of
// e4m3 for both add and sub, and corner plus random pairs (random sub_i) for
// each preset.
#include "Vfp_add_bf16.h"
#include "Vfp_add_e4m3.h"
#include "Vfp_add_fp16.h"
#include "Vfp_add_fp24.h"
#include "Vfp_add_fp32.h"
#include "tests/rtl/fp_bench.h"

namespace kdrt::fp::bench {
namespace {

template <class Dut>
bool Run(Format f) {
  // Exhaustive formats: every pair as an add, then again as a sub.
  Source pairs = PairSource(f, RandomCount(), 100 + f.m);
  Source again = PairSource(f, RandomCount(), 100 + f.m);
  const bool exhaustive = f.Width() <= 8;
  auto rng = std::make_shared<test::Rng>(7);
  bool second = false;
  Source src = [=](Vec& v) mutable {
    if (!second) {
      if (pairs(v)) {
        v.sub = exhaustive ? false : rng->Below(2) != 0;
        return true;
      }
      if (!exhaustive) return false;
      second = true;
    }
    if (!again(v)) return false;
    v.sub = true;
    return true;
  };
  return RunUnit<Dut>(
      "fp_add", f, kdrt_fp_latency::kAdd, src,
      [](Dut& d, const Vec& v) {
        d.a_i = v.a;
        d.b_i = v.b;
        d.sub_i = v.sub;
      },
      [](const Dut& d) { return Out{d.res_o}; },
      [f](const Vec& v) { return Out{v.sub ? Sub(f, v.a, v.b) : Add(f, v.a, v.b)}; }, 1, 11);
}

}  // namespace
}  // namespace kdrt::fp::bench

int main() {
  using namespace kdrt::fp;
  using namespace kdrt::fp::bench;
  bool ok = Run<Vfp_add_e4m3>(MakeFormat(4, 3));
  ok = Run<Vfp_add_fp32>(kFp32) && ok;
  ok = Run<Vfp_add_fp24>(kFp24) && ok;
  ok = Run<Vfp_add_bf16>(kBf16) && ok;
  ok = Run<Vfp_add_fp16>(kFp16) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
