#include "trace/hit_compare.h"

#include <cinttypes>
#include <cstdio>

#include "fp/format.h"

namespace kdrt {

bool SameBits(const Hit& a, const Hit& b) {
  return a.prim == b.prim && fp::BitsOf(a.t) == fp::BitsOf(b.t) && fp::BitsOf(a.u) == fp::BitsOf(b.u) &&
         fp::BitsOf(a.v) == fp::BitsOf(b.v);
}

bool IsTie(const Hit& a, const Hit& b) {
  if (!a.IsHit() || !b.IsHit() || a.prim == b.prim) return false;
  const int64_t ta = fp::BitsOf(a.t), tb = fp::BitsOf(b.t);  // t >= 0: the encodings order like the values
  return (ta > tb ? ta - tb : tb - ta) <= kTieUlps;
}

std::string FloatText(float f) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g (0x%08" PRIx32 ")", static_cast<double>(f), fp::BitsOf(f));
  return buf;
}

std::string HitText(const Hit& h) {
  std::string s = h.IsHit() ? "hit, prim " + std::to_string(h.prim) : "miss, prim none (0xffffffff)";
  return s + ", t " + FloatText(h.t) + ", u " + FloatText(h.u) + ", v " + FloatText(h.v);
}

}  // namespace kdrt
