// Build-time measurement, not a check: disabled by default, run with
//   accel_tests --gtest_also_run_disabled_tests --gtest_filter='*BuildTimes*'
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "accel/kdtree.h"
#include "kdtree_test_util.h"

namespace kdrt {
namespace {

void Report(const char* scene, size_t n, const char* method, const KdTree& t) {
  const TreeStats& s = t.stats;
  std::printf("%-7s %7zu %-12s %7.3f s  nodes %9u  refs/tri %6.2f  sah %10.2f  max depth %u\n",
              scene, n, method, s.build_seconds, s.nodes, s.refs_per_triangle, s.sah_cost,
              s.max_depth);
}

TEST(DISABLED_BuildTimes, RandomAndSphere) {
  for (int n : {10000, 100000, 800000}) {
    const Scene random =
        test::MakeScene(test::RandomSmallTriangles(1, n, 0.5f / std::cbrt(float(n))), "random");
    const Scene sphere = test::SphereScene(n);
    for (const Scene* scene : {&random, &sphere}) {
      BuildOptions o;
      Report(scene->source.substr(0, 6).c_str(), scene->triangles.size(), "sah",
             BuildKdTree(*scene, o));
      o.perfect_splits = true;
      Report(scene->source.substr(0, 6).c_str(), scene->triangles.size(), "sah+perfect",
             BuildKdTree(*scene, o));
      o.perfect_splits = false;
      o.method = SplitMethod::kMidpoint;
      Report(scene->source.substr(0, 6).c_str(), scene->triangles.size(), "midpoint",
             BuildKdTree(*scene, o));
    }
  }
}

}  // namespace
}  // namespace kdrt
