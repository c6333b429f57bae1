// Verilator bench for rtl/fp_from_f32.sv against kdrt::fp::FromF32Bits:
// binary32 corner values, values around the target format's smallest and
// largest normals (rounding into FTZ and overflow), subnormals, NaNs, and
// random bits.
#include "Vfp_from_f32_bf16.h"
#include "Vfp_from_f32_e4m3.h"
#include "Vfp_from_f32_fp16.h"
#include "Vfp_from_f32_fp24.h"
#include "Vfp_from_f32_fp32.h"
#include "tests/rtl/fp_bench.h"

#include <algorithm>

namespace kdrt::fp::bench {
namespace {

Source F32Source(Format f, uint64_t n, uint64_t seed) {
  auto corners = std::make_shared<std::vector<uint32_t>>(test::CornerValues(kFp32));
  auto rng = std::make_shared<test::Rng>(seed);
  auto i = std::make_shared<uint64_t>(0);
  return [=](Vec& v) {
    const uint64_t k = (*i)++;
    if (k < corners->size()) {
      v = {(*corners)[k], 0, false};
      return true;
    }
    if (k >= corners->size() + n) return false;
    uint32_t bits = static_cast<uint32_t>(rng->Next());
    switch (rng->Below(4)) {
      case 0:  // fp32 subnormal
        bits &= 0x807FFFFFu;
        break;
      case 1: {  // near the target's smallest or largest normal
        const int unbiased =
            (rng->Below(2) ? f.Bias() : 1 - f.Bias()) + static_cast<int>(rng->Below(5)) - 2;
        const int e32 = std::min(255, std::max(0, 127 + unbiased));
        bits = (bits & 0x807FFFFFu) | static_cast<uint32_t>(e32) << 23;
        // Sometimes exactly halfway between two target values.
        if (rng->Below(2) && f.m < 23) {
          bits = (bits & ~((1u << (23 - f.m)) - 1)) | (1u << (22 - f.m));
        }
        break;
      }
      default:
        break;
    }
    v = {bits, 0, false};
    return true;
  };
}

template <class Dut>
bool Run(Format f) {
  return RunUnit<Dut>(
      "fp_from_f32", f, kdrt_fp_latency::kFromF32, F32Source(f, RandomCount(), 400 + f.m),
      [](Dut& d, const Vec& v) { d.f32_i = v.a; },
      [](const Dut& d) { return Out{d.res_o}; },
      [f](const Vec& v) { return Out{FromF32Bits(f, v.a)}; }, 1, 14);
}

}  // namespace
}  // namespace kdrt::fp::bench

int main() {
  using namespace kdrt::fp;
  using namespace kdrt::fp::bench;
  bool ok = Run<Vfp_from_f32_e4m3>(MakeFormat(4, 3));
  ok = Run<Vfp_from_f32_fp32>(kFp32) && ok;
  ok = Run<Vfp_from_f32_fp24>(kFp24) && ok;
  ok = Run<Vfp_from_f32_bf16>(kBf16) && ok;
  ok = Run<Vfp_from_f32_fp16>(kFp16) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
