// The fp32 fast path: native float with FTZ|DAZ must be bit-identical to the
// generic model for fp32 (which confirms x86 flushes with tininess after
// rounding), and NativeF32Arith must match SoftArith(kFp32).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "fp/format.h"
#include "fp/ftz.h"
#include "tests/fp/fp_vectors.h"

namespace kdrt::fp {
namespace {

using test::Hex;

// Equal bits, or both NaN (native NaNs keep payloads and x86's default NaN is
// negative; the model's are canonical).
bool Same(uint32_t native_bits, uint32_t model_bits) {
  const bool native_nan = (native_bits & 0x7FFFFFFFu) > 0x7F800000u;
  if (native_nan || IsNaN(kFp32, model_bits)) {
    return native_nan && model_bits == kFp32.CanonicalNaN();
  }
  return native_bits == model_bits;
}

// Native float on fp32 operands that have been loaded (so never subnormal,
// matching what the tracer feeds it).
TEST(FpNative, ArithmeticMatchesModel) {
  ScopedFtzDaz ftz;
  using N = NativeF32Arith;
  const SoftArith soft(kFp32);
  const std::vector<uint32_t> corners = test::CornerValues(kFp32);
  test::Rng rng(7);
  const uint64_t n = test::RandomPairCount();
  int failures = 0;
  for (uint64_t i = 0; i < n && failures < 5; ++i) {
    const auto [ra, rb] = test::RandomPair(kFp32, rng, corners);
    const float fa = N::Load(FloatOf(ra)), fb = N::Load(FloatOf(rb));
    const uint32_t a = soft.Load(FloatOf(ra)), b = soft.Load(FloatOf(rb));
    ASSERT_TRUE(Same(BitsOf(fa), a)) << "Load(" << Hex(ra) << ")";
    const struct {
      const char* name;
      float native;
      uint32_t model;
    } results[] = {
        {"add", N::Add(fa, fb), soft.Add(a, b)},
        {"sub", N::Sub(fa, fb), soft.Sub(a, b)},
        {"mul", N::Mul(fa, fb), soft.Mul(a, b)},
        {"div", N::Div(fa, fb), soft.Div(a, b)},
        {"min", N::Min(fa, fb), soft.Min(a, b)},
        {"max", N::Max(fa, fb), soft.Max(a, b)},
        {"neg", N::Neg(fa), soft.Neg(a)},
        {"abs", N::Abs(fa), soft.Abs(a)},
        // The same raw operations without the policy class, as the generic
        // free functions see them (the raw operand bits, DAZ inside).
        {"raw add", FloatOf(ra) + FloatOf(rb), Add(kFp32, ra, rb)},
        {"raw mul", FloatOf(ra) * FloatOf(rb), Mul(kFp32, ra, rb)},
        {"raw div", FloatOf(ra) / FloatOf(rb), Div(kFp32, ra, rb)},
    };
    for (const auto& r : results) {
      if (!Same(BitsOf(r.native), r.model)) {
        ADD_FAILURE() << r.name << "(" << Hex(ra) << ", " << Hex(rb) << "): native "
                      << Hex(BitsOf(r.native)) << ", model " << Hex(r.model);
        ++failures;
      }
    }
    if (N::Lt(fa, fb) != soft.Lt(a, b) || N::Le(fa, fb) != soft.Le(a, b) ||
        N::Eq(fa, fb) != soft.Eq(a, b) || N::IsZero(fa) != soft.IsZero(a) ||
        (!std::isnan(fa) && N::IsNeg(fa) != soft.IsNeg(a)) ||
        !Same(BitsOf(N::Store(fa)), BitsOf(soft.Store(a)))) {
      ADD_FAILURE() << "predicates or store differ on (" << Hex(ra) << ", " << Hex(rb) << ")";
      ++failures;
    }
  }
}

TEST(FpNative, Constants) {
  const SoftArith soft(kFp32);
  EXPECT_EQ(BitsOf(NativeF32Arith::Zero()), soft.Zero());
  EXPECT_EQ(BitsOf(NativeF32Arith::One()), soft.One());
  EXPECT_EQ(BitsOf(NativeF32Arith::Inf()), soft.Inf());
}

// The guard really changes and restores the control register: a subnormal
// product is kept without it and flushed with it.
TEST(FpNative, GuardSetsAndRestoresFtz) {
  volatile float tiny = 1e-30f;
  volatile float scale = 1e-10f;
  EXPECT_NE(tiny * scale, 0.0f);
  {
    ScopedFtzDaz ftz;
    EXPECT_EQ(tiny * scale, 0.0f);
    volatile float sub = 1e-40f;
    EXPECT_EQ(sub + 0.0f, 0.0f);  // DAZ
  }
  EXPECT_NE(tiny * scale, 0.0f);
}

}  // namespace
}  // namespace kdrt::fp
