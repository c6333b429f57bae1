// The soft formats' out-of-line functions; the arithmetic itself is inline
// in format.h.
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

}  // namespace kdrt::fp
