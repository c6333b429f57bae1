// The scene-relative frame (trace/frame.h): scaling every ray's direction by
// 2^k changes no triangle id in any preset, and t scales by exactly 2^-k,
// because the ray setup normalises the direction's exponent before anything
// is rounded.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "fp/ftz.h"
#include "trace/frame.h"

#include "tests/common/moved_sphere.h"
#include "trace_test_util.h"

namespace kdrt {
namespace {

TEST(Frame, DirectionScaleChangesNoTriangle) {
  const testing::MeshAndRays m = testing::MovedSphere(0, 1);
  testing::Prepared p(m.scene);
  for (const fp::Format& f : fp::Presets()) {
    TraceOptions o;
    o.format = f;
    o.threads = 2;
    const std::vector<Hit> base = TraceRays(p.view(), m.rays, o);
    for (int k : {-100, -60, -20, 20, 60, 100}) {
      std::vector<Ray> scaled = m.rays;
      for (Ray& r : scaled) r.d = r.d * std::ldexp(1.0f, k);
      const std::vector<Hit> hits = TraceRays(p.view(), scaled, o);
      for (size_t i = 0; i < hits.size(); ++i) {
        ASSERT_EQ(hits[i].prim, base[i].prim) << f.Name() << " 2^" << k << " ray " << i;
        ASSERT_EQ(hits[i].t, std::ldexp(base[i].t, -k)) << f.Name() << " 2^" << k << " ray " << i;
        ASSERT_EQ(fp::BitsOf(hits[i].u), fp::BitsOf(base[i].u)) << f.Name() << " 2^" << k << " ray " << i;
      }
    }
  }
}

// A random fp32 encoding of every kind: normal values of every exponent,
// subnormals, zeros, infinities and NaNs of both signs.
float AnyFloat(std::mt19937& rng) {
  const uint32_t bits = static_cast<uint32_t>(rng());
  switch (rng() % 8) {
    case 0:
      return fp::FloatOf(bits & 0x807FFFFFu);  // subnormal or zero
    case 1:
      return fp::FloatOf((bits & 0x80000000u) | 0x7F800000u);  // infinity
    case 2:
      return fp::FloatOf(bits | 0x7F800000u);  // NaN or infinity
    case 3:  // near 1, the common case
      return fp::FloatOf((bits & 0x807FFFFFu) | ((120u + bits % 16u) << 23));
    default:
      return fp::FloatOf(bits);
  }
}

bool SameBits(float a, float b) { return fp::BitsOf(a) == fp::BitsOf(b); }

// The native frame mapping of the fp32 tracer gives the soft-float one's bits
// on every kind of input, for every frame scale.
TEST(Frame, NativeMappingMatchesSoftFloat) {
  std::mt19937 rng(7);
  for (int i = 0; i < 400000; ++i) {
    Frame f;
    for (float& c : f.origin) c = rng() % 4 ? AnyFloat(rng) : 0.0f;
    for (float& c : f.origin) c = std::isfinite(c) ? c : 1.0f;  // a frame is finite
    f.scale_log2 = static_cast<int32_t>(rng() % (2 * kMaxFrameScaleLog2 + 1)) - kMaxFrameScaleLog2;
    Ray w;
    for (int k = 0; k < 3; ++k) {
      w.o[k] = AnyFloat(rng);
      w.d[k] = AnyFloat(rng);
    }
    w.tmin = rng() % 2 ? 0.0f : AnyFloat(rng);
    w.tmax = rng() % 2 ? INFINITY : AnyFloat(rng);
    const FramedRay soft = ToFrame(w, f);
    FramedRay native;
    {
      fp::ScopedFtzDaz ftz;
      native = ToFrameFtz(w, f);
    }
    ASSERT_EQ(native.t_scale_log2, soft.t_scale_log2) << i;
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(SameBits(native.ray.o[k], soft.ray.o[k])) << i << " o" << k << ": " << w.o[k];
      ASSERT_TRUE(SameBits(native.ray.d[k], soft.ray.d[k])) << i << " d" << k << ": " << w.d[k];
    }
    ASSERT_TRUE(SameBits(native.ray.tmin, soft.ray.tmin)) << i << " tmin " << w.tmin;
    ASSERT_TRUE(SameBits(native.ray.tmax, soft.ray.tmax)) << i << " tmax " << w.tmax;
  }
}

TEST(Frame, NativeDistanceToWorldMatchesSoftFloat) {
  std::mt19937 rng(11);
  for (int i = 0; i < 400000; ++i) {
    const float t = AnyFloat(rng);
    const int32_t s = static_cast<int32_t>(rng() % 641) - 320;
    const float soft = DistanceToWorld(t, s);
    float native;
    {
      fp::ScopedFtzDaz ftz;
      native = DistanceToWorldFtz(t, s);
    }
    ASSERT_TRUE(SameBits(native, soft)) << i << ": " << t << " * 2^" << s;
  }
}

}  // namespace
}  // namespace kdrt
