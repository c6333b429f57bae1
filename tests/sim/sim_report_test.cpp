// The report's bound of the rays in flight (sim/sim_report.h,
// WindowBoundCycles).
#include "sim/sim_report.h"

#include <gtest/gtest.h>

#include <vector>

namespace kdrt::sim {
namespace {

RayCounters Ray(uint32_t nodes, uint32_t tests) {
  RayCounters c;
  c.nodes = nodes;
  c.tri_tests = tests;
  return c;
}

// Four rays that only traverse, then four that only test: the whole run's
// bound overlaps the two (max(40, 40) = 40 cycles), windows of four rays
// cannot (40 + 40), and windows of eight are the whole run again.
TEST(WindowBound, ChangingMixCostsEachWindowItsLargerUnit) {
  std::vector<RayCounters> rays(4, Ray(10, 0));
  rays.insert(rays.end(), 4, Ray(0, 10));
  EXPECT_EQ(WindowBoundCycles(rays, nullptr, 4), 80.0);
  EXPECT_EQ(WindowBoundCycles(rays, nullptr, 8), 40.0);
  EXPECT_EQ(WindowBoundCycles(rays, nullptr, 1000), 40.0);
  // One ray at a time: each ray's larger count.
  EXPECT_EQ(WindowBoundCycles(rays, nullptr, 1), 80.0);
  // Interleaved by the issue order, windows of two hold one of each.
  const std::vector<uint32_t> order = {0, 4, 1, 5, 2, 6, 3, 7};
  EXPECT_EQ(WindowBoundCycles(rays, &order, 2), 40.0);
  EXPECT_EQ(WindowBoundCycles(rays, &order, 1), 80.0);
  // An empty order (IssueOrder's "linear") is the rays' own.
  const std::vector<uint32_t> linear;
  EXPECT_EQ(WindowBoundCycles(rays, &linear, 4), 80.0);
}

// A last window shorter than the others counts too, and a window of 0 rays
// is "not reported".
TEST(WindowBound, LastPartialWindowAndZero) {
  const std::vector<RayCounters> rays = {Ray(3, 1), Ray(3, 1), Ray(1, 5)};
  EXPECT_EQ(WindowBoundCycles(rays, nullptr, 2), 6.0 + 5.0);
  EXPECT_EQ(WindowBoundCycles(rays, nullptr, 3), 7.0);
  EXPECT_EQ(WindowBoundCycles(rays, nullptr, 0), 0.0);
  EXPECT_EQ(WindowBoundCycles({}, nullptr, 4), 0.0);
}

}  // namespace
}  // namespace kdrt::sim
