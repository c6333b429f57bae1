// Verilator bench for rtl/fp_ldexp.sv (combinational) against
// kdrt::fp::Ldexp: every encoding of formats up to 16 bits with every shift
// that can matter, corner values and random encodings and shifts otherwise.
#include <cstdio>

#include "Vfp_ldexp_bf16.h"
#include "Vfp_ldexp_e4m3.h"
#include "Vfp_ldexp_fp16.h"
#include "Vfp_ldexp_fp24.h"
#include "Vfp_ldexp_fp32.h"
#include "tests/rtl/fp_bench.h"

namespace kdrt::fp::bench {
namespace {

constexpr int kShiftBits = 10;  // the module's default NW
constexpr int kMinShift = -(1 << (kShiftBits - 1)), kMaxShift = (1 << (kShiftBits - 1)) - 1;

template <class Dut>
bool Run(Format f) {
  Dut dut;
  uint64_t n = 0;
  auto check = [&](uint32_t a, int shift) {
    dut.a_i = a;
    dut.n_i = static_cast<uint32_t>(shift) & ((1u << kShiftBits) - 1);
    dut.eval();
    ++n;
    const uint32_t want = Ldexp(f, a, shift);
    if (dut.y_o != want) {
      std::printf("FAIL fp_ldexp %s: first mismatch: a=%s n=%d: rtl %s, model %s\n", f.Name().c_str(),
                  test::Hex(a).c_str(), shift, test::Hex(dut.y_o).c_str(), test::Hex(want).c_str());
      return false;
    }
    return true;
  };
  const int reach = (1 << f.e) + 2;  // beyond it every result saturates
  if (f.Width() <= 16) {
    for (uint32_t a = 0; a < (1u << f.Width()); ++a) {
      for (int s = -reach; s <= reach; ++s) {
        if (!check(a, s)) return false;
      }
      if (!check(a, kMinShift) || !check(a, kMaxShift)) return false;
    }
  } else {
    for (uint32_t a : test::CornerValues(f)) {
      for (int s = -reach; s <= reach; ++s) {
        if (!check(a, s)) return false;
      }
    }
    test::Rng rng(900 + f.m);
    for (uint64_t i = 0; i < RandomCount(); ++i) {
      const int s = static_cast<int>(rng.Next() % (kMaxShift - kMinShift + 1)) + kMinShift;
      if (!check(static_cast<uint32_t>(rng.Next()) & f.WidthMask(), s)) return false;
    }
  }
  dut.final();
  std::printf("PASS fp_ldexp %s: %llu vectors, combinational\n", f.Name().c_str(), static_cast<unsigned long long>(n));
  return true;
}

}  // namespace
}  // namespace kdrt::fp::bench

int main() {
  using namespace kdrt::fp;
  using namespace kdrt::fp::bench;
  bool ok = Run<Vfp_ldexp_e4m3>(MakeFormat(4, 3));
  ok = Run<Vfp_ldexp_fp32>(kFp32) && ok;
  ok = Run<Vfp_ldexp_fp24>(kFp24) && ok;
  ok = Run<Vfp_ldexp_bf16>(kBf16) && ok;
  ok = Run<Vfp_ldexp_fp16>(kFp16) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
