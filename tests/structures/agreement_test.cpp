// Every software structure gives the kd-tree's hit buffer: on camera rays and
// on random rays starting inside the scene with finite tmax, in fp32 and
// fp64, the hit records are bit for bit the kd-tree's except at ties (both
// hit at the same t bits, another triangle), which are counted and must stay
// rare; any-hit queries answer hit/miss as the closest-hit trace does; and
// the structures agree with Embree by the oracle test's criteria.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <glm/geometric.hpp>
#include <glm/common.hpp>

#include "oracle/embree_scene.h"
#include "structures/structure.h"
#include "structures/structure_tracer.h"
#include "tests/structures/structures_test_util.h"

namespace kdrt {
namespace {

using testing::BruteForceHits;
using testing::FromTriangles;
using testing::InsideRays;

struct AgreementCase {
  AccelKind kind;
  const char* generator;
  int size;
};

std::string CaseName(const ::testing::TestParamInfo<AgreementCase>& info) {
  return std::string(AccelKindName(info.param.kind)) + "_" + info.param.generator;
}

struct Comparison {
  size_t mismatches = 0, ties = 0, hits = 0;
};

Comparison Compare(const std::vector<Hit>& kd, const std::vector<Hit>& ours, const std::vector<Ray>& rays,
                   const char* what) {
  Comparison c;
  for (size_t i = 0; i < kd.size(); ++i) {
    if (kd[i].IsHit()) ++c.hits;
    if (SameBits(kd[i], ours[i])) continue;
    if (IsTie(kd[i], ours[i])) {
      ++c.ties;
      continue;
    }
    if (++c.mismatches <= 5) {
      ADD_FAILURE() << what << " ray " << i << " (o " << rays[i].o.x << " " << rays[i].o.y << " " << rays[i].o.z
                    << ", d " << rays[i].d.x << " " << rays[i].d.y << " " << rays[i].d.z << ", tmax " << rays[i].tmax
                    << "): kd-tree " << HitText(kd[i]) << ", structure " << HitText(ours[i]);
    }
  }
  return c;
}

class StructureAgreement : public ::testing::TestWithParam<AgreementCase> {};

TEST_P(StructureAgreement, SameHitsAsKdTree) {
  const AgreementCase& ac = GetParam();
  testing::Prepared p(GenerateScene(ac.generator, ac.size));
  const ImageView image = p.view();
  const StructureInput input = MakeStructureInput(image);
  const std::unique_ptr<Structure> s = BuildStructure(ac.kind, input, StructureOptions{});
  EXPECT_GT(s->stats().nodes, 0u);
  EXPECT_GE(s->stats().references, input.ids.size());
  EXPECT_GT(s->stats().memory_bytes, 0u);

  const std::vector<Ray> camera = testing::CameraRays(p.scene, 96);
  const std::vector<Ray> inside = InsideRays(p.scene, 6000, 7);
  for (const char* format : {"fp32", "fp64"}) {
    TraceOptions o;
    o.format = fp::ParseFormat(format);
    for (const auto* set : {&camera, &inside}) {
      const std::string what = std::string(format) + (set == &camera ? " camera" : " inside");
      const std::vector<Hit> kd = TraceRays(image, *set, o);
      AccelTotals totals;
      const std::vector<Hit> ours = TraceStructureRays(*s, image.frame(), *set, o, &totals);
      const Comparison c = Compare(kd, ours, *set, what.c_str());
      std::printf("[ agree    ] %s %s:%d %s: %zu mismatches, %zu ties of %zu hits; %.2f nodes, %.2f tests, "
                  "%.2f mailbox hits per ray\n",
                  AccelKindName(ac.kind), ac.generator, ac.size, what.c_str(), c.mismatches, c.ties, c.hits,
                  double(totals.nodes) / set->size(), double(totals.tri_tests) / set->size(),
                  double(totals.mailbox_hits) / set->size());
      EXPECT_EQ(c.mismatches, 0u) << what;
      EXPECT_LE(c.ties, c.hits / 50 + 2) << what;
      EXPECT_GT(totals.tri_tests, 0u);
      EXPECT_GT(totals.nodes, 0u);
      if (!s->uses_mailbox()) {
        EXPECT_EQ(totals.mailbox_hits, 0u);
      }

      // Any hit: the same hit/miss answer, and a hit that is one.
      TraceOptions any = o;
      any.query = Query::kAny;
      AccelTotals any_totals;
      const std::vector<Hit> occluded = TraceStructureRays(*s, image.frame(), *set, any, &any_totals);
      size_t differ = 0;
      for (size_t i = 0; i < kd.size(); ++i) differ += occluded[i].IsHit() != kd[i].IsHit();
      EXPECT_EQ(differ, 0u) << what << " any-hit";
      EXPECT_LE(any_totals.tri_tests, totals.tri_tests) << what << " any-hit";
    }
  }
}

// Across the generators, each structure.
std::vector<AgreementCase> AllCases() {
  std::vector<AgreementCase> cases;
  for (AccelKind k : {AccelKind::kGrid, AccelKind::kHgrid, AccelKind::kOctree, AccelKind::kBvh}) {
    for (const char* g : {"room", "balls", "rings", "tetra", "tree", "gears"}) cases.push_back({k, g, 3000});
  }
  return cases;
}
INSTANTIATE_TEST_SUITE_P(Generators, StructureAgreement, ::testing::ValuesIn(AllCases()), CaseName);

// The oracle test's criteria (tests/trace/oracle_test.cpp) against Embree.
class StructureOracle : public ::testing::TestWithParam<AccelKind> {};

TEST_P(StructureOracle, PrimaryRaysAgreeWithEmbree) {
  for (const char* g : {"balls", "tree"}) {
    testing::Prepared p(GenerateScene(g, 5000));
    const ImageView image = p.view();
    const StructureInput input = MakeStructureInput(image);
    const std::unique_ptr<Structure> s = BuildStructure(GetParam(), input, StructureOptions{});
    const EmbreeScene embree(p.scene, 1);
    const std::vector<Ray> rays = testing::CameraRays(p.scene, 128);
    const std::vector<Hit> ours = TraceStructureRays(*s, image.frame(), rays, TraceOptions{});
    size_t hitmiss = 0, t_disagree = 0, ties = 0, both = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      const Hit theirs = embree.Intersect(rays[i]);
      if (ours[i].IsHit() != theirs.IsHit()) {
        ++hitmiss;
        continue;
      }
      if (!ours[i].IsHit()) continue;
      ++both;
      const float rel = std::fabs(ours[i].t - theirs.t) / std::max(std::fabs(theirs.t), 1e-30f);
      if (rel > 1e-5f) {
        ++t_disagree;
      } else if (ours[i].prim != theirs.prim) {
        ++ties;
      }
    }
    EXPECT_GE(1.0 - double(hitmiss) / rays.size(), 0.9999) << g;
    EXPECT_EQ(t_disagree, 0u) << g;
    EXPECT_LE(ties, both / 100 + 2) << g;
  }
}

INSTANTIATE_TEST_SUITE_P(Structures, StructureOracle,
                         ::testing::Values(AccelKind::kGrid, AccelKind::kHgrid, AccelKind::kOctree, AccelKind::kBvh),
                         [](const auto& info) { return std::string(AccelKindName(info.param)); });

}  // namespace
}  // namespace kdrt
