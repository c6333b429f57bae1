// The ray queue (sim/ray_queue.h): the ids it hands out and the issue orders
// of `kdrt sim --ray-order`.
#include "sim/ray_queue.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <set>

#include "common/error.h"

namespace kdrt::sim {
namespace {

TEST(IssueOrder, LinearIsTheListsOrder) { EXPECT_TRUE(IssueOrder("linear", 0, 100).empty()); }

// Z-order over a row-major frame: every id once, and each aligned 2^k x 2^k
// block of the frame is a run of 4^k consecutive positions.
TEST(IssueOrder, MortonVisitsAlignedBlocksInOneRun) {
  const uint32_t width = 16, height = 8;
  const std::vector<uint32_t> order = IssueOrder("morton", width, width * height);
  ASSERT_EQ(order.size(), width * height);
  std::vector<uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<uint32_t> ids(width * height);
  std::iota(ids.begin(), ids.end(), 0u);
  EXPECT_EQ(sorted, ids);
  EXPECT_EQ(order[0], 0u);
  EXPECT_EQ(order[1], 1u);       // (1, 0)
  EXPECT_EQ(order[2], width);    // (0, 1)
  EXPECT_EQ(order[3], width + 1);  // (1, 1)
  for (uint32_t block : {2u, 4u, 8u}) {
    for (size_t start = 0; start < order.size(); start += block * block) {
      std::set<uint32_t> xs, ys;
      for (size_t k = start; k < start + block * block; ++k) {
        xs.insert(order[k] % width / block);
        ys.insert(order[k] / width / block);
      }
      EXPECT_EQ(xs.size(), 1u) << "block " << block << " at " << start;
      EXPECT_EQ(ys.size(), 1u) << "block " << block << " at " << start;
    }
  }
}

// A frame whose sides are not powers of two still gets every id once.
TEST(IssueOrder, MortonOnAnyFrame) {
  const std::vector<uint32_t> order = IssueOrder("morton", 24, 24 * 20);
  std::vector<uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
}

TEST(IssueOrder, RefusesWhatIsNotAFrame) {
  EXPECT_THROW(IssueOrder("morton", 0, 16), InputError);
  EXPECT_THROW(IssueOrder("morton", 5, 16), InputError);
  EXPECT_THROW(IssueOrder("spiral", 4, 16), InputError);
}

// morton:K: the Z-order cut into K runs, one ray of each in turn; every
// ray once, and morton:1 is morton.
TEST(IssueOrder, MortonStreamsInterleaveRunsOfTheZOrder) {
  const std::vector<uint32_t> z = IssueOrder("morton", 24, 24 * 20);
  EXPECT_EQ(IssueOrder("morton:1", 24, 24 * 20), z);
  const std::vector<uint32_t> four = IssueOrder("morton:4", 24, 24 * 20);
  ASSERT_EQ(four.size(), z.size());
  const size_t run = z.size() / 4;  // 120
  for (size_t i = 0; i < run; ++i) {
    for (size_t s = 0; s < 4; ++s) ASSERT_EQ(four[4 * i + s], z[s * run + i]) << i << " " << s;
  }
  // Seven runs of a list of 10: runs of 2, the last one empty.
  const std::vector<uint32_t> ten = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  EXPECT_EQ(InterleaveStreams(ten, 7), (std::vector<uint32_t>{0, 2, 4, 6, 8, 1, 3, 5, 7, 9}));
  EXPECT_EQ(InterleaveStreams(ten, 3), (std::vector<uint32_t>{0, 4, 8, 1, 5, 9, 2, 6, 3, 7}));
  EXPECT_EQ(InterleaveStreams(ten, 1), ten);
  EXPECT_EQ(InterleaveStreams(ten, 20), ten);  // runs of one ray: the list's own order
  std::vector<uint32_t> sorted = IssueOrder("morton:256", 24, 24 * 20);
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
  EXPECT_EQ(MortonStreams("linear"), 0);
  EXPECT_EQ(MortonStreams("morton"), 1);
  EXPECT_EQ(MortonStreams("morton:16"), 16);
  for (const char* bad : {"morton:0", "morton:257", "morton:", "morton:x", "morton:-1", "morton:4x", "morton4"}) {
    EXPECT_THROW(MortonStreams(bad), InputError) << bad;
  }
}

// A secondary pass's rays by their pixels' Z-order: every ray once, the
// pixels in the frame's Z-order, and one pixel's rays (a shadow ray per
// light, AO samples) together in their list order.
TEST(PixelIssueOrder, SortsRaysByTheirPixelsZOrder) {
  const uint32_t width = 4;
  // Pixels of a 4x4 frame, some twice, some not at all (missed rays cast none).
  const std::vector<uint32_t> pixel = {15, 0, 5, 4, 4, 1, 10, 0};
  const std::vector<uint32_t> order = PixelIssueOrder(pixel, width);
  EXPECT_EQ(order, (std::vector<uint32_t>{1, 7, 5, 3, 4, 2, 6, 0}));
  const std::vector<uint32_t> frame = IssueOrder("morton", width, 16);
  std::vector<uint32_t> rank(16);
  for (uint32_t k = 0; k < 16; ++k) rank[frame[k]] = k;
  for (size_t k = 1; k < order.size(); ++k) {
    EXPECT_LE(rank[pixel[order[k - 1]]], rank[pixel[order[k]]]) << k;
  }
  EXPECT_TRUE(PixelIssueOrder({}, width).empty());
  EXPECT_THROW(PixelIssueOrder(pixel, 0), InputError);
}

// The queue hands out the order's ids, a chunk of positions per core.
TEST(RayQueue, HandsOutTheIssueOrderInChunks) {
  const std::vector<uint32_t> order = {3, 1, 0, 2, 5, 4};
  RayQueue q(order.size(), 2, 2, &order);
  size_t id = 0;
  ASSERT_TRUE(q.Take(0, &id));
  EXPECT_EQ(id, 3u);
  ASSERT_TRUE(q.Take(1, &id));
  EXPECT_EQ(id, 0u);  // core 1's chunk is positions 2 and 3
  ASSERT_TRUE(q.Take(0, &id));
  EXPECT_EQ(id, 1u);
  ASSERT_TRUE(q.Take(0, &id));
  EXPECT_EQ(id, 5u);  // core 0's next chunk: positions 4 and 5
  ASSERT_TRUE(q.Take(1, &id));
  EXPECT_EQ(id, 2u);
  EXPECT_TRUE(q.Exhausted(1));
  ASSERT_TRUE(q.Take(0, &id));
  EXPECT_EQ(id, 4u);
  EXPECT_FALSE(q.Take(0, &id));
}

}  // namespace
}  // namespace kdrt::sim
