// The one definition of "the same hit record" (bit for bit: prim and the bits
// of t, u and v) and of how a record is written in messages; used by the
// co-simulation checker, `kdrt compare` and the tests.
#pragma once

#include <string>

#include "common/ray.h"

namespace kdrt {

bool SameBits(const Hit& a, const Hit& b);

// "hit, prim 12, t 1.5 (0x3fc00000), u ..., v ..." or "miss, prim none (0xffffffff), ...".
std::string HitText(const Hit& h);

// "1.5 (0x3fc00000)": the value and its bits.
std::string FloatText(float f);

}  // namespace kdrt
