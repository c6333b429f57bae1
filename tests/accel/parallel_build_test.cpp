// The parallel SAH build (BuildOptions::threads) gives the serial build's
// tree: the same nodes and leaf lists, entry for entry, on every generator,
// with and without perfect splits, without automatic clipping and without the default minimum split gain, for
// several thread counts, including more threads than subtrees.
#include <gtest/gtest.h>

#include <cstring>

#include "accel/kdtree.h"
#include "common/error.h"
#include "scenes/gen/generators.h"

namespace kdrt {
namespace {

size_t FirstDifference(const KdTree& a, const KdTree& b) {
  const size_t n = std::min(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < n; ++i) {
    if (a.nodes[i].word0 != b.nodes[i].word0 || a.nodes[i].word1 != b.nodes[i].word1) return i;
  }
  return n;
}

class ParallelBuild : public ::testing::TestWithParam<const char*> {};

TEST_P(ParallelBuild, SameTreeAsTheSerialBuild) {
  const Scene scene = GenerateScene(GetParam(), 30000);
  for (int variant = 0; variant < 4; ++variant) {
    const bool perfect = variant == 1;
    BuildOptions serial;
    serial.perfect_splits = perfect;
    serial.auto_clip = variant != 3;
    serial.min_split_gain = variant == 2 ? 0.0f : kDefaultMinSplitGain;
    serial.threads = 1;
    const KdTree expected = BuildKdTree(scene, serial);
    for (int threads : {2, 3, 16}) {
      BuildOptions o = serial;
      o.threads = threads;
      const KdTree got = BuildKdTree(scene, o);
      const std::string what = std::string(GetParam()) + (perfect ? " perfect" : "") +
                               (variant == 2 ? " min gain 0" : "") + (variant == 3 ? " no auto clip" : "") + ", " +
                               std::to_string(threads) + " threads";
      ASSERT_EQ(got.nodes.size(), expected.nodes.size()) << what;
      EXPECT_EQ(FirstDifference(got, expected), expected.nodes.size()) << what << ": first differing node";
      EXPECT_EQ(got.lists, expected.lists) << what;
      EXPECT_EQ(got.stats.sah_cost, expected.stats.sah_cost) << what;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Generators, ParallelBuild,
                         ::testing::Values("room", "balls", "rings", "tetra", "tree", "gears", "strips", "hoops"));

TEST(ParallelBuild, RefusesANegativeThreadCount) {
  BuildOptions o;
  o.threads = -1;
  EXPECT_THROW(BuildKdTree(GenerateScene("balls", 100), o), InputError);
}

}  // namespace
}  // namespace kdrt
