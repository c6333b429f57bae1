// The one definition of "the same hit record" (bit for bit: prim and the bits
// of t, u and v) and of how a record is written in messages; used by the
// co-simulation checker, `kdrt compare` and the tests.
#pragma once

#include <string>

#include "common/ray.h"

namespace kdrt {

bool SameBits(const Hit& a, const Hit& b);

// Two structures tracing one ray "tie" when both hit, on different triangles,
// at t within kTieUlps encodings of each other: two triangles meeting the ray
// at (nearly) one point, as where a wall meets the ceiling. Which one a
// structure returns depends on where it may stop: the kd-tree stops after
// the cell that holds its hit and can miss a triangle of the next cell that
// the watertight test puts an ulp closer. Anything else that differs is a
// mismatch (a bug).
inline constexpr uint32_t kTieUlps = 16;
bool IsTie(const Hit& a, const Hit& b);

// "hit, prim 12, t 1.5 (0x3fc00000), u ..., v ..." or "miss, prim none (0xffffffff), ...".
std::string HitText(const Hit& h);

// "1.5 (0x3fc00000)": the value and its bits.
std::string FloatText(float f);

}  // namespace kdrt
