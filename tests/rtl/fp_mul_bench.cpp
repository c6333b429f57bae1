// Verilator bench for rtl/fp_mul.sv against kdrt::fp::Mul: every pair of
// e4m3, and corner plus random pairs for each preset.
#include "Vfp_mul_bf16.h"
#include "Vfp_mul_e4m3.h"
#include "Vfp_mul_fp16.h"
#include "Vfp_mul_fp24.h"
#include "Vfp_mul_fp32.h"
#include "tests/rtl/fp_bench.h"

namespace kdrt::fp::bench {
namespace {

template <class Dut>
bool Run(Format f) {
  return RunUnit<Dut>(
      "fp_mul", f, kdrt_fp_latency::kMul, PairSource(f, RandomCount(), 200 + f.m),
      [](Dut& d, const Vec& v) {
        d.a_i = v.a;
        d.b_i = v.b;
      },
      [](const Dut& d) { return Out{d.res_o}; },
      [f](const Vec& v) { return Out{Mul(f, v.a, v.b)}; }, 1, 12);
}

}  // namespace
}  // namespace kdrt::fp::bench

int main() {
  using namespace kdrt::fp;
  using namespace kdrt::fp::bench;
  bool ok = Run<Vfp_mul_e4m3>(MakeFormat(4, 3));
  ok = Run<Vfp_mul_fp32>(kFp32) && ok;
  ok = Run<Vfp_mul_fp24>(kFp24) && ok;
  ok = Run<Vfp_mul_bf16>(kBf16) && ok;
  ok = Run<Vfp_mul_fp16>(kFp16) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
