// Packets (trace/packet.h) against the scalar walk: for every generator and
// preset, camera rays, shadow rays to a light and incoherent rays give the
// same hit records bit for bit and the same per-ray counters with packets
// off and at every width; formats the packet path does not run say so in
// the plan and still give the scalar results.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "common/error.h"
#include "fp/format.h"
#include "trace/packet.h"
#include "trace_test_util.h"

namespace kdrt {
namespace {

bool SameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The scene's bounding box.
void Box(const Scene& scene, float lo[3], float hi[3]) {
  for (int k = 0; k < 3; ++k) lo[k] = INFINITY, hi[k] = -INFINITY;
  for (const Triangle& t : scene.triangles) {
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
    }
  }
}

// Traces `rays` with packets off and at each width; every hit and counter equal.
void ExpectPacketsMatch(const ImageView& image, const std::vector<Ray>& rays, TraceOptions to,
                        const std::string& what) {
  to.threads = 1;
  to.packets = 0;
  std::vector<RayCounters> ref_counters;
  const std::vector<Hit> ref = TraceRays(image, rays, to, nullptr, &ref_counters);
  for (int width : {4, 8, 16}) {
    to.packets = width;
    std::vector<RayCounters> counters;
    TraceStats stats;
    const std::vector<Hit> hits = TraceRays(image, rays, to, &stats, &counters);
    const bool packed = to.format.IsFp32() && TravFormat(to).IsFp32();
    EXPECT_EQ(stats.packets.width, packed ? width : 0) << what;
    ASSERT_EQ(hits.size(), ref.size());
    int mismatches = 0;
    for (size_t i = 0; i < rays.size() && mismatches < 5; ++i) {
      const bool same = hits[i].prim == ref[i].prim && SameBits(hits[i].t, ref[i].t) &&
                        SameBits(hits[i].u, ref[i].u) && SameBits(hits[i].v, ref[i].v) &&
                        counters[i].nodes == ref_counters[i].nodes && counters[i].leaves == ref_counters[i].leaves &&
                        counters[i].tri_tests == ref_counters[i].tri_tests &&
                        counters[i].overflows == ref_counters[i].overflows;
      if (!same) {
        ++mismatches;
        ADD_FAILURE() << what << " width " << width << " ray " << i << ": prim " << hits[i].prim << " vs "
                      << ref[i].prim << ", t " << hits[i].t << " vs " << ref[i].t << ", nodes " << counters[i].nodes
                      << " vs " << ref_counters[i].nodes << ", tests " << counters[i].tri_tests << " vs "
                      << ref_counters[i].tri_tests;
      }
    }
  }
}

// Rays from each camera hit towards a light above the scene (any hit).
std::vector<Ray> ShadowRays(const ImageView& image, const std::vector<Ray>& camera, const Scene& scene) {
  TraceOptions to;
  to.threads = 1;
  to.packets = 0;
  const std::vector<Hit> hits = TraceRays(image, camera, to);
  float lo[3], hi[3];
  Box(scene, lo, hi);
  const float light[3] = {0.3f * lo[0] + 0.7f * hi[0], hi[1] + (hi[1] - lo[1]), 0.6f * lo[2] + 0.4f * hi[2]};
  std::vector<Ray> rays;
  for (size_t i = 0; i < camera.size(); ++i) {
    if (!hits[i].IsHit()) continue;
    Ray r;
    for (int k = 0; k < 3; ++k) {
      const float p = camera[i].o[k] + hits[i].t * camera[i].d[k];
      r.o[k] = p;
      r.d[k] = light[k] - p;
    }
    r.tmin = 1e-4f;
    r.tmax = 1.0f;
    rays.push_back(r);
  }
  return rays;
}

// Random origins and directions inside the scene box, and axis-parallel rays
// (zero direction components, origins on the box's coordinate grid).
std::vector<Ray> IncoherentRays(const Scene& scene, int n) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), s(-1.0f, 1.0f);
  float l[3], h[3];
  Box(scene, l, h);
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    Ray r;
    for (int k = 0; k < 3; ++k) {
      r.o[k] = l[k] + u(rng) * (h[k] - l[k]);
      r.d[k] = i % 3 == 0 && k != i % 9 / 3 ? 0.0f : s(rng);
    }
    r.tmin = 0.0f;
    r.tmax = INFINITY;
    rays.push_back(r);
  }
  return rays;
}

TEST(Packets, EveryGeneratorSameHitsAndCountersAtEveryWidth) {
  for (const std::string& name : GeneratorNames()) {
    const testing::Prepared p(GenerateScene(name, 1500));
    const std::vector<Ray> camera = testing::CameraRays(p.scene, 32);
    TraceOptions to;
    ExpectPacketsMatch(p.view(), camera, to, name + " camera");
    to.row_width = 32;  // tiles
    ExpectPacketsMatch(p.view(), camera, to, name + " camera tiles");
    to.row_width = 0;
    ExpectPacketsMatch(p.view(), IncoherentRays(p.scene, 512), to, name + " incoherent");
    to.query = Query::kAny;
    ExpectPacketsMatch(p.view(), ShadowRays(p.view(), camera, p.scene), to, name + " shadow");
  }
}

TEST(Packets, StackLimitAndMollerSameAsScalar) {
  const testing::Prepared p(GenerateScene("tree", 1500));
  const std::vector<Ray> camera = testing::CameraRays(p.scene, 32);
  TraceOptions to;
  to.stack_depth = 2;  // pushes onto a full stack end rays
  ExpectPacketsMatch(p.view(), camera, to, "stack depth 2");
  to.stack_depth = 0;
  to.isect = IsectMethod::kMoller;
  ExpectPacketsMatch(p.view(), camera, to, "moller");
}

TEST(Packets, EveryPresetSameHits) {
  const testing::Prepared p(GenerateScene("balls", 1500));
  const std::vector<Ray> camera = testing::CameraRays(p.scene, 16);
  for (const fp::Format& f : fp::Presets()) {
    TraceOptions to;
    to.format = f;
    ExpectPacketsMatch(p.view(), camera, to, f.Name());
    TraceStats stats;
    to.packets = 8;
    TraceRays(p.view(), camera, to, &stats);
    EXPECT_EQ(stats.packets.why_scalar.empty(), f.IsFp32()) << f.Name();
  }
}

TEST(Packets, ParseWidth) {
  EXPECT_EQ(ParsePacketWidth("off"), 0);
  EXPECT_EQ(ParsePacketWidth("8"), 8);
  EXPECT_THROW(ParsePacketWidth("5"), InputError);
}

}  // namespace
}  // namespace kdrt
