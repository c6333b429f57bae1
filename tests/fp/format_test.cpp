// Directed cases for the (E, M) model whose expected encodings follow from
// IEEE 754 binary16/bfloat16/binary32 and the policy in fp/format.h.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "fp/format.h"

namespace kdrt::fp {
namespace {

TEST(FpFormat, ParsesNamesAndRejectsBadOnes) {
  EXPECT_EQ(ParseFormat("fp32"), (Format{8, 23}));
  EXPECT_EQ(ParseFormat("fp24"), (Format{7, 16}));
  EXPECT_EQ(ParseFormat("bf16"), (Format{8, 7}));
  EXPECT_EQ(ParseFormat("fp16"), (Format{5, 10}));
  EXPECT_EQ(ParseFormat("e4m3"), (Format{4, 3}));
  EXPECT_EQ(ParseFormat("e8m23"), kFp32);
  EXPECT_EQ(ParseFormat("e4m3").Name(), "e4m3");
  EXPECT_EQ(kBf16.Name(), "bf16");
  for (const char* bad : {"", "fp63", "FP64", "e11m51", "e9m3", "e1m3", "e4m0", "e4m24", "e4m3x", "e4", "m3",
                          "e-4m3", "e 4m3", "e4m+3"}) {
    EXPECT_THROW(ParseFormat(bad), InputError) << bad;
  }
  EXPECT_THROW(MakeFormat(8, 24), InputError);
  EXPECT_THROW(SoftArith(Format{0, 0}), InputError);
  EXPECT_EQ(Presets().size(), 4u);
}

// fp64 is a name for the native double reference, not a soft format: it
// parses, but nothing that computes on encodings accepts it.
TEST(FpFormat, Fp64IsParsedButNotASoftFormat) {
  EXPECT_EQ(ParseFormat("fp64"), kFp64);
  EXPECT_EQ(ParseFormat("e11m52"), kFp64);
  EXPECT_TRUE(ParseFormat("fp64").IsFp64());
  EXPECT_FALSE(kFp32.IsFp64());
  EXPECT_EQ(kFp64.Name(), "fp64");
  EXPECT_THROW(MakeFormat(11, 52), InputError);
  EXPECT_THROW(SoftArith{kFp64}, InputError);
  for (const Format& f : Presets()) EXPECT_FALSE(f.IsFp64());
  try {
    ParseFormat("fp99");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fp64"), std::string::npos) << e.what();
  }
}

TEST(FpFormat, Helpers) {
  EXPECT_EQ(kFp16.Width(), 16);
  EXPECT_EQ(kFp24.Width(), 24);
  EXPECT_EQ(kFp16.Bias(), 15);
  EXPECT_EQ(kFp16.CanonicalNaN(), 0x7E00u);
  EXPECT_EQ(kFp32.CanonicalNaN(), 0x7FC00000u);
  EXPECT_EQ(kBf16.CanonicalNaN(), 0x7FC0u);
  EXPECT_EQ(kFp16.Inf(true), 0xFC00u);
  EXPECT_EQ(kFp16.One(), 0x3C00u);
  EXPECT_EQ(kBf16.One(), 0x3F80u);
}

TEST(FpFormat, ConversionsRoundToNearestEven) {
  EXPECT_EQ(FromDouble(kFp16, 1.0), 0x3C00u);
  EXPECT_EQ(FromDouble(kFp16, -2.0), 0xC000u);
  EXPECT_EQ(FromDouble(kFp16, 65504.0), 0x7BFFu);  // largest finite
  EXPECT_EQ(FromDouble(kFp16, 65519.0), 0x7BFFu);
  EXPECT_EQ(FromDouble(kFp16, 65520.0), 0x7C00u);  // tie rounds to even = 2^16: overflow
  EXPECT_EQ(FromDouble(kFp16, -1e9), 0xFC00u);
  EXPECT_EQ(FromDouble(kFp16, 1.0 + std::ldexp(1.0, -11)), 0x3C00u);      // tie, down to even
  EXPECT_EQ(FromDouble(kFp16, 1.0 + 3 * std::ldexp(1.0, -11)), 0x3C02u);  // tie, up to even
  EXPECT_EQ(FromDouble(kFp16, 1.0 + std::ldexp(1.0, -11) + std::ldexp(1.0, -30)), 0x3C01u);
  EXPECT_EQ(FromFloat(kBf16, 1.00390625f), 0x3F80u);  // 1 + 2^-8: tie, to even
  EXPECT_EQ(FromF32Bits(kFp32, 0x3F800001u), 0x3F800001u);
  EXPECT_TRUE(std::isnan(ToDouble(kFp16, 0x7E00u)));
  EXPECT_EQ(BitsOf(ToFloat(kFp16, 0xFE01u)), 0x7FC00000u);  // any NaN -> canonical
  EXPECT_EQ(FromF32Bits(kFp16, 0xFF800001u), 0x7E00u);
  EXPECT_EQ(ToFloat(kFp16, 0x3555u), static_cast<float>(0x155 + 1024) / 4096.0f);
  EXPECT_EQ(ToDouble(kFp24, FromDouble(kFp24, 3.0)), 3.0);
}

TEST(FpFormat, FlushesSubnormalsWithTininessAfterRounding) {
  const double min_normal = std::ldexp(1.0, -14);
  EXPECT_EQ(FromDouble(kFp16, min_normal), 0x0400u);
  EXPECT_EQ(FromDouble(kFp16, -min_normal / 2), 0x8000u);
  // Rounds up to the smallest normal with M+1 bits: not tiny after rounding.
  EXPECT_EQ(FromDouble(kFp16, min_normal * (1 - std::ldexp(1.0, -12))), 0x0400u);
  // Exactly representable just below the smallest normal: tiny, flushed.
  EXPECT_EQ(FromDouble(kFp16, min_normal * (1 - std::ldexp(1.0, -11))), 0x0000u);
  // DAZ: subnormal fp32 and fp16 inputs are zeros of the same sign.
  EXPECT_EQ(FromF32Bits(kFp32, 0x80000001u), 0x80000000u);
  EXPECT_EQ(FromF32Bits(kFp16, 0x007FFFFFu), 0x0000u);
  EXPECT_EQ(ToDouble(kFp16, 0x83FFu), 0.0);
  EXPECT_TRUE(std::signbit(ToDouble(kFp16, 0x83FFu)));
  EXPECT_EQ(Add(kFp16, 0x0001u, 0x0001u), 0x0000u);
  EXPECT_EQ(Mul(kFp16, 0x03FFu, 0x7BFFu), 0x0000u);
  EXPECT_EQ(Div(kFp16, 0x3C00u, 0x8001u), 0xFC00u);  // 1 / -subnormal = 1 / -0
  EXPECT_TRUE(IsZero(kFp16, 0x0200u));
  // A difference of two normals that would be subnormal is flushed.
  EXPECT_EQ(Sub(kFp16, 0x0401u, 0x0400u), 0x0000u);
  EXPECT_EQ(Sub(kFp16, 0x0400u, 0x0401u), 0x8000u);
}

TEST(FpFormat, InfinitiesNaNsAndSignedZeros) {
  const Format f = kFp16;
  const uint32_t nan = f.CanonicalNaN(), inf = f.Inf(), ninf = f.Inf(true);
  const uint32_t one = 0x3C00, two = 0x4000, zero = 0x0000, nzero = 0x8000;
  EXPECT_EQ(Add(f, inf, ninf), nan);
  EXPECT_EQ(Sub(f, inf, inf), nan);
  EXPECT_EQ(Add(f, inf, inf), inf);
  EXPECT_EQ(Add(f, ninf, one), ninf);
  EXPECT_EQ(Mul(f, zero, inf), nan);
  EXPECT_EQ(Mul(f, nzero, two), nzero);
  EXPECT_EQ(Div(f, one, zero), inf);
  EXPECT_EQ(Div(f, one, nzero), ninf);
  EXPECT_EQ(Div(f, zero, zero), nan);
  EXPECT_EQ(Div(f, inf, ninf), nan);
  EXPECT_EQ(Div(f, one, inf), zero);
  EXPECT_EQ(Div(f, 0xBC00, inf), nzero);
  EXPECT_EQ(Add(f, nzero, nzero), nzero);
  EXPECT_EQ(Add(f, zero, nzero), zero);
  EXPECT_EQ(Sub(f, one, one), zero);
  EXPECT_EQ(Sub(f, nzero, zero), nzero);
  EXPECT_EQ(Add(f, 0xFE01, one), nan);  // NaN payload/sign not propagated
  EXPECT_EQ(Mul(f, 0x7BFF, two), inf);  // overflow
  EXPECT_EQ(Mul(f, 0x7BFF, 0xC000), ninf);
  EXPECT_EQ(Div(f, 0x3C00, 0x4200), 0x3555u);  // 1/3 rounds down
  EXPECT_EQ(Div(f, 0x4000, 0x4200), 0x3955u);  // 2/3
  EXPECT_EQ(Min(f, zero, nzero), nzero);
  EXPECT_EQ(Min(f, nzero, zero), nzero);
  EXPECT_EQ(Max(f, nzero, zero), zero);
  EXPECT_EQ(Max(f, zero, nzero), zero);
  EXPECT_EQ(Min(f, one, nan), nan);
  EXPECT_EQ(Max(f, 0xFE01, one), nan);
  EXPECT_EQ(Min(f, one, two), one);
  EXPECT_EQ(Max(f, ninf, two), two);
  EXPECT_EQ(Min(f, 0x0001, one), zero);  // a subnormal comes out flushed
  EXPECT_FALSE(Lt(f, nan, one));
  EXPECT_FALSE(Le(f, nan, nan));
  EXPECT_FALSE(Eq(f, nan, nan));
  EXPECT_TRUE(Eq(f, zero, nzero));
  EXPECT_TRUE(Le(f, nzero, zero));
  EXPECT_FALSE(Lt(f, nzero, zero));
  EXPECT_TRUE(Lt(f, ninf, 0xFBFF));
  EXPECT_TRUE(Eq(f, 0x0001, nzero));  // DAZ
  EXPECT_EQ(Neg(f, one), 0xBC00u);
  EXPECT_EQ(Neg(f, 0xFE01), nan);
  EXPECT_EQ(Neg(f, zero), nzero);
  EXPECT_EQ(Abs(f, 0xBC00), one);
  EXPECT_EQ(Abs(f, 0xFFFF), nan);
  EXPECT_TRUE(IsNaN(f, 0xFFFF));
  EXPECT_TRUE(IsInf(f, ninf));
  EXPECT_TRUE(SignBit(f, nzero));
}

TEST(FpFormat, SoftArithPolicy) {
  const SoftArith s(kBf16);
  EXPECT_EQ(s.Load(1.0f), 0x3F80u);
  EXPECT_EQ(s.Store(s.Load(-3.5f)), -3.5f);
  EXPECT_EQ(s.One(), 0x3F80u);
  EXPECT_EQ(s.Inf(), 0x7F80u);
  EXPECT_EQ(s.Zero(), 0u);
  EXPECT_EQ(s.Add(s.One(), s.One()), 0x4000u);
  EXPECT_EQ(s.Div(s.One(), s.Zero()), s.Inf());
  EXPECT_TRUE(s.IsNeg(s.Neg(s.One())));
  EXPECT_TRUE(s.IsZero(s.Sub(s.One(), s.One())));
  EXPECT_TRUE(s.Lt(s.Zero(), s.One()));
  EXPECT_EQ(s.Load(1e-40f), 0u);  // DAZ on load
}

}  // namespace
}  // namespace kdrt::fp
