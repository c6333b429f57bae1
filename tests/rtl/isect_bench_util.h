// Helpers shared by the Verilator benches of rt_ray_setup and rt_isect_unit:
// packing values into verilated ports of any width, random streams with
// bubbles and backpressure, and printing rays and triangles.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <type_traits>

#include <verilated.h>

#include "common/image_format.h"
#include "common/ray.h"
#include "fp/format.h"

namespace kdrt::rtlbench {

inline bool LongRun() {
  const char* v = std::getenv("KDRT_LONG");
  return v != nullptr && std::string(v) == "1";
}

// Packed ports: Verilator maps up to 64 bits to an integer, wider ones to
// VlWide<N> (32-bit words, least significant first).
template <class P>
std::enable_if_t<std::is_integral_v<P>> PutBits(P& port, int lsb, int width, uint64_t value) {
  const uint64_t mask = (width >= 64 ? ~uint64_t{0} : (uint64_t{1} << width) - 1) << lsb;
  const uint64_t cur = static_cast<uint64_t>(port);
  port = static_cast<P>((cur & ~mask) | ((value << lsb) & mask));
}
template <std::size_t N>
void PutBits(VlWide<N>& port, int lsb, int width, uint64_t value) {
  for (int i = 0; i < width; ++i) {
    const int b = lsb + i;
    const uint32_t bit = 1u << (b % 32);
    if ((value >> i) & 1) {
      port.m_storage[b / 32] |= bit;
    } else {
      port.m_storage[b / 32] &= ~bit;
    }
  }
}
template <class P>
std::enable_if_t<std::is_integral_v<P>, uint64_t> GetBits(const P& port, int lsb, int width) {
  const uint64_t v = static_cast<uint64_t>(port) >> lsb;
  return width >= 64 ? v : v & ((uint64_t{1} << width) - 1);
}
template <std::size_t N>
uint64_t GetBits(const VlWide<N>& port, int lsb, int width) {
  uint64_t v = 0;
  for (int i = 0; i < width; ++i) {
    const int b = lsb + i;
    v |= static_cast<uint64_t>((port.m_storage[b / 32] >> (b % 32)) & 1u) << i;
  }
  return v;
}

inline std::string Hex(uint32_t x) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%08x", x);
  return buf;
}

inline std::string F32(float x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g (%s)", x, Hex(fp::BitsOf(x)).c_str());
  return buf;
}

inline std::string Fmt(fp::Format f, uint32_t x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g (%s)", fp::ToDouble(f, x), Hex(x).c_str());
  return buf;
}

inline std::string RayString(const Ray& r) {
  std::string s = "ray o = (";
  for (int i = 0; i < 3; ++i) s += (i ? ", " : "") + F32(r.o[i]);
  s += ")\n    d = (";
  for (int i = 0; i < 3; ++i) s += (i ? ", " : "") + F32(r.d[i]);
  s += ")\n    tmin = " + F32(r.tmin) + ", tmax = " + F32(r.tmax);
  return s;
}

inline std::string TriangleString(const img::TriangleRecord& t) {
  std::string s = "triangle";
  const float* v[3] = {t.v0, t.v1, t.v2};
  for (int k = 0; k < 3; ++k) {
    s += "\n    v" + std::to_string(k) + " = (";
    for (int i = 0; i < 3; ++i) s += (i ? ", " : "") + F32(v[k][i]);
    s += ")";
  }
  return s;
}

// Random numbers for the stimulus (mt19937_64's raw stream is portable).
class Rng {
 public:
  explicit Rng(uint64_t seed) : gen_(seed) {}
  double Unit() { return static_cast<double>(gen_() >> 11) * (1.0 / 9007199254740992.0); }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Unit(); }
  bool Chance(double p) { return Unit() < p; }
  uint32_t Below(uint32_t n) { return static_cast<uint32_t>(gen_() % n); }
  uint32_t Bits32() { return static_cast<uint32_t>(gen_() >> 32); }
  double LogUniform(double lo, double hi) { return std::exp(Uniform(std::log(lo), std::log(hi))); }
  double Gauss() {
    // Box-Muller on our own uniforms: portable, unlike std::normal_distribution.
    const double u1 = 1.0 - Unit(), u2 = Unit();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::mt19937_64 gen_;
};

// fp32 values a memory image never holds (the loaders reject them) and
// values at the edges of the formats; the units must still match the model.
inline float SpecialF32(Rng& rng) {
  static const uint32_t kBits[] = {
      0x7FC00000u, 0xFFC00000u, 0x7F800001u, 0x7F800000u, 0xFF800000u, 0x00000000u,
      0x80000000u, 0x00000001u, 0x807FFFFFu, 0x00800000u, 0x7F7FFFFFu, 0xFF7FFFFFu,
      0x7149F2CAu /* 1e30 */, 0x0DA24260u /* 1e-30 */, 0x477FE000u /* 65504 */, 0x38800000u /* 2^-14 */};
  return fp::FloatOf(kBits[rng.Below(sizeof kBits / sizeof kBits[0])]);
}

}  // namespace kdrt::rtlbench
