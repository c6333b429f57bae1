// Why leaves stay leaves (TreeStats::leaf_causes, `kdrt info`): the builder
// counts every leaf under the first rule that ended its recursion. The counts
// must add up to the tree's own statistics, recounted from its nodes, and
// hand-made scenes must land on the rule they are built for.
#include <gtest/gtest.h>

#include <glm/vec3.hpp>

#include "accel/kdtree.h"
#include "kdtree_test_util.h"
#include "scenes/gen/generators.h"

namespace kdrt {
namespace {

const LeafCauseCount& Count(const KdTree& t, LeafCause c) {
  return t.stats.leaf_causes.by_cause[static_cast<int>(c)];
}

// Leaves, references, large leaves and the largest leaf, recounted from the
// nodes and summed over the causes, agree.
void ExpectCausesAddUp(const KdTree& t, const std::string& what) {
  uint64_t leaves = 0, references = 0, large = 0, large_nodes = 0;
  uint32_t largest = 0;
  ASSERT_TRUE(t.stats.leaf_causes.recorded) << what;
  for (const LeafCauseCount& n : t.stats.leaf_causes.by_cause) {
    leaves += n.leaves;
    references += n.references;
    large += n.large;
    largest = std::max(largest, n.largest);
  }
  for (const img::Node& n : t.nodes) large_nodes += n.IsLeaf() && n.Count() > kLargeLeafPrims;
  EXPECT_EQ(leaves, t.stats.leaves) << what;
  EXPECT_EQ(references, t.stats.references) << what;
  EXPECT_EQ(large, large_nodes) << what;
  EXPECT_EQ(largest, t.stats.max_leaf_prims) << what;
}

TEST(LeafCauses, AddUpToTheTreeOnEveryGeneratorAndBuilder) {
  for (const char* g : {"room", "balls", "rings", "tetra", "tree", "gears", "strips", "hoops"}) {
    const Scene scene = GenerateScene(g, 3000);
    for (SplitMethod m : {SplitMethod::kSah, SplitMethod::kMedian, SplitMethod::kMidpoint}) {
      BuildOptions o;
      o.method = m;
      ExpectCausesAddUp(BuildKdTree(scene, o), std::string(g) + " " + SplitMethodName(m));
    }
  }
}

// The parallel build counts the leaves of its parts: the same counts as the
// serial build, whose tree it reproduces.
TEST(LeafCauses, ParallelBuildCountsAsTheSerialOne) {
  const Scene scene = GenerateScene("tree", 20000);
  BuildOptions serial, parallel;
  parallel.threads = 3;
  const KdTree a = BuildKdTree(scene, serial), b = BuildKdTree(scene, parallel);
  for (int i = 0; i < kLeafCauseCount; ++i) {
    const LeafCauseCount &x = a.stats.leaf_causes.by_cause[i], &y = b.stats.leaf_causes.by_cause[i];
    const char* name = LeafCauseName(static_cast<LeafCause>(i));
    EXPECT_EQ(x.leaves, y.leaves) << name;
    EXPECT_EQ(x.references, y.references) << name;
    EXPECT_EQ(x.large, y.large) << name;
    EXPECT_EQ(x.largest, y.largest) << name;
  }
  ExpectCausesAddUp(b, "tree 20000, 3 threads");
}

// 40 copies of one triangle: the SAH's candidate planes all lie on the
// cell's faces, so the root is a leaf that no plane can split; the median
// and midpoint planes cut through the triangle and would keep all 40 on
// both sides.
TEST(LeafCauses, CopiesOfOneTriangleCannotBeSeparated) {
  std::vector<Triangle> tris(40, Triangle{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0.5f), glm::vec3(0, 1, 1)});
  for (SplitMethod m : {SplitMethod::kSah, SplitMethod::kMedian, SplitMethod::kMidpoint}) {
    BuildOptions o;
    o.method = m;
    const KdTree t = BuildKdTree(test::MakeScene(tris, "copies"), o);
    EXPECT_EQ(t.stats.leaves, 1u) << SplitMethodName(m);
    const LeafCauseCount& n = Count(t, m == SplitMethod::kSah ? LeafCause::kNoPlane : LeafCause::kNoGain);
    EXPECT_EQ(n.leaves, 1u) << SplitMethodName(m);
    EXPECT_EQ(n.large, 1u) << SplitMethodName(m);
    EXPECT_EQ(n.largest, 40u) << SplitMethodName(m);
  }
}

// Small triangles far apart under a depth limit of 2: at most 4 leaves, the
// ones holding triangles ended by the limit; with no limit every leaf holds
// at most one triangle (max_leaf_prims 1).
TEST(LeafCauses, DepthLimitAndFewTriangles) {
  std::vector<Triangle> tris;
  for (int i = 0; i < 64; ++i) {
    const glm::vec3 o(float(i % 4) * 10, float(i / 4 % 4) * 10, float(i / 16) * 10);
    tris.push_back(Triangle{o, o + glm::vec3(1, 0, 0), o + glm::vec3(0, 1, 0)});
  }
  const Scene scene = test::MakeScene(tris, "spread");
  BuildOptions limited;
  limited.max_depth = 2;
  const KdTree a = BuildKdTree(scene, limited);
  EXPECT_LE(a.stats.leaves, 4u);
  EXPECT_GE(Count(a, LeafCause::kDepth).leaves, 1u);
  EXPECT_EQ(Count(a, LeafCause::kDepth).references, 64u);
  const KdTree b = BuildKdTree(scene, BuildOptions{});
  EXPECT_EQ(Count(b, LeafCause::kDepth).leaves, 0u);
  EXPECT_EQ(Count(b, LeafCause::kFew).references, 64u);
  EXPECT_EQ(Count(b, LeafCause::kFew).largest, 1u);
  ExpectCausesAddUp(a, "depth 2");
  ExpectCausesAddUp(b, "no limit");
}

}  // namespace
}  // namespace kdrt
