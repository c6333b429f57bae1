// The generic (E, M) arithmetic against MPFR: exhaustive for e4m3, random and
// corner pairs for every preset. KDRT_LONG=1 runs 1e7 random pairs per preset
// and operation instead of 1e6.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "fp/format.h"
#include "tests/fp/fp_vectors.h"
#include "tests/fp/mpfr_reference.h"

namespace kdrt::fp {
namespace {

using test::Op;

uint32_t Model(Format f, Op op, uint32_t a, uint32_t b) {
  switch (op) {
    case Op::kAdd: return Add(f, a, b);
    case Op::kSub: return Sub(f, a, b);
    case Op::kMul: return Mul(f, a, b);
    case Op::kDiv: return Div(f, a, b);
    case Op::kMin: return Min(f, a, b);
    case Op::kMax: return Max(f, a, b);
    case Op::kLt: return Lt(f, a, b);
    case Op::kLe: return Le(f, a, b);
    case Op::kEq: return Eq(f, a, b);
  }
  return 0;
}

const Op kAllOps[] = {Op::kAdd, Op::kSub, Op::kMul, Op::kDiv, Op::kMin,
                      Op::kMax, Op::kLt,  Op::kLe,  Op::kEq};

// Checks one pair; returns false (after one gtest failure) on a mismatch so
// that a broken operation reports its first failing pair only.
bool Check(Format f, test::MpfrReference& ref, Op op, uint32_t a, uint32_t b) {
  const uint32_t want = ref.Compute(op, a, b);
  const uint32_t got = Model(f, op, a, b);
  if (want == got) return true;
  ADD_FAILURE() << f.Name() << " " << test::OpName(op) << "(" << test::Hex(a) << ", "
                << test::Hex(b) << "): model " << test::Hex(got) << ", MPFR " << test::Hex(want);
  return false;
}

TEST(FpMpfr, ExhaustiveE4M3) {
  const Format f = MakeFormat(4, 3);
  test::MpfrReference ref(f);
  for (Op op : kAllOps) {
    for (uint32_t a = 0; a < 256; ++a) {
      for (uint32_t b = 0; b < 256; ++b) {
        if (!Check(f, ref, op, a, b)) goto next_op;
      }
    }
  next_op:;
  }
}

// Also a format with the narrowest exponent and a wide mantissa, and one with
// a one-bit mantissa: the edges of the accepted range.
TEST(FpMpfr, ExhaustiveE2M5AndE5M1) {
  for (Format f : {MakeFormat(2, 5), MakeFormat(5, 1)}) {
    test::MpfrReference ref(f);
    const uint32_t n = 1u << f.Width();
    for (Op op : kAllOps) {
      bool ok = true;
      for (uint32_t a = 0; a < n && ok; ++a) {
        for (uint32_t b = 0; b < n && ok; ++b) ok = Check(f, ref, op, a, b);
      }
    }
  }
}

class FpMpfrPreset : public ::testing::TestWithParam<Format> {};

TEST_P(FpMpfrPreset, CornerPairs) {
  const Format f = GetParam();
  test::MpfrReference ref(f);
  const std::vector<uint32_t> corners = test::CornerValues(f);
  for (Op op : kAllOps) {
    bool ok = true;
    for (uint32_t a : corners) {
      for (uint32_t b : corners) {
        if (ok) ok = Check(f, ref, op, a, b);
      }
    }
  }
}

TEST_P(FpMpfrPreset, RandomPairs) {
  const Format f = GetParam();
  test::MpfrReference ref(f);
  const std::vector<uint32_t> corners = test::CornerValues(f);
  test::Rng rng(0x5EED0000u + static_cast<uint64_t>(f.e * 32 + f.m));
  const uint64_t n = test::RandomPairCount();
  bool ok[9] = {true, true, true, true, true, true, true, true, true};
  for (uint64_t i = 0; i < n; ++i) {
    const auto [a, b] = test::RandomPair(f, rng, corners);
    for (int k = 0; k < 9; ++k) {
      if (ok[k]) ok[k] = Check(f, ref, kAllOps[k], a, b);
    }
  }
}

// Conversion from binary32 against MPFR (rounding a float, which is exact in
// double, once to the format), including subnormal and NaN inputs.
TEST_P(FpMpfrPreset, FromF32Bits) {
  const Format f = GetParam();
  test::MpfrReference ref(f);
  test::Rng rng(42);
  const uint64_t n = test::RandomPairCount();
  for (uint64_t i = 0; i < n; ++i) {
    uint32_t bits = static_cast<uint32_t>(rng.Next());
    if (i % 7 == 0) bits &= 0x807FFFFFu;                                // fp32 subnormal
    if (i % 11 == 0) {  // near the format's smallest or largest normal
      const int unbiased = ((i & 1) ? f.Bias() : 1 - f.Bias()) + static_cast<int>(rng.Below(3)) - 1;
      bits = (bits & 0x807FFFFFu) | static_cast<uint32_t>(127 + unbiased) << 23;
    }
    uint32_t want;
    if ((bits & 0x7F800000u) == 0) {
      want = (bits >> 31) ? f.SignMask() : 0;  // DAZ
    } else {
      want = ref.RoundDouble(static_cast<double>(FloatOf(bits)));
    }
    const uint32_t got = FromF32Bits(f, bits);
    ASSERT_EQ(got, want) << f.Name() << " FromF32Bits(" << test::Hex(bits) << ")";
  }
}

INSTANTIATE_TEST_SUITE_P(Presets, FpMpfrPreset, ::testing::ValuesIn(Presets()),
                         [](const ::testing::TestParamInfo<Format>& info) {
                           return info.param.Name();
                         });

}  // namespace
}  // namespace kdrt::fp
