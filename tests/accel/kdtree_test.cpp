// kd-tree builder tests: structure and coverage for every method on random
// scenes, SAH quality, degenerate handling, option and name parsing.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/kdtree.h"
#include "common/error.h"
#include "kdtree_test_util.h"
#include "scenes/gen/generators.h"

namespace kdrt {
namespace {

using test::CheckCoverage;
using test::CheckTreeStructure;

struct MethodCase {
  const char* name;
  SplitMethod method;
  bool perfect;
  float min_split_gain = kDefaultMinSplitGain;
};

const MethodCase kMethods[] = {
    {"sah", SplitMethod::kSah, false},
    {"sah_perfect", SplitMethod::kSah, true},
    {"sah_no_min_gain", SplitMethod::kSah, false, 0.0f},
    {"median", SplitMethod::kMedian, false},
    {"midpoint", SplitMethod::kMidpoint, false},
};

BuildOptions Options(const MethodCase& m) {
  BuildOptions o;
  o.method = m.method;
  o.perfect_splits = m.perfect;
  o.min_split_gain = m.min_split_gain;
  return o;
}

class EveryMethod : public ::testing::TestWithParam<MethodCase> {};

TEST_P(EveryMethod, SmallMixedScenes) {
  for (uint32_t seed = 1; seed <= 6; ++seed) {
    const Scene scene = test::MixedScene(seed, 20 + 15 * static_cast<int>(seed));
    const BuildOptions options = Options(GetParam());
    const KdTree tree = BuildKdTree(scene, options);
    CheckTreeStructure(scene, options, tree);
    CheckCoverage(scene, options, tree, seed, 8);
    EXPECT_GT(tree.stats.degenerate_triangles, 0u);
  }
}

TEST_P(EveryMethod, MediumMixedScene) {
  const Scene scene = test::MixedScene(77, 3000);
  const BuildOptions options = Options(GetParam());
  const KdTree tree = BuildKdTree(scene, options);
  CheckTreeStructure(scene, options, tree);
  CheckCoverage(scene, options, tree, 77, 4);
  EXPECT_GT(tree.stats.inner_nodes, 100u);
}

TEST_P(EveryMethod, GridSnappedPlanarTriangles) {
  // Every vertex on a 1/8 grid: many events coincide and many triangles lie
  // exactly in planes that are also split candidates.
  for (uint32_t seed = 10; seed < 13; ++seed) {
    const Scene scene = test::MakeScene(test::GridSnappedTriangles(seed, 400), "grid");
    const BuildOptions options = Options(GetParam());
    const KdTree tree = BuildKdTree(scene, options);
    CheckTreeStructure(scene, options, tree);
    CheckCoverage(scene, options, tree, seed, 8);
  }
}

TEST_P(EveryMethod, ThinLongAndDuplicatedTriangles) {
  std::vector<Triangle> tris = test::ThinLongTriangles(5, 200);
  const std::vector<Triangle> copy = tris;
  tris.insert(tris.end(), copy.begin(), copy.end());  // every triangle twice
  const Scene scene = test::MakeScene(tris, "thin");
  const BuildOptions options = Options(GetParam());
  const KdTree tree = BuildKdTree(scene, options);
  CheckTreeStructure(scene, options, tree);
  CheckCoverage(scene, options, tree, 5, 16);
}

TEST_P(EveryMethod, LeafSizeAndDepthLimits) {
  const Scene scene = test::MixedScene(31, 600);
  BuildOptions options = Options(GetParam());
  options.max_leaf_prims = 4;
  options.max_depth = 5;
  const KdTree tree = BuildKdTree(scene, options);
  CheckTreeStructure(scene, options, tree);  // checks depth <= 5
  CheckCoverage(scene, options, tree, 31, 4);
  EXPECT_LE(tree.stats.max_depth, 5u);

  options.max_depth = 0;
  const KdTree root_only = BuildKdTree(scene, options);
  ASSERT_EQ(root_only.nodes.size(), 1u);
  EXPECT_TRUE(root_only.nodes[0].IsLeaf());
  EXPECT_EQ(root_only.stats.references,
            scene.triangles.size() - root_only.stats.degenerate_triangles);
}

TEST_P(EveryMethod, DegenerateTrianglesAreLeftOut) {
  std::vector<Triangle> tris = test::RandomSmallTriangles(3, 50, 0.05f);
  // Degenerate ones far outside the unit cube must not widen the bounds.
  const std::vector<Triangle> bad = test::DegenerateTriangles(4, 9, 50.0f);
  tris.insert(tris.begin() + 10, bad.begin(), bad.end());
  const Scene scene = test::MakeScene(tris, "degenerate");
  const BuildOptions options = Options(GetParam());
  const KdTree tree = BuildKdTree(scene, options);
  EXPECT_EQ(tree.stats.degenerate_triangles, 9u);
  for (uint32_t id : tree.lists) EXPECT_FALSE(id >= 10 && id < 19) << "degenerate id " << id;
  for (int a = 0; a < 3; ++a) EXPECT_LE(tree.bounds_max[a], 1.1f);
  CheckTreeStructure(scene, options, tree);
  CheckCoverage(scene, options, tree, 4, 4);
}

TEST_P(EveryMethod, OnlyDegenerateOrNoTrianglesGiveOneEmptyLeaf) {
  for (const Scene& scene : {test::MakeScene(test::DegenerateTriangles(1, 6, 0.0f), "degen"),
                             test::MakeScene({}, "empty")}) {
    const BuildOptions options = Options(GetParam());
    const KdTree tree = BuildKdTree(scene, options);
    ASSERT_EQ(tree.nodes.size(), 1u);
    EXPECT_TRUE(tree.nodes[0].IsLeaf());
    EXPECT_EQ(tree.nodes[0].Count(), 0u);
    EXPECT_EQ(tree.nodes[0].FirstEntry(), 0u);
    EXPECT_TRUE(tree.lists.empty());
    EXPECT_EQ(tree.stats.empty_leaves, 1u);
    EXPECT_EQ(tree.stats.degenerate_triangles, scene.triangles.size());
  }
}

TEST_P(EveryMethod, DeterministicOutput) {
  const Scene scene = test::MixedScene(8, 500);
  const BuildOptions options = Options(GetParam());
  const KdTree a = BuildKdTree(scene, options);
  const KdTree b = BuildKdTree(scene, options);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].word0, b.nodes[i].word0);
    EXPECT_EQ(a.nodes[i].word1, b.nodes[i].word1);
  }
  EXPECT_EQ(a.lists, b.lists);
}

INSTANTIATE_TEST_SUITE_P(Methods, EveryMethod, ::testing::ValuesIn(kMethods),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(SahTree, CheaperThanMidpointAndMedianOnClusteredScene) {
  // Eight clusters of 100 triangles in a 10^3 box. (In much larger, emptier
  // boxes the default empty bonus spends the depth limit on empty cuts and
  // midpoint can win; see docs/kdtree.md.)
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    const Scene scene = test::ClusteredScene(seed, 8, 100, 10.0f);
    BuildOptions options;
    const KdTree sah = BuildKdTree(scene, options);
    options.perfect_splits = true;
    const KdTree perfect = BuildKdTree(scene, options);
    options.perfect_splits = false;
    options.method = SplitMethod::kMidpoint;
    const KdTree midpoint = BuildKdTree(scene, options);
    options.method = SplitMethod::kMedian;
    const KdTree median = BuildKdTree(scene, options);
    EXPECT_LT(sah.stats.sah_cost, midpoint.stats.sah_cost) << "seed " << seed;
    EXPECT_LT(sah.stats.sah_cost, median.stats.sah_cost) << "seed " << seed;
    EXPECT_LT(perfect.stats.sah_cost, midpoint.stats.sah_cost) << "seed " << seed;
    // Empty space around the clusters is cut off into empty leaves.
    EXPECT_GT(sah.stats.empty_leaves, 0u);
  }
}

TEST(SahTree, SplitsBetweenTwoSeparatedTriangles) {
  const Scene scene = test::MakeScene({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                       {{9, 0, 0}, {10, 0, 0}, {10, 1, 0}}},
                                      "pair");
  const KdTree tree = BuildKdTree(scene);
  ASSERT_FALSE(tree.nodes[0].IsLeaf());
  EXPECT_EQ(tree.nodes[0].Axis(), 0);
  EXPECT_GE(tree.nodes[0].Split(), 1.0f);
  EXPECT_LE(tree.nodes[0].Split(), 9.0f);
  EXPECT_EQ(tree.stats.references, 2u);  // neither triangle is duplicated
  CheckTreeStructure(scene, BuildOptions{}, tree);
}

TEST(SahTree, SingleTriangleIsOneLeaf) {
  const Scene scene = test::MakeScene({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, "one");
  const KdTree tree = BuildKdTree(scene);
  ASSERT_EQ(tree.nodes.size(), 1u);
  EXPECT_EQ(tree.nodes[0].Count(), 1u);
  EXPECT_EQ(tree.lists, std::vector<uint32_t>{0});
}

TEST(SahTree, PlanarTriangleOnTheSplitPlaneGoesToOneSide) {
  // Two flat squares (x = 0 and x = 4, two triangles each) and one flat
  // triangle in x = 2 between them; with a large intersection cost the best
  // tree separates all three groups, and the planar triangle is never
  // duplicated even though it lies exactly on a candidate plane.
  std::vector<Triangle> tris = {
      {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}}, {{0, 0, 0}, {0, 1, 1}, {0, 0, 1}},
      {{4, 0, 0}, {4, 1, 0}, {4, 1, 1}}, {{4, 0, 0}, {4, 1, 1}, {4, 0, 1}},
      {{2, 0, 0}, {2, 1, 0}, {2, 1, 1}},
  };
  const Scene scene = test::MakeScene(tris, "planar");
  BuildOptions options;
  const KdTree tree = BuildKdTree(scene, options);
  CheckTreeStructure(scene, options, tree);
  CheckCoverage(scene, options, tree, 1, 8);
  int planar_refs = 0;
  for (uint32_t id : tree.lists) planar_refs += id == 4;
  EXPECT_EQ(planar_refs, 1);
  // Midpoint splits through it (x = 2) and puts it below only.
  options.method = SplitMethod::kMidpoint;
  options.max_leaf_prims = 0;
  const KdTree mid = BuildKdTree(scene, options);
  CheckTreeStructure(scene, options, mid);
  CheckCoverage(scene, options, mid, 1, 8);
  ASSERT_FALSE(mid.nodes[0].IsLeaf());
  EXPECT_EQ(mid.nodes[0].Split(), 2.0f);
  planar_refs = 0;
  for (uint32_t id : mid.lists) planar_refs += id == 4;
  EXPECT_EQ(planar_refs, 1);
}

TEST(EveryMethodTree, TrianglesSharingAnEdgeOnTheSplitAreNotDuplicated) {
  // Two triangles of a mesh sharing the edge x = 1, one on each side: the
  // plane through the edge separates them, as with the paper's (strict)
  // classification; a rule that duplicates touching triangles cannot.
  const Scene scene = test::MakeScene(
      {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5f}}, {{1, 0, 0}, {2, 0, 0.5f}, {1, 1, 0.5f}}}, "edge");
  for (const MethodCase& m : kMethods) {
    if (m.method == SplitMethod::kMedian) continue;  // would split at a box centre, 1.5
    BuildOptions options = Options(m);
    options.isect_cost = 1000.0f;  // makes the SAH split worth it
    const KdTree tree = BuildKdTree(scene, options);
    CheckTreeStructure(scene, options, tree);
    CheckCoverage(scene, options, tree, 3, 16);
    ASSERT_FALSE(tree.nodes[0].IsLeaf()) << m.name;
    EXPECT_EQ(tree.nodes[0].Axis(), 0) << m.name;
    EXPECT_EQ(tree.nodes[0].Split(), 1.0f) << m.name;
    EXPECT_EQ(tree.stats.references, 2u) << m.name;
  }
}

TEST(SahTree, PerfectSplitsReduceReferencesOfDiagonalTriangles) {
  // Long diagonal slivers: their boxes overlap much more than the triangles.
  std::vector<Triangle> tris;
  for (int i = 0; i < 64; ++i) {
    const float o = i / 64.0f;
    tris.push_back({{o, 0, 0}, {o + 1, 1, 1}, {o + 0.01f, 0, 0.01f}});
  }
  const Scene scene = test::MakeScene(tris, "diagonal");
  BuildOptions options;
  options.auto_clip = false;
  const KdTree plain = BuildKdTree(scene, options);
  options.perfect_splits = true;
  const KdTree perfect = BuildKdTree(scene, options);
  CheckTreeStructure(scene, options, perfect);
  CheckCoverage(scene, options, perfect, 2, 32);
  EXPECT_LT(perfect.stats.sah_cost, plain.stats.sah_cost);
  // The default build clips them too: its boxes give no good split.
  const KdTree automatic = BuildKdTree(scene, BuildOptions{});
  CheckTreeStructure(scene, BuildOptions{}, automatic);
  CheckCoverage(scene, BuildOptions{}, automatic, 2, 32);
  EXPECT_LT(automatic.stats.sah_cost, plain.stats.sah_cost);
}

// Long thin cylinders (gen:hoops) and fanned slivers (gen:gears): where the
// boxes give no good split the builder clips the node's triangles to its
// cell (BuildOptions::auto_clip). The tree stays sound (every triangle
// reachable where it lies), is cheaper by the SAH and holds fewer
// references than the boxes' tree. Where the boxes split well (balls) the
// tree is the boxes' tree.
TEST(SahTree, AutoClipSeparatesLongSlivers) {
  BuildOptions boxes;
  boxes.auto_clip = false;
  for (const char* g : {"hoops", "gears"}) {
    const Scene scene = GenerateScene(g, 10000);
    const KdTree a = BuildKdTree(scene, boxes);
    const KdTree b = BuildKdTree(scene, BuildOptions{});
    CheckTreeStructure(scene, BuildOptions{}, b);
    CheckCoverage(scene, BuildOptions{}, b, 3, 2);
    EXPECT_LT(b.stats.sah_cost * 2, a.stats.sah_cost) << g;
    EXPECT_LT(b.stats.references, a.stats.references) << g;
    EXPECT_LT(b.stats.max_leaf_prims, a.stats.max_leaf_prims) << g;
  }
  const Scene balls = GenerateScene("balls", 20000);
  const KdTree c = BuildKdTree(balls, boxes), d = BuildKdTree(balls, BuildOptions{});
  EXPECT_EQ(c.lists, d.lists);
  EXPECT_EQ(c.nodes.size(), d.nodes.size());
}

TEST(BuildKdTree, RejectsBadInput) {
  Scene scene = test::MakeScene({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, "bad.nff");
  scene.triangles[0].v1.y = std::nanf("");
  EXPECT_THROW(BuildKdTree(scene), InputError);
  scene.triangles[0].v1.y = INFINITY;
  EXPECT_THROW(BuildKdTree(scene), InputError);
  try {
    BuildKdTree(scene);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.nff"), std::string::npos) << e.what();
  }

  const Scene good = test::MakeScene({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, "good");
  BuildOptions o;
  o.max_depth = -2;
  EXPECT_THROW(BuildKdTree(good, o), InputError);
  o = {};
  o.max_depth = kMaxTreeDepth + 1;
  EXPECT_THROW(BuildKdTree(good, o), InputError);
  o = {};
  o.max_leaf_prims = -1;
  EXPECT_THROW(BuildKdTree(good, o), InputError);
  o = {};
  o.isect_cost = std::nanf("");
  EXPECT_THROW(BuildKdTree(good, o), InputError);
  o = {};
  o.empty_bonus = 1.5f;
  EXPECT_THROW(BuildKdTree(good, o), InputError);
  for (float gain : {-0.1f, 1.0f, std::nanf("")}) {
    o = {};
    o.min_split_gain = gain;
    EXPECT_THROW(BuildKdTree(good, o), InputError) << gain;
  }
}

// Concave polygons fanned into long overlapping slivers (gen:gears): nearly
// every split keeps most slivers on both sides and gains a fraction of a
// test, so the plain greedy rule splits to the bottom and duplicates every
// sliver. A minimum gain stops those splits: far fewer references, a leaf
// ended by the bad-refinement rule, and still a tree that separates what
// can be separated (every triangle reachable where it lies).
TEST(SahTree, MinSplitGainStopsDuplicatingOverlappingSlivers) {
  const Scene scene = GenerateScene("gears", 20000);
  BuildOptions plain;
  plain.min_split_gain = 0.0f;
  BuildOptions gain;
  gain.min_split_gain = 0.1f;
  const KdTree a = BuildKdTree(scene, plain);
  const KdTree b = BuildKdTree(scene, gain);
  CheckTreeStructure(scene, gain, b);
  CheckCoverage(scene, gain, b, 5, 2);
  EXPECT_LT(b.stats.references * 3, a.stats.references)
      << "plain " << a.stats.references << ", min gain 0.1 " << b.stats.references;
  EXPECT_GT(b.stats.leaf_causes.by_cause[static_cast<int>(LeafCause::kNoGain)].leaves,
            a.stats.leaf_causes.by_cause[static_cast<int>(LeafCause::kNoGain)].leaves);
  EXPECT_GT(b.stats.inner_nodes, 1000u);
  // Where splits gain much (well separated tetrahedra), the rule changes
  // nothing.
  const Scene tetra = GenerateScene("tetra", 20000);
  const KdTree c = BuildKdTree(tetra, plain), d = BuildKdTree(tetra, gain);
  EXPECT_EQ(c.lists, d.lists);
  EXPECT_EQ(c.nodes.size(), d.nodes.size());
}

TEST(BuildKdTree, DefaultMaxDepthFormula) {
  EXPECT_EQ(DefaultMaxDepth(1), 8);
  EXPECT_EQ(DefaultMaxDepth(1024), 21);  // 8 + 13
  EXPECT_EQ(DefaultMaxDepth(1000000), 34);  // 8 + 1.3 * 19.93 = 33.9
}

TEST(SplitMethodNames, RoundTripAndUnknown) {
  for (SplitMethod m : {SplitMethod::kSah, SplitMethod::kMedian, SplitMethod::kMidpoint}) {
    EXPECT_EQ(ParseSplitMethod(SplitMethodName(m)), m);
  }
  EXPECT_STREQ(SplitMethodName(SplitMethod::kSah), "sah");
  EXPECT_STREQ(SplitMethodName(SplitMethod::kMedian), "median");
  EXPECT_STREQ(SplitMethodName(SplitMethod::kMidpoint), "midpoint");
  EXPECT_THROW(ParseSplitMethod("bvh"), InputError);
  EXPECT_THROW(ParseSplitMethod(""), InputError);
  try {
    ParseSplitMethod("octree");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("octree"), std::string::npos);
  }
}

}  // namespace
}  // namespace kdrt
