// Verilator bench for rtl/fp_to_f32.sv (combinational) against
// kdrt::fp::ToFloat: every encoding of formats up to 16 bits, corner values
// and random encodings of fp32 and fp24.
#include <cstdio>

#include "Vfp_to_f32_bf16.h"
#include "Vfp_to_f32_e4m3.h"
#include "Vfp_to_f32_fp16.h"
#include "Vfp_to_f32_fp24.h"
#include "Vfp_to_f32_fp32.h"
#include "tests/rtl/fp_bench.h"

namespace kdrt::fp::bench {
namespace {

template <class Dut>
bool Run(Format f) {
  sim::SimCtrl<Dut> sim;  // no clock: every check is one Settle()
  Dut& dut = sim.top();
  auto check = [&](uint32_t a) {
    dut.a_i = a;
    sim.Settle();
    const uint32_t want = BitsOf(ToFloat(f, a));
    if (dut.f32_o != want) {
      std::printf("FAIL fp_to_f32 %s: first mismatch: a=%s: rtl %s, model %s\n",
                  f.Name().c_str(), test::Hex(a).c_str(), test::Hex(dut.f32_o).c_str(),
                  test::Hex(want).c_str());
      return false;
    }
    return true;
  };
  uint64_t n = 0;
  if (f.Width() <= 16) {
    for (uint32_t a = 0; a < (1u << f.Width()); ++a, ++n) {
      if (!check(a)) return false;
    }
  } else {
    for (uint32_t a : test::CornerValues(f)) {
      if (!check(a)) return false;
      ++n;
    }
    test::Rng rng(500 + f.m);
    for (uint64_t i = 0; i < RandomCount(); ++i, ++n) {
      if (!check(static_cast<uint32_t>(rng.Next()) & f.WidthMask())) return false;
    }
  }
  std::printf("PASS fp_to_f32 %s: %llu vectors, combinational\n", f.Name().c_str(),
              static_cast<unsigned long long>(n));
  return true;
}

}  // namespace
}  // namespace kdrt::fp::bench

int main() {
  using namespace kdrt::fp;
  using namespace kdrt::fp::bench;
  bool ok = Run<Vfp_to_f32_e4m3>(MakeFormat(4, 3));
  ok = Run<Vfp_to_f32_fp32>(kFp32) && ok;
  ok = Run<Vfp_to_f32_fp24>(kFp24) && ok;
  ok = Run<Vfp_to_f32_bf16>(kBf16) && ok;
  ok = Run<Vfp_to_f32_fp16>(kFp16) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
