// Verilator bench for rtl/fp_cmp.sv (Stages = 1) against kdrt::fp::Lt, Le,
// Eq, Min and Max: every pair of e4m3, and corner plus random pairs for each
// preset.
#include "Vfp_cmp_bf16.h"
#include "Vfp_cmp_e4m3.h"
#include "Vfp_cmp_fp16.h"
#include "Vfp_cmp_fp24.h"
#include "Vfp_cmp_fp32.h"
#include "tests/rtl/fp_bench.h"

namespace kdrt::fp::bench {
namespace {

template <class Dut>
bool Run(Format f) {
  return RunUnit<Dut>(
      "fp_cmp", f, 1, PairSource(f, RandomCount(), 300 + f.m),
      [](Dut& d, const Vec& v) {
        d.a_i = v.a;
        d.b_i = v.b;
      },
      [](const Dut& d) { return Out{d.lt_o, d.le_o, d.eq_o, d.min_o, d.max_o}; },
      [f](const Vec& v) {
        return Out{Lt(f, v.a, v.b), Le(f, v.a, v.b), Eq(f, v.a, v.b), Min(f, v.a, v.b),
                   Max(f, v.a, v.b)};
      },
      5, 13);
}

}  // namespace
}  // namespace kdrt::fp::bench

int main() {
  using namespace kdrt::fp;
  using namespace kdrt::fp::bench;
  bool ok = Run<Vfp_cmp_e4m3>(MakeFormat(4, 3));
  ok = Run<Vfp_cmp_fp32>(kFp32) && ok;
  ok = Run<Vfp_cmp_fp24>(kFp24) && ok;
  ok = Run<Vfp_cmp_bf16>(kBf16) && ok;
  ok = Run<Vfp_cmp_fp16>(kFp16) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
