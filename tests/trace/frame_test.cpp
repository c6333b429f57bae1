// The scene-relative frame (trace/frame.h): scaling every ray's direction by
// 2^k changes no triangle id in any preset, and t scales by exactly 2^-k,
// because the ray setup normalises the direction's exponent before anything
// is rounded.
#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace kdrt
