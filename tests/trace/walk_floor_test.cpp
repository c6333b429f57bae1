// The walk floor of kdrt_bench (bench/walk_floor.h): its bare walk must visit
// the nodes the tracer visits (the same count per ray, ending after the
// tracer's leaves), or the floor it reports is a floor for another walk.
#include <gtest/gtest.h>

#include <vector>

#include "bench/walk_floor.h"
#include "trace_test_util.h"

namespace kdrt {
namespace {

TEST(WalkFloor, VisitsTheTracersNodeCount) {
  for (const char* name : {"balls", "rings", "tree", "gears"}) {
    testing::Prepared p(GenerateScene(name, 3000));
    const ImageView image = p.view();
    const std::vector<Ray> rays = testing::CameraRays(p.scene, 64);
    TraceOptions options;
    options.threads = 1;
    TraceStats stats;
    std::vector<RayCounters> per_ray;
    TraceRays(image, rays, options, &stats, &per_ray);
    std::vector<uint32_t> leaves(per_ray.size());
    for (size_t i = 0; i < per_ray.size(); ++i) leaves[i] = per_ray[i].leaves + per_ray[i].empty_skipped;
    const bench::WalkFloor floor = bench::MeasureWalkFloor(image, rays, leaves, 1);
    const double tracer_nodes = static_cast<double>(stats.totals.nodes) / static_cast<double>(rays.size());
    // The bare walk has no slack, so a split within a few ulps of a cell's
    // end may send it down one child where the tracer took both: a few
    // nodes in a thousand at most.
    EXPECT_NEAR(floor.nodes_per_ray, tracer_nodes, 0.002 * tracer_nodes) << name;
    EXPECT_GT(floor.nodes_per_ray, 3.0) << name;
  }
}

}  // namespace
}  // namespace kdrt
