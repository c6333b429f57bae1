// The shared L2 in front of the memory model (sim/l2_cache.h).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "sim/l2_cache.h"

namespace kdrt::sim {
namespace {

struct Fixture {
  std::vector<uint8_t> image;
  MemoryModel memory;
  SharedL2 l2;
  uint64_t cycle = 0;
  explicit Fixture(const L2Config& c, int cores = 2, MemoryConfig m = {1 << 16, 20, 16.0})
      : image(MakeImage()), memory(m), l2(c, (memory.LoadImage(image), memory), image, cores) {}
  static std::vector<uint8_t> MakeImage() {
    std::vector<uint8_t> b(4096);
    for (size_t i = 0; i < b.size(); ++i) b[i] = static_cast<uint8_t>(i * 7 + 3);
    return b;
  }
  // Runs cycles until core `core` gets a beat (at most `limit` cycles); the
  // cycle of the answer, or -1.
  int64_t WaitFor(int core, MemoryResponse* r, int limit = 1000) {
    for (int i = 0; i < limit; ++i, ++cycle) {
      if (l2.port(core).Respond(cycle, r)) return static_cast<int64_t>(cycle++);
    }
    return -1;
  }
};

L2Config Small() {
  L2Config c;
  c.size_bytes = 1024;  // 2 sets x 8 ways x 64 B
  c.ways = 8;
  c.line_bytes = 64;
  c.latency = 5;
  return c;
}

TEST(SharedL2, MissFetchesTheLineThenHitsAfterTheLatency) {
  Fixture f(Small());
  f.l2.port(0).Request(128 + 16, 7, f.cycle);
  MemoryResponse r;
  const int64_t miss_cycle = f.WaitFor(0, &r);
  // 4 beats from the memory: latency 20, one per cycle, answered the cycle after the last.
  EXPECT_EQ(miss_cycle, 20 + 3 + 1);
  EXPECT_EQ(r.tag, 7);
  EXPECT_EQ(r.addr, 144u);
  EXPECT_EQ(std::memcmp(r.data, f.image.data() + 144, 16), 0);
  EXPECT_EQ(f.memory.requests(), 4u);
  // Another beat of the same line, from core 1: a hit.
  const uint64_t asked = f.cycle;
  f.l2.port(1).Request(128 + 48, 9, asked);
  const int64_t hit_cycle = f.WaitFor(1, &r);
  EXPECT_EQ(static_cast<uint64_t>(hit_cycle), asked + 5);
  EXPECT_EQ(std::memcmp(r.data, f.image.data() + 176, 16), 0);
  EXPECT_EQ(f.memory.requests(), 4u) << "a hit reads nothing from the memory";
  EXPECT_EQ(f.l2.stats().hits, 1u);
  EXPECT_EQ(f.l2.stats().line_fills, 1u);
}

TEST(SharedL2, MissesToALineInFlightMerge) {
  Fixture f(Small());
  f.l2.port(0).Request(0, 1, 0);
  f.l2.port(1).Request(32, 2, 1);
  EXPECT_EQ(f.memory.requests(), 4u);
  EXPECT_EQ(f.l2.stats().merged, 1u);
  MemoryResponse r;
  EXPECT_GE(f.WaitFor(0, &r), 20);
  EXPECT_EQ(r.tag, 1);
  EXPECT_GE(f.WaitFor(1, &r), 20);
  EXPECT_EQ(r.tag, 2);
  EXPECT_EQ(std::memcmp(r.data, f.image.data() + 32, 16), 0);
}

TEST(SharedL2, LeastRecentlyUsedWayIsReplaced) {
  L2Config c = Small();
  c.size_bytes = 128;  // 1 set x 2 ways
  c.ways = 2;
  Fixture f(c);
  MemoryResponse r;
  for (uint64_t line : {0, 1, 0, 2}) {  // 0 is used again before 2 comes in: 1 goes
    f.l2.port(0).Request(line * 64, 0, f.cycle);
    ASSERT_GE(f.WaitFor(0, &r), 0);
  }
  const uint64_t before = f.memory.requests();
  f.l2.port(0).Request(0, 0, f.cycle);
  ASSERT_GE(f.WaitFor(0, &r), 0);
  EXPECT_EQ(f.memory.requests(), before) << "line 0 should still be there";
  f.l2.port(0).Request(64, 0, f.cycle);
  ASSERT_GE(f.WaitFor(0, &r), 0);
  EXPECT_EQ(f.memory.requests(), before + 4) << "line 1 should have been replaced";
}

TEST(SharedL2, OneBeatPerCorePerCycle) {
  Fixture f(Small());
  MemoryResponse r;
  f.l2.port(0).Request(0, 0, f.cycle);
  ASSERT_GE(f.WaitFor(0, &r), 0);
  const uint64_t asked = f.cycle;
  for (uint16_t b = 0; b < 4; ++b) f.l2.port(0).Request(16 * b, b, asked);
  for (uint16_t b = 0; b < 4; ++b) {
    ASSERT_EQ(f.WaitFor(0, &r), static_cast<int64_t>(asked + 5 + b));
    EXPECT_EQ(r.tag, b) << "oldest first";
  }
}

TEST(SharedL2, RefusesBadGeometryAndAddresses) {
  L2Config c = Small();
  c.size_bytes = 1000;
  MemoryModel m(MemoryConfig{});
  std::vector<uint8_t> image(64);
  EXPECT_THROW(SharedL2(c, m, image, 1), std::invalid_argument);
  c = Small();
  c.latency = 0;
  EXPECT_THROW(SharedL2(c, m, image, 1), std::invalid_argument);
  Fixture f(Small());
  EXPECT_THROW(f.l2.port(0).Request(8, 0, 0), MemoryError);
  EXPECT_THROW(f.l2.port(0).Request(1 << 16, 0, 0), MemoryError);
}

}  // namespace
}  // namespace kdrt::sim
