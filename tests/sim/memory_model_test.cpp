// The memory model (sim/memory_model.h): latency, bandwidth, contents,
// out-of-range requests; and the model choice of `kdrt sim`
// (sim/core_params.h).
#include <gtest/gtest.h>

#include <vector>

#include "accel/kdtree.h"
#include "common/error.h"
#include "scenes/gen/generators.h"
#include "sim/memory_model.h"
#include "sim/core_params.h"
#include "trace/memory_image.h"

namespace kdrt::sim {
namespace {

std::vector<uint8_t> Counting(size_t n) {
  std::vector<uint8_t> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = static_cast<uint8_t>(i * 7 + 3);
  return v;
}

// Cycles at which each of `count` back-to-back requests (all made in cycle 0)
// is answered.
std::vector<uint64_t> AnswerCycles(const MemoryConfig& config, int count) {
  MemoryModel m(config);
  m.LoadImage(Counting(4096));
  for (int i = 0; i < count; ++i) m.Request(16u * i, static_cast<uint8_t>(i), 0);
  std::vector<uint64_t> when;
  MemoryResponse r;
  for (uint64_t c = 0; when.size() < static_cast<size_t>(count) && c < 100000; ++c) {
    if (m.Respond(c, &r)) {
      EXPECT_EQ(r.tag, static_cast<uint16_t>(when.size()));
      when.push_back(c);
    }
  }
  return when;
}

TEST(MemoryModel, AnswersAfterTheLatency) {
  MemoryConfig c;
  c.latency = 7;
  const std::vector<uint64_t> when = AnswerCycles(c, 1);
  ASSERT_EQ(when.size(), 1u);
  EXPECT_EQ(when[0], 7u);
}

TEST(MemoryModel, FullBandwidthGivesOneBeatPerCycle) {
  MemoryConfig c;
  c.latency = 5;
  c.bytes_per_cycle = 16;
  const std::vector<uint64_t> when = AnswerCycles(c, 10);
  ASSERT_EQ(when.size(), 10u);
  for (size_t i = 0; i < when.size(); ++i) EXPECT_EQ(when[i], 5 + i);
}

// Many requests outstanding at once (the queue grows past its first size
// while it wraps around): still answered in request order, with their tags
// and bytes.
TEST(MemoryModel, ManyOutstandingRequestsKeepTheirOrder) {
  MemoryConfig c;
  c.latency = 300;
  MemoryModel m(c);
  const std::vector<uint8_t> image = Counting(1 << 16);
  m.LoadImage(image);
  MemoryResponse r;
  uint64_t asked = 0, answered = 0;
  for (uint64_t cycle = 0; answered < 2000; ++cycle) {
    // Bursts of requests, then quiet spells, so the ring wraps and grows.
    for (int k = 0; k < (cycle % 500 < 100 ? 3 : 0) && asked < 2000; ++k, ++asked) {
      m.Request(16 * (asked % 4096), static_cast<uint16_t>(asked), cycle);
    }
    if (m.Respond(cycle, &r)) {
      ASSERT_EQ(r.tag, static_cast<uint16_t>(answered));
      ASSERT_EQ(r.addr, 16 * (answered % 4096));
      ASSERT_EQ(r.data[5], image[16 * (answered % 4096) + 5]);
      ++answered;
    }
    ASSERT_EQ(m.outstanding(), asked - answered);
  }
  EXPECT_GT(m.max_outstanding(), 200u);
}

TEST(MemoryModel, LowBandwidthSpacesTheBeats) {
  MemoryConfig c;
  c.latency = 3;
  c.bytes_per_cycle = 4;  // one beat every 4 cycles on average
  const std::vector<uint64_t> when = AnswerCycles(c, 21);
  ASSERT_EQ(when.size(), 21u);
  // Once the bucket's start-up credit is spent, 19 beats need 76 cycles.
  EXPECT_EQ(when.back() - when[1], 76u);
  for (size_t i = 1; i < when.size(); ++i) EXPECT_GE(when[i] - when[i - 1], 1u);
}

TEST(MemoryModel, FractionalBandwidthAveragesOut) {
  MemoryConfig c;
  c.latency = 1;
  c.bytes_per_cycle = 2.5;  // 6.4 cycles per beat
  const std::vector<uint64_t> when = AnswerCycles(c, 51);
  ASSERT_EQ(when.size(), 51u);
  const double span = static_cast<double>(when.back() - when.front());
  EXPECT_NEAR(span / 50.0, 6.4, 0.05);
}

TEST(MemoryModel, ReturnsTheImageBytesAndZerosBeyond) {
  MemoryConfig c;
  c.size_bytes = 1 << 16;
  c.latency = 1;
  MemoryModel m(c);
  const std::vector<uint8_t> image = Counting(40);  // ends inside the third beat
  m.LoadImage(image);
  m.Request(16, 1, 0);
  m.Request(32, 2, 0);
  m.Request(4096, 3, 0);
  MemoryResponse r;
  std::vector<MemoryResponse> got;
  for (uint64_t cycle = 0; cycle < 10; ++cycle) {
    if (m.Respond(cycle, &r)) got.push_back(r);
  }
  ASSERT_EQ(got.size(), 3u);
  for (int k = 0; k < 16; ++k) EXPECT_EQ(got[0].data[k], image[16 + k]);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(got[1].data[k], image[32 + k]);
  for (int k = 8; k < 16; ++k) EXPECT_EQ(got[1].data[k], 0);
  for (int k = 0; k < 16; ++k) EXPECT_EQ(got[2].data[k], 0);
  EXPECT_EQ(m.bytes_read(), 48u);
  EXPECT_EQ(m.requests(), 3u);
  EXPECT_EQ(m.max_outstanding(), 3u);
}

TEST(MemoryModel, RefusesRequestsOutsideTheMemory) {
  MemoryConfig c;
  c.size_bytes = 1024;
  MemoryModel m(c);
  EXPECT_NO_THROW(m.Request(1008, 0, 0));
  EXPECT_THROW(m.Request(1024, 0, 0), MemoryError);
  EXPECT_THROW(m.Request(8, 0, 0), MemoryError);  // misaligned
  try {
    m.Request(4096, 0, 5);
    FAIL();
  } catch (const MemoryError& e) {
    EXPECT_NE(std::string(e.what()).find("outside the modelled memory of 1024 bytes"), std::string::npos);
  }
  EXPECT_THROW(m.LoadImage(Counting(2048)), MemoryError);
  // The fit check alone (the fast model's, which loads no image).
  EXPECT_NO_THROW(m.CheckFits(1024));
  EXPECT_THROW(m.CheckFits(1025), MemoryError);
}

TEST(MemoryModel, RejectsBadConfigurations) {
  MemoryConfig c;
  c.latency = 0;
  EXPECT_THROW(MemoryModel{c}, std::invalid_argument);
  c = MemoryConfig{};
  c.bytes_per_cycle = 0;
  EXPECT_THROW(MemoryModel{c}, std::invalid_argument);
}

struct SceneImage {
  Scene scene;
  FramedImage image;
  const KdTree& tree = image.tree;
  const std::vector<uint8_t>& bytes = image.bytes;
  explicit SceneImage(const std::string& name, int size)
      : scene(GenerateScene(name, size)), image(BuildFramedImage(scene, BuildOptions{})) {}
};

TEST(SimConfig, RequirementsFollowTheImage) {
  const SceneImage s("balls", 300);
  const ImageView image(s.bytes);
  const SceneRequirements req = DeriveRequirements(image);
  EXPECT_EQ(req.stack_depth, std::max<int>(1, s.tree.stats.max_depth));
  EXPECT_EQ(req.image_bytes, s.bytes.size());
  EXPECT_LT(image.header().node_count - 1, uint64_t{1} << req.node_idx_bits);
  EXPECT_GE(image.header().node_count - 1, uint64_t{1} << (req.node_idx_bits - 1));
  EXPECT_LT(s.bytes.size() - 1, uint64_t{1} << req.addr_bits);
  EXPECT_EQ(req.tri_bytes, image.header().tri_count * 48u);
  EXPECT_EQ(BitsFor(0), 1);
  EXPECT_EQ(BitsFor(255), 8);
  EXPECT_EQ(BitsFor(256), 9);
}

TEST(SimConfig, PrebuiltModelWhenItCovers) {
  const SceneImage s("room", 300);
  const SceneRequirements req = DeriveRequirements(ImageView(s.bytes));
  const ConfigChoice c = ChooseConfig(fp::kBf16, req, ConfigOverrides{}, 0, false);
  EXPECT_TRUE(c.prebuilt);
  EXPECT_EQ(c.config, DefaultConfig(fp::kBf16));
  EXPECT_EQ(c.mem_size, uint64_t{1} << c.config[kAddrWidth]);
  // A non-preset format has no prebuilt model: one sized for the scene.
  const ConfigChoice d = ChooseConfig(fp::MakeFormat(6, 9), req, ConfigOverrides{}, 0, false);
  EXPECT_FALSE(d.prebuilt);
  EXPECT_EQ(d.config[kStackDepth], req.stack_depth);
  EXPECT_EQ(d.config[kNodeIdxWidth], req.node_idx_bits);
}

TEST(SimConfig, OverridesWinAndTooSmallOnesAreRefused) {
  const SceneImage s("balls", 300);
  const SceneRequirements req = DeriveRequirements(ImageView(s.bytes));
  ConfigOverrides ov;
  ov.value[kNodeCacheLines] = 128;
  const ConfigChoice c = ChooseConfig(fp::kFp32, req, ov, 0, false);
  EXPECT_FALSE(c.prebuilt);
  EXPECT_EQ(c.config[kNodeCacheLines], 128);
  EXPECT_EQ(c.config[kStackDepth], req.stack_depth);

  ov = ConfigOverrides{};
  ov.value[kStackDepth] = req.stack_depth - 1;
  try {
    ChooseConfig(fp::kFp32, req, ov, 0, false);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(">= " + std::to_string(req.stack_depth)), std::string::npos);
  }
  EXPECT_EQ(ChooseConfig(fp::kFp32, req, ov, 0, /*allow_overflow=*/true).config[kStackDepth], req.stack_depth - 1);

  ov = ConfigOverrides{};
  EXPECT_THROW(ChooseConfig(fp::kFp32, req, ov, /*mem_size=*/req.image_bytes - 16, false), InputError);
  ov = ConfigOverrides{};
  ov.value[kAddrWidth] = req.addr_bits - 1;
  EXPECT_THROW(ChooseConfig(fp::kFp32, req, ov, 0, false), InputError);
  ov = ConfigOverrides{};
  ov.value[kTriCacheLines] = 48;  // not a power of two
  EXPECT_THROW(ChooseConfig(fp::kFp32, req, ov, 0, false), InputError);
  ov = ConfigOverrides{};
  ov.value[kCacheWays] = 3;  // not a power of two
  EXPECT_THROW(ChooseConfig(fp::kFp32, req, ov, 0, false), InputError);
  ov.value[kCacheWays] = 8;
  ov.value[kTriCacheLines] = 4;  // a set larger than the cache
  try {
    ChooseConfig(fp::kFp32, req, ov, 0, false);
    ADD_FAILURE() << "8 ways in a 4-line cache accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("more ways than the 4 triangle cache lines"), std::string::npos) << e.what();
  }
  ov.value[kTriCacheLines] = 8;
  EXPECT_EQ(ChooseConfig(fp::kFp32, req, ov, 0, false).config[kCacheWays], 8);
}

}  // namespace
}  // namespace kdrt::sim
