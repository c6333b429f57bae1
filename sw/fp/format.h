// Bit-accurate parameterised floating-point formats (E exponent bits, M
// mantissa bits): the arithmetic shared by the reference tracer and the RTL
// (rtl/fp_*.sv). The RTL is checked bit for bit against these functions.
//
// Encoding: right-aligned in a uint32_t, bit E+M = sign, bits [E+M-1:M] =
// biased exponent (bias 2^(E-1)-1), bits [M-1:0] = mantissa. Bits above E+M
// are ignored on input and zero on output.
//
// Policy (see docs/number-formats.md):
//  - round to nearest, ties to even;
//  - DAZ: a subnormal operand is a zero of the same sign;
//  - FTZ: a result whose magnitude, rounded to M+1 significant bits with an
//    unbounded exponent range, is below the smallest normal is a signed zero
//    (x86 SSE with FTZ|DAZ: tininess after rounding);
//  - overflow after rounding gives an infinity;
//  - every NaN result is the canonical quiet NaN (sign 0, exponent all ones,
//    mantissa MSB 1, other bits 0);
//  - exact zero sums are +0 except (-0) + (-0) = -0;
//  - Min/Max: NaN if either operand is NaN; Min(-0,+0) = -0, Max(-0,+0) = +0.
//
// All free functions assume the caller's floating-point rounding mode is the
// default round-to-nearest (they use double arithmetic internally); they work
// with or without ScopedFtzDaz held, because no double they compute is
// subnormal.
#pragma once

#include <cstdint>
#include <cstring>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

// The soft arithmetic below is forced inline: GCC left FromDouble out of
// line in the triangle test, a call per operation.
#if defined(__GNUC__)
#define KDRT_FP_INLINE inline __attribute__((always_inline))
#else
#define KDRT_FP_INLINE inline
#endif

namespace kdrt::fp {

// A soft format has 2 <= e <= 8 and 1 <= m <= 23; everything below (the
// encoding helpers, the free arithmetic functions, SoftArith) holds only for
// those. The one exception is kFp64 (e = 11, m = 52): IEEE binary64, computed
// natively by NativeF64Arith as the accuracy reference; it has no encoding in
// a uint32_t, no soft-float model and no RTL. Code that takes a Format from
// the user must either route fp64 to NativeF64Arith or refuse it (IsFp64).
struct Format {
  int e = 8;   // exponent bits, 2..8 (11 for fp64)
  int m = 23;  // mantissa bits (without the hidden bit), 1..23 (52 for fp64)

  bool IsFp32() const { return e == 8 && m == 23; }
  bool IsFp64() const { return e == 11 && m == 52; }

  int Width() const { return 1 + e + m; }
  int Bias() const { return (1 << (e - 1)) - 1; }
  uint32_t ExpAllOnes() const { return (1u << e) - 1; }
  uint32_t SignMask() const { return 1u << (e + m); }
  uint32_t ExpMask() const { return ExpAllOnes() << m; }
  uint32_t MantMask() const { return (1u << m) - 1; }
  uint32_t WidthMask() const { return (SignMask() << 1) - 1; }
  uint32_t CanonicalNaN() const { return ExpMask() | (1u << (m - 1)); }
  uint32_t Inf(bool negative = false) const { return (negative ? SignMask() : 0u) | ExpMask(); }
  uint32_t Zero(bool negative = false) const { return negative ? SignMask() : 0u; }
  uint32_t One() const { return static_cast<uint32_t>(Bias()) << m; }
  // "fp32", "fp24", "bf16", "fp16" for the presets, "eXmY" otherwise.
  std::string Name() const;

  bool operator==(const Format& o) const { return e == o.e && m == o.m; }
  bool operator!=(const Format& o) const { return !(*this == o); }
};

// Named presets for code and tests; the preset list itself (Presets(), the
// names Name() gives) is cmake/presets.cmake.
inline constexpr Format kFp32{8, 23};
inline constexpr Format kFp24{7, 16};
inline constexpr Format kBf16{8, 7};
inline constexpr Format kFp16{5, 10};
// Not a preset (no RTL model, not in Presets()): the double-precision truth.
inline constexpr Format kFp64{11, 52};

// Throws kdrt::InputError unless 2 <= e <= 8 and 1 <= m <= 23 (so also for
// fp64: it is not a soft format). The arithmetic functions below do not check
// (they are the hot path): build every soft Format through MakeFormat.
Format MakeFormat(int e, int m);
// "fp32", "fp24", "bf16", "fp16", "eXmY" (e.g. "e4m3"), or "fp64" (kFp64,
// also "e11m52"); throws InputError. Callers get kFp64 only from here.
Format ParseFormat(const std::string& name);
std::vector<Format> Presets();
// "fp32, fp24, bf16, fp16": the preset names, for help texts and messages.
std::string PresetNames();

// Classification (a subnormal encoding counts as a zero: DAZ).
inline bool IsNaN(Format f, uint32_t x) {
  return (x & f.ExpMask()) == f.ExpMask() && (x & f.MantMask()) != 0;
}
inline bool IsInf(Format f, uint32_t x) {
  return (x & f.ExpMask()) == f.ExpMask() && (x & f.MantMask()) == 0;
}
inline bool IsZero(Format f, uint32_t x) { return (x & f.ExpMask()) == 0; }
inline bool SignBit(Format f, uint32_t x) { return (x & f.SignMask()) != 0; }

// Conversions. FromDouble/FromFloat/FromF32Bits round once (RNE, DAZ on the
// input, FTZ and overflow as above). ToFloat/ToDouble are exact; a NaN becomes
// 0x7FC00000 / the default quiet double NaN. The conversions, the
// arithmetic (Add, Sub, Mul, Div) and the comparisons (Lt, Le, Eq: IEEE,
// false when either operand is NaN, -0 == +0) are inline, further below.

// Correctly rounded under the policy above.
uint32_t Min(Format f, uint32_t a, uint32_t b);
uint32_t Max(Format f, uint32_t a, uint32_t b);
// Sign flips never flush a subnormal (they are bit operations, like the
// hardware's); a NaN operand gives the canonical NaN.
uint32_t Neg(Format f, uint32_t x);
uint32_t Abs(Format f, uint32_t x);
// Steps of k encodings, for conservative interval ends (the traversal widens
// its cells with them; rtl/fp_nudge.sv). Only positive finite non-zero
// values move: NudgeUp saturates at +inf, NudgeDown gives +0 where it would
// leave the normal range. Zeros, negatives, infinities and NaNs are returned
// as they are (a NaN as the canonical NaN). Exact integer steps on the
// encoding: no rounding involved.
uint32_t NudgeUp(Format f, uint32_t x, uint32_t k);
uint32_t NudgeDown(Format f, uint32_t x, uint32_t k);
// x * 2^n: exact, except that a result below the normal range is a signed
// zero (FTZ) and one above it an infinity; zeros, infinities stay, a NaN is
// the canonical NaN. (A subnormal x is a zero: DAZ.) rtl/fp_ldexp.sv.
// Inline, further below.
inline uint32_t BitsOf(float x) {
  uint32_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
inline float FloatOf(uint32_t u) {
  float x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}

// The arithmetic: decode both operands exactly to double, compute there and
// round once to (E, M). Inline: as calls into format.cpp these were most of a
// soft format's tracing time.
//
// Why that is exact: for +, -, * and / of p-bit operands, computing the result
// in a binary format with at least 2p+2 significand bits and then rounding it
// to p bits gives the correctly rounded p-bit result (Figueroa, "When is
// double rounding innocuous?", SIGNUM 1995). Here p = M+1 <= 24 and double has
// 53 >= 2*24+2 = 50 bits. Double's exponent range also covers every sum,
// product and quotient of operands with E <= 8 (magnitudes between 2^-254 and
// 2^256), so the double result never overflows or becomes subnormal, and our
// own rounding uses an unbounded exponent range before the FTZ/overflow rule,
// exactly as the policy above says.

KDRT_FP_INLINE double ToDouble(Format f, uint32_t x) {
  x &= f.WidthMask();
  const bool neg = SignBit(f, x);
  const uint32_t exp = (x & f.ExpMask()) >> f.m;
  const uint32_t mant = x & f.MantMask();
  double mag;
  if (exp == f.ExpAllOnes()) {
    if (mant != 0) return std::numeric_limits<double>::quiet_NaN();
    mag = std::numeric_limits<double>::infinity();
  } else if (exp == 0) {
    mag = 0.0;  // DAZ
  } else {
    // The double with the same value, built from its fields: every normal
    // value of an E <= 8 format is a normal double. (std::ldexp here was a
    // libm call per operand.)
    const uint64_t dexp = static_cast<uint64_t>(static_cast<int>(exp) - f.Bias() + 1023);
    const uint64_t bits = (uint64_t{neg} << 63) | (dexp << 52) | (uint64_t{mant} << (52 - f.m));
    double value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  return neg ? -mag : mag;
}

// Rounds a float's or a double's encoding at bit `shift` (clearing the bits
// below it), ties to even: adding half an ulp minus one plus the kept lowest
// bit and truncating rounds to nearest even, and a carry out of the fraction
// steps the exponent, as rounding up to a power of two does. Exact for
// normal numbers.
template <class U>
KDRT_FP_INLINE U RoundEncoding(U u, int shift) {
  u += (U{1} << (shift - 1)) - 1 + ((u >> shift) & 1u);
  return u & ~((U{1} << shift) - 1);
}

KDRT_FP_INLINE uint32_t FromDouble(Format f, double x) {
  uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const bool neg = (bits >> 63) != 0;
  uint64_t mag = bits & ~(uint64_t{1} << 63);
  if ((mag >> 52) == 0x7FF) return (mag << 12) != 0 ? f.CanonicalNaN() : f.Inf(neg);
  // A subnormal double is far below the smallest normal of any format here.
  if ((mag >> 52) == 0) return f.Zero(neg);

  // The fraction rounded to M bits on the encoding.
  const int shift = 52 - f.m;
  mag = RoundEncoding(mag, shift);
  const int biased = static_cast<int>(mag >> 52) - 1023 + f.Bias();
  if (biased <= 0) return f.Zero(neg);                                    // FTZ
  if (biased >= static_cast<int>(f.ExpAllOnes())) return f.Inf(neg);  // overflow
  return f.Zero(neg) | (static_cast<uint32_t>(biased) << f.m) |
         (static_cast<uint32_t>(mag >> shift) & f.MantMask());
}

KDRT_FP_INLINE uint32_t FromF32Bits(Format f, uint32_t bits) {
  if ((bits & 0x7F800000u) == 0) return f.Zero((bits >> 31) != 0);  // DAZ
  return FromDouble(f, static_cast<double>(FloatOf(bits)));
}

KDRT_FP_INLINE uint32_t FromFloat(Format f, float x) { return FromF32Bits(f, BitsOf(x)); }

KDRT_FP_INLINE float ToFloat(Format f, uint32_t x) {
  if (IsNaN(f, x)) return FloatOf(0x7FC00000u);
  return static_cast<float>(ToDouble(f, x));  // exact: E <= 8, M <= 23
}

KDRT_FP_INLINE uint32_t Add(Format f, uint32_t a, uint32_t b) {
  return FromDouble(f, ToDouble(f, a) + ToDouble(f, b));
}

KDRT_FP_INLINE uint32_t Sub(Format f, uint32_t a, uint32_t b) {
  return FromDouble(f, ToDouble(f, a) - ToDouble(f, b));
}

KDRT_FP_INLINE uint32_t Mul(Format f, uint32_t a, uint32_t b) {
  return FromDouble(f, ToDouble(f, a) * ToDouble(f, b));
}

KDRT_FP_INLINE uint32_t Div(Format f, uint32_t a, uint32_t b) {
  return FromDouble(f, ToDouble(f, a) / ToDouble(f, b));
}

KDRT_FP_INLINE bool Lt(Format f, uint32_t a, uint32_t b) { return ToDouble(f, a) < ToDouble(f, b); }
KDRT_FP_INLINE bool Le(Format f, uint32_t a, uint32_t b) { return ToDouble(f, a) <= ToDouble(f, b); }
KDRT_FP_INLINE bool Eq(Format f, uint32_t a, uint32_t b) { return ToDouble(f, a) == ToDouble(f, b); }

KDRT_FP_INLINE uint32_t Ldexp(Format f, uint32_t x, int n) {
  // Exact in double (a product with a power of two), then rounded once
  // under the policy: only FTZ or overflow can change it. An |n| beyond
  // double's normal range (no caller comes close) takes libm's ldexp.
  if (n < -1022 || n > 1023) return FromDouble(f, std::ldexp(ToDouble(f, x), n));
  const uint64_t scale_bits = static_cast<uint64_t>(n + 1023) << 52;
  double scale;
  std::memcpy(&scale, &scale_bits, sizeof scale);
  return FromDouble(f, ToDouble(f, x) * scale);
}

// Arithmetic policies: the tracer is templated on one of these; both have the
// same interface. NativeF32Arith and SoftArith(kFp32) give bit-identical
// results for every non-NaN result and both give a NaN when one does
// (checked by tests/fp/native_test.cpp). IsNeg of a NaN is unspecified for
// NativeF32Arith (x86's default NaN is negative); callers must not rely on it.

// The fast fp32 path: native float. The caller MUST hold ScopedFtzDaz
// (fp/ftz.h) on the calling thread, and every value must come from Load or
// from another method of this class (Load flushes subnormals; the arithmetic
// then never produces one).
struct NativeF32Arith {
  using T = float;

  static T Load(float fp32_from_memory) {
    // Done on the bits: the compiler would fold x * 1.0f away, and it does
    // not know that DAZ makes that multiply flush.
    uint32_t u = BitsOf(fp32_from_memory);
    uint32_t keep = (u & 0x7F800000u) == 0 ? 0x80000000u : 0xFFFFFFFFu;
    return FloatOf(u & keep);
  }
  static float Store(T x) { return x; }
  static T Add(T a, T b) { return a + b; }
  static T Sub(T a, T b) { return a - b; }
  static T Mul(T a, T b) { return a * b; }
  static T Div(T a, T b) { return a / b; }
  static T Min(T a, T b) {
    if (a < b) return a;
    if (b < a) return b;
    if (a == b) return FloatOf(BitsOf(a) | BitsOf(b));  // min(-0, +0) = -0
    return a + b;                                       // a NaN
  }
  static T Max(T a, T b) {
    if (a > b) return a;
    if (b > a) return b;
    if (a == b) return FloatOf(BitsOf(a) & BitsOf(b));  // max(-0, +0) = +0
    return a + b;
  }
  static T Neg(T x) { return -x; }
  static T Abs(T x) { return std::fabs(x); }
  static T NudgeUp(T x, uint32_t k) {
    if (!(x > 0.0f) || x == std::numeric_limits<float>::infinity()) return x;
    const uint32_t u = BitsOf(x) + k;
    return u >= 0x7F800000u ? std::numeric_limits<float>::infinity() : FloatOf(u);
  }
  static T NudgeDown(T x, uint32_t k) {
    if (!(x > 0.0f) || x == std::numeric_limits<float>::infinity()) return x;
    const uint32_t u = BitsOf(x);
    return u < 0x00800000u + k ? 0.0f : FloatOf(u - k);
  }
  static bool Lt(T a, T b) { return a < b; }
  static bool Le(T a, T b) { return a <= b; }
  static bool Eq(T a, T b) { return a == b; }
  static bool IsNeg(T x) { return std::signbit(x); }
  static bool IsZero(T x) { return x == 0.0f; }
  static T Zero() { return 0.0f; }
  static T Inf() { return std::numeric_limits<float>::infinity(); }
  static T One() { return 1.0f; }
};

// IEEE binary64, the accuracy reference (`kdrt render --format fp64`): the
// same traversal and tests in native double. The caller MUST hold
// ScopedIeeeDefault (fp/ftz.h): gradual underflow and round to nearest, so
// the results do not depend on the thread's MXCSR. Load widens fp32 exactly
// (a subnormal fp32 too: it is a normal double); Store rounds once to the
// fp32 hit record. The traversal slack is kTraversalSlackUlps encodings of
// double, the same rule as the other formats (NudgeUp/NudgeDown below).
struct NativeF64Arith {
  using T = double;

  static uint64_t Bits(T x) {
    uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
  }
  static T FromBits(uint64_t u) {
    T x;
    std::memcpy(&x, &u, sizeof x);
    return x;
  }

  static T Load(float fp32_from_memory) { return static_cast<T>(fp32_from_memory); }
  static float Store(T x) { return static_cast<float>(x); }
  static T Add(T a, T b) { return a + b; }
  static T Sub(T a, T b) { return a - b; }
  static T Mul(T a, T b) { return a * b; }
  static T Div(T a, T b) { return a / b; }
  static T Min(T a, T b) {
    if (a < b) return a;
    if (b < a) return b;
    if (a == b) return FromBits(Bits(a) | Bits(b));  // min(-0, +0) = -0
    return a + b;                                    // a NaN
  }
  static T Max(T a, T b) {
    if (a > b) return a;
    if (b > a) return b;
    if (a == b) return FromBits(Bits(a) & Bits(b));  // max(-0, +0) = +0
    return a + b;
  }
  static T Neg(T x) { return -x; }
  static T Abs(T x) { return std::fabs(x); }
  // As fp::NudgeUp/NudgeDown on double's encoding: +0 below the smallest
  // normal, +inf above the largest finite value.
  static T NudgeUp(T x, uint32_t k) {
    constexpr uint64_t kInfBits = 0x7FF0000000000000ull;
    if (!(x > 0.0) || x == std::numeric_limits<T>::infinity()) return x;
    const uint64_t u = Bits(x) + k;
    return u >= kInfBits ? std::numeric_limits<T>::infinity() : FromBits(u);
  }
  static T NudgeDown(T x, uint32_t k) {
    constexpr uint64_t kMinNormalBits = 0x0010000000000000ull;
    if (!(x > 0.0) || x == std::numeric_limits<T>::infinity()) return x;
    const uint64_t u = Bits(x);
    return u < kMinNormalBits + k ? 0.0 : FromBits(u - k);
  }
  static bool Lt(T a, T b) { return a < b; }
  static bool Le(T a, T b) { return a <= b; }
  static bool Eq(T a, T b) { return a == b; }
  static bool IsNeg(T x) { return std::signbit(x); }
  static bool IsZero(T x) { return x == 0.0; }
  static T Zero() { return 0.0; }
  static T Inf() { return std::numeric_limits<T>::infinity(); }
  static T One() { return 1.0; }
};

// Any soft (E, M) format, computed in software on the encodings. Throws
// InputError for fp64 (and anything else MakeFormat refuses).
class SoftArith {
 public:
  using T = uint32_t;

  explicit SoftArith(Format f) : f_(MakeFormat(f.e, f.m)) {}
  Format format() const { return f_; }

  T Load(float fp32_from_memory) const { return FromFloat(f_, fp32_from_memory); }
  float Store(T x) const { return ToFloat(f_, x); }
  T Add(T a, T b) const { return fp::Add(f_, a, b); }
  T Sub(T a, T b) const { return fp::Sub(f_, a, b); }
  T Mul(T a, T b) const { return fp::Mul(f_, a, b); }
  T Div(T a, T b) const { return fp::Div(f_, a, b); }
  T Min(T a, T b) const { return fp::Min(f_, a, b); }
  T Max(T a, T b) const { return fp::Max(f_, a, b); }
  T Neg(T x) const { return fp::Neg(f_, x); }
  T NudgeUp(T x, uint32_t k) const { return fp::NudgeUp(f_, x, k); }
  T NudgeDown(T x, uint32_t k) const { return fp::NudgeDown(f_, x, k); }
  T Abs(T x) const { return fp::Abs(f_, x); }
  bool Lt(T a, T b) const { return fp::Lt(f_, a, b); }
  bool Le(T a, T b) const { return fp::Le(f_, a, b); }
  bool Eq(T a, T b) const { return fp::Eq(f_, a, b); }
  bool IsNeg(T x) const { return fp::SignBit(f_, x); }
  bool IsZero(T x) const { return fp::IsZero(f_, x); }
  T Zero() const { return f_.Zero(); }
  T Inf() const { return f_.Inf(); }
  T One() const { return f_.One(); }

 private:
  Format f_;
};

}  // namespace kdrt::fp
