// The scene-relative frame of the memory image (docs/memory-image.md): the
// image holds geometry and split planes translated to the scene box and
// scaled by a power of two, so every coordinate lies in about [-16, 16]
// whatever the scene's offset and size, a range every format represents
// well. The ray setup maps each ray the same way (in fp32, before the
// conversion to the datapath format) and scales its direction by a power of
// two so its largest component lies in [1, 2); hit distances go back to the
// caller's units by an exact power-of-two scale. These functions are the
// definition the RTL ray setup and hit output follow bit for bit.
#pragma once

#include <cstdint>

#include "common/ray.h"
#include "fp/format.h"
#include "scene/scene.h"

namespace kdrt {

// Bounds the frame's scale (scenes span at most fp32's range, so it never
// binds for real input) and with it the hardware's shift counters.
inline constexpr int32_t kMaxFrameScaleLog2 = 160;

// The frame puts the largest distance of a vertex from the origin in
// (2^(R-1), 2^R]. R = 4 centres the watertight test's products in fp16's
// exponent range (2^-14 .. 2^16): its degree-3 terms (e*z, tmax*det) for
// rays from a few scene sizes away stay below 2^16, and the degree-2 edge
// functions of triangles down to ~1/2000 of the scene stay above 2^-14.
// Measured (tests/trace/formats_test.cpp, fp16, 3k triangles): R = 0 lost
// same-triangle t accuracy and 4-27 % more pixels changed; R = 3..5 were
// best; R = 6 overflowed t.
inline constexpr int kFrameReachLog2 = 4;

struct Frame {
  float origin[3] = {0.0f, 0.0f, 0.0f};  // the scene box's centre, in fp32
  int32_t scale_log2 = 0;                 // framed = (world - origin) * 2^scale_log2
};

// The frame of a scene: origin at the centre of its bounding box (rounded to
// fp32), the scale the power of two that brings the largest distance from the
// origin into (2^(R-1), 2^R], R = kFrameReachLog2.
Frame ChooseFrame(const Scene& world);

// One coordinate in the frame: (x - origin) * 2^s computed in double and
// rounded once to fp32 (monotone, so vertex and split order is kept and a
// shared vertex stays shared).
float ToFrame(float x, float origin, int32_t scale_log2);
Scene ToFrame(const Scene& world, const Frame& frame);

// A ray as the hardware's ray setup maps it: in fp32 with the formats'
// policy (round to nearest even, subnormals flushed):
//   o'[i] = ldexp(o[i] - origin[i], s)
//   m     = 127 - (the largest biased exponent among d[x], d[y], d[z]); 0 if all are zero
//   d'[i] = ldexp(d[i], m)
//   t_scale_log2 = m - s;  tmin' = ldexp(tmin, -t_scale_log2), likewise tmax
// A distance t' along the framed ray is t' * 2^t_scale_log2 along the world ray.
struct FramedRay {
  Ray ray;
  int32_t t_scale_log2 = 0;
};
FramedRay ToFrame(const Ray& world, const Frame& frame);

// ToFrame's rule on the subtraction and the power-of-two scaling it is
// given: sub(a, b) = a - b and scale(x, n) = x * 2^n in fp32 under the
// policy above (ToFrame: the soft-float ones; ToFrameFtz below: native).
template <class Sub, class Scale>
FramedRay MapToFrame(const Ray& world, const Frame& frame, Sub sub, Scale scale) {
  FramedRay r;
  uint32_t max_exp = 0;
  for (int i = 0; i < 3; ++i) {
    r.ray.o[i] = scale(sub(world.o[i], frame.origin[i]), frame.scale_log2);
    const uint32_t e = (fp::BitsOf(world.d[i]) >> 23) & 0xFFu;
    max_exp = e > max_exp ? e : max_exp;
  }
  const int m = max_exp == 0 ? 0 : 127 - static_cast<int>(max_exp);
  for (int i = 0; i < 3; ++i) r.ray.d[i] = scale(world.d[i], m);
  r.t_scale_log2 = m - frame.scale_log2;
  r.ray.tmin = scale(world.tmin, -r.t_scale_log2);
  r.ray.tmax = scale(world.tmax, -r.t_scale_log2);
  return r;
}

// ldexp(t, t_scale_log2) in fp32 under the same policy (exact unless the
// result leaves the normal range: then a signed zero or an infinity).
float DistanceToWorld(float t, int32_t t_scale_log2);

// The same two functions on native fp32, bit for bit (tests Frame.Native*),
// for the fp32 tracer, where the soft-float calls above were a tenth of a
// ray's time. The caller MUST hold fp::ScopedFtzDaz (fp/ftz.h), as for
// fp::NativeF32Arith: flushing and round to nearest then make the native
// subtraction the policy's. A NaN anywhere in the ray takes the soft path
// (native arithmetic keeps a NaN's payload, the policy gives its canonical
// NaN).
//
// x * 2^n: products with normal powers of two are exact, and a chain of them
// all of one sign leaves the normal range only where the whole product does
// (DAZ makes a subnormal x a zero, FTZ a tiny result a signed zero, as
// fp::Ldexp).
inline float ScalePow2Ftz(float x, int n) {
  while (n > 126) {
    x *= 0x1p126f;
    n -= 126;
  }
  while (n < -126) {
    x *= 0x1p-126f;
    n += 126;
  }
  return x * fp::FloatOf(static_cast<uint32_t>(n + 127) << 23);
}

inline FramedRay ToFrameFtz(const Ray& world, const Frame& frame) {
  bool nan = false;
  for (int i = 0; i < 3; ++i) nan |= world.o[i] != world.o[i] || world.d[i] != world.d[i];
  if (nan || world.tmin != world.tmin || world.tmax != world.tmax) return ToFrame(world, frame);
  // Subnormal inputs are flushed on the bits (fp::NativeF32Arith::Load):
  // where a scale is a constant 1 the compiler folds the product away, and
  // with it DAZ.
  const auto in = [](float x) { return fp::NativeF32Arith::Load(x); };
  return MapToFrame(
      world, frame, [&in](float a, float b) { return in(a) - in(b); },
      [&in](float x, int n) { return ScalePow2Ftz(in(x), n); });
}

inline float DistanceToWorldFtz(float t, int32_t t_scale_log2) {
  return t != t ? DistanceToWorld(t, t_scale_log2) : ScalePow2Ftz(fp::NativeF32Arith::Load(t), t_scale_log2);
}

}  // namespace kdrt
