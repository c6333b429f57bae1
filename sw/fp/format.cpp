// The generic path: decode both operands exactly to double, compute there and
// round once to (E, M).
//
// Why that is exact: for +, -, * and / of p-bit operands, computing the result
// in a binary format with at least 2p+2 significand bits and then rounding it
// to p bits gives the correctly rounded p-bit result (Figueroa, "When is
// double rounding innocuous?", SIGNUM 1995). Here p = M+1 <= 24 and double has
// 53 >= 2*24+2 = 50 bits. Double's exponent range also covers every sum,
// product and quotient of operands with E <= 8 (magnitudes between 2^-254 and
// 2^256), so the double result never overflows or becomes subnormal, and our
// own rounding uses an unbounded exponent range before the FTZ/overflow rule,
// exactly as the policy in format.h says.
#include "fp/format.h"

#include <cstdio>

#include "common/error.h"
#include "fp/presets.h"  // generated from cmake/presets.cmake

namespace kdrt::fp {

std::string Format::Name() const {
  if (IsFp64()) return "fp64";
#define KDRT_PRESET_NAME(name, pe, pm) \
  if (e == pe && m == pm) return #name;
  KDRT_PRESET_LIST(KDRT_PRESET_NAME)
#undef KDRT_PRESET_NAME
  return "e" + std::to_string(e) + "m" + std::to_string(m);
}

Format MakeFormat(int e, int m) {
  if (Format{e, m}.IsFp64()) {
    throw InputError("number format fp64 has no soft-float model: it is computed natively in double");
  }
  if (e < 2 || e > 8 || m < 1 || m > 23) {
    throw InputError("number format e" + std::to_string(e) + "m" + std::to_string(m) +
                     ": need 2 <= exponent bits <= 8 and 1 <= mantissa bits <= 23 (or fp64)");
  }
  return Format{e, m};
}

Format ParseFormat(const std::string& name) {
  for (const Format& f : Presets()) {
    if (name == f.Name()) return f;
  }
  if (name == "fp64") return kFp64;
  int e = 0, m = 0, consumed = 0;
  if (std::sscanf(name.c_str(), "e%dm%d%n", &e, &m, &consumed) == 2 &&
      consumed == static_cast<int>(name.size()) && name.find_first_of("+- ") == std::string::npos) {
    if (Format{e, m}.IsFp64()) return kFp64;
    return MakeFormat(e, m);
  }
  throw InputError("unknown number format '" + name + "': expected " + PresetNames() +
                   ", eXmY (e.g. e4m3) or fp64");
}

std::string PresetNames() {
  std::string names;
  for (const Format& f : Presets()) names += (names.empty() ? "" : ", ") + f.Name();
  return names;
}

std::vector<Format> Presets() {
#define KDRT_PRESET_FORMAT(name, e, m) Format{e, m},
  return {KDRT_PRESET_LIST(KDRT_PRESET_FORMAT)};
#undef KDRT_PRESET_FORMAT
}

double ToDouble(Format f, uint32_t x) {
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
    mag = std::ldexp(static_cast<double>((1u << f.m) | mant),
                     static_cast<int>(exp) - f.Bias() - f.m);
  }
  return neg ? -mag : mag;
}

uint32_t FromDouble(Format f, double x) {
  uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const bool neg = (bits >> 63) != 0;
  const int dexp = static_cast<int>((bits >> 52) & 0x7FF);
  const uint64_t frac = bits & ((uint64_t{1} << 52) - 1);
  if (dexp == 0x7FF) return frac != 0 ? f.CanonicalNaN() : f.Inf(neg);
  // A subnormal double is far below the smallest normal of any format here.
  if (dexp == 0) return f.Zero(neg);

  // Round the 53-bit significand to M+1 bits, ties to even.
  const uint64_t sig = (uint64_t{1} << 52) | frac;
  const int shift = 52 - f.m;
  uint64_t kept = sig >> shift;
  const uint64_t rest = sig & ((uint64_t{1} << shift) - 1);
  const uint64_t half = uint64_t{1} << (shift - 1);
  if (rest > half || (rest == half && (kept & 1) != 0)) ++kept;
  int exp = dexp - 1023;
  if ((kept >> (f.m + 1)) != 0) {  // rounding carried into a new bit
    kept >>= 1;
    ++exp;
  }
  const int biased = exp + f.Bias();
  if (biased <= 0) return f.Zero(neg);                                    // FTZ
  if (biased >= static_cast<int>(f.ExpAllOnes())) return f.Inf(neg);  // overflow
  return f.Zero(neg) | (static_cast<uint32_t>(biased) << f.m) |
         (static_cast<uint32_t>(kept) & f.MantMask());
}

uint32_t FromF32Bits(Format f, uint32_t bits) {
  if ((bits & 0x7F800000u) == 0) return f.Zero((bits >> 31) != 0);  // DAZ
  return FromDouble(f, static_cast<double>(FloatOf(bits)));
}

uint32_t FromFloat(Format f, float x) { return FromF32Bits(f, BitsOf(x)); }

float ToFloat(Format f, uint32_t x) {
  if (IsNaN(f, x)) return FloatOf(0x7FC00000u);
  return static_cast<float>(ToDouble(f, x));  // exact: E <= 8, M <= 23
}

uint32_t Add(Format f, uint32_t a, uint32_t b) {
  return FromDouble(f, ToDouble(f, a) + ToDouble(f, b));
}
uint32_t Sub(Format f, uint32_t a, uint32_t b) {
  return FromDouble(f, ToDouble(f, a) - ToDouble(f, b));
}
uint32_t Mul(Format f, uint32_t a, uint32_t b) {
  return FromDouble(f, ToDouble(f, a) * ToDouble(f, b));
}
uint32_t Div(Format f, uint32_t a, uint32_t b) {
  return FromDouble(f, ToDouble(f, a) / ToDouble(f, b));
}

namespace {
// The operand as the arithmetic sees it: in range, subnormals flushed.
uint32_t Canonical(Format f, uint32_t x) {
  x &= f.WidthMask();
  return IsZero(f, x) ? (x & f.SignMask()) : x;
}
}  // namespace

uint32_t Min(Format f, uint32_t a, uint32_t b) {
  if (IsNaN(f, a) || IsNaN(f, b)) return f.CanonicalNaN();
  const double da = ToDouble(f, a), db = ToDouble(f, b);
  if (da < db) return Canonical(f, a);
  if (db < da) return Canonical(f, b);
  // Equal: the same bits, or zeros of either sign (min takes -0 if any).
  return Canonical(f, a) | Canonical(f, b);
}

uint32_t Max(Format f, uint32_t a, uint32_t b) {
  if (IsNaN(f, a) || IsNaN(f, b)) return f.CanonicalNaN();
  const double da = ToDouble(f, a), db = ToDouble(f, b);
  if (da > db) return Canonical(f, a);
  if (db > da) return Canonical(f, b);
  return Canonical(f, a) & Canonical(f, b);
}

uint32_t Neg(Format f, uint32_t x) {
  x &= f.WidthMask();
  return IsNaN(f, x) ? f.CanonicalNaN() : x ^ f.SignMask();
}

uint32_t Abs(Format f, uint32_t x) {
  x &= f.WidthMask();
  return IsNaN(f, x) ? f.CanonicalNaN() : x & ~f.SignMask();
}

namespace {
bool IsPositiveFinite(Format f, uint32_t x) {
  return !SignBit(f, x) && !IsZero(f, x) && (x & f.ExpMask()) != f.ExpMask();
}
}  // namespace

uint32_t NudgeUp(Format f, uint32_t x, uint32_t k) {
  x &= f.WidthMask();
  if (IsNaN(f, x)) return f.CanonicalNaN();
  if (!IsPositiveFinite(f, x)) return x;
  // The encodings of positive values are ordered like the values.
  return x + k >= f.Inf() ? f.Inf() : x + k;
}

uint32_t NudgeDown(Format f, uint32_t x, uint32_t k) {
  x &= f.WidthMask();
  if (IsNaN(f, x)) return f.CanonicalNaN();
  if (!IsPositiveFinite(f, x)) return x;
  const uint32_t min_normal = 1u << f.m;
  return x < min_normal + k ? 0u : x - k;
}

uint32_t Ldexp(Format f, uint32_t x, int n) {
  // Exact in double (|n| is bounded by the callers' exponent fields), then
  // rounded once under the policy: only FTZ or overflow can change it.
  return FromDouble(f, std::ldexp(ToDouble(f, x), n));
}

bool Lt(Format f, uint32_t a, uint32_t b) { return ToDouble(f, a) < ToDouble(f, b); }
bool Le(Format f, uint32_t a, uint32_t b) { return ToDouble(f, a) <= ToDouble(f, b); }
bool Eq(Format f, uint32_t a, uint32_t b) { return ToDouble(f, a) == ToDouble(f, b); }

}  // namespace kdrt::fp
