// Operand generators shared by the model tests (tests/fp) and the Verilator
// benches (tests/rtl), so both see the same kinds of vectors.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fp/format.h"

namespace kdrt::fp::test {

// splitmix64: small, fast, and the same sequence on every platform.
class Rng {
 public:
  explicit Rng(uint64_t seed) : s_(seed) {}
  uint64_t Next() {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  uint32_t Below(uint32_t n) { return static_cast<uint32_t>(Next() % n); }

 private:
  uint64_t s_;
};

inline bool LongRun() {
  const char* v = std::getenv("KDRT_LONG");
  return v != nullptr && std::string(v) == "1";
}

// Random operand pairs per preset and operation: 1e6 by default, 1e7 with
// KDRT_LONG=1.
inline uint64_t RandomPairCount() { return LongRun() ? 10000000ull : 1000000ull; }

inline std::string Hex(uint32_t x) {
  std::ostringstream s;
  s << "0x" << std::hex << x;
  return s.str();
}

inline uint32_t Pack(Format f, bool neg, uint32_t exp, uint32_t mant) {
  return (neg ? f.SignMask() : 0u) | (exp << f.m) | (mant & f.MantMask());
}

// Values every operation should meet: signed zeros, subnormals, the smallest
// and largest normals, infinities, NaNs (canonical and not), numbers around 1
// and values one ulp either side of a binade boundary.
inline std::vector<uint32_t> CornerValues(Format f) {
  const uint32_t emax = f.ExpAllOnes() - 1;
  const uint32_t bias = static_cast<uint32_t>(f.Bias());
  const uint32_t all = f.MantMask();
  // Exponent of ulp(1)/2, clamped for formats too narrow to hold it.
  const uint32_t half_ulp_exp = bias > static_cast<uint32_t>(f.m) + 1 ? bias - f.m - 1 : 1;
  std::vector<uint32_t> mags = {
      Pack(f, false, 0, 0),                 // zero
      Pack(f, false, 0, 1),                 // smallest subnormal
      Pack(f, false, 0, all),               // largest subnormal
      Pack(f, false, 1, 0),                 // smallest normal
      Pack(f, false, 1, 1),                 //
      Pack(f, false, 1, all),               // largest in the smallest binade
      Pack(f, false, 2, 0),                 //
      Pack(f, false, emax, all),            // largest finite
      Pack(f, false, emax, all - 1),        //
      Pack(f, false, emax, 0),              //
      Pack(f, false, emax - 1, all),        //
      Pack(f, false, bias, 0),              // 1
      Pack(f, false, bias, 1),              // 1 + ulp
      Pack(f, false, bias - 1, all),        // 1 - ulp/2
      Pack(f, false, bias, 1u << (f.m - 1)),  // 1.5
      Pack(f, false, bias + 1, 0),          // 2
      Pack(f, false, bias - 1, 0),          // 0.5
      Pack(f, false, bias + 1, all),        //
      Pack(f, false, half_ulp_exp, 0),      // ulp(1)/2: ties when added to 1
      Pack(f, false, half_ulp_exp, 1),
      Pack(f, false, f.ExpAllOnes(), 0),    // inf
      f.CanonicalNaN(),                     // canonical NaN
      Pack(f, false, f.ExpAllOnes(), 1),    // another NaN
  };
  std::vector<uint32_t> out;
  for (uint32_t v : mags) {
    out.push_back(v);
    out.push_back(v | f.SignMask());
  }
  return out;
}

// A random operand: mostly uniform encodings (which cover every class in
// proportion), sometimes a corner value.
inline uint32_t RandomOperand(Format f, Rng& rng, const std::vector<uint32_t>& corners) {
  const uint32_t r = rng.Below(16);
  if (r == 0) return corners[rng.Below(static_cast<uint32_t>(corners.size()))];
  return static_cast<uint32_t>(rng.Next()) & f.WidthMask();
}

// Pairs biased towards the interesting cases: independent operands, operands
// of nearby exponents (alignment, cancellation, rounding carries) and nearly
// equal operands (massive cancellation, exact zero sums).
inline std::pair<uint32_t, uint32_t> RandomPair(Format f, Rng& rng,
                                                const std::vector<uint32_t>& corners) {
  const uint32_t a = RandomOperand(f, rng, corners);
  uint32_t b;
  switch (rng.Below(4)) {
    case 0:
    case 1:
      b = RandomOperand(f, rng, corners);
      break;
    case 2: {  // exponent within +-(M+3) of a's
      const int ea = static_cast<int>((a & f.ExpMask()) >> f.m);
      int eb = ea + static_cast<int>(rng.Below(2 * f.m + 7)) - (f.m + 3);
      if (eb < 0) eb = 0;
      if (eb > static_cast<int>(f.ExpAllOnes())) eb = static_cast<int>(f.ExpAllOnes());
      b = (static_cast<uint32_t>(rng.Next()) & (f.SignMask() | f.MantMask())) |
          (static_cast<uint32_t>(eb) << f.m);
      break;
    }
    default: {  // a few ulps from a, either sign
      const uint32_t delta = rng.Below(9);
      b = (rng.Below(2) ? a + delta : a - delta) & f.WidthMask();
      if (rng.Below(2)) b ^= f.SignMask();
      break;
    }
  }
  if (rng.Below(2)) return {b, a};
  return {a, b};
}

}  // namespace kdrt::fp::test
