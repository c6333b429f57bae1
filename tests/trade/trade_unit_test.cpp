// The pieces of `kdrt trade` on inputs whose answers are known by hand: the
// accuracy statistics, the PSNR, the recommendation, the SVG plot and the
// physical columns and plot.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "tests/common/read_file.h"
#include "trade/accuracy.h"
#include "trade/report.h"
#include "trade/svg_plot.h"
#include "trade/trade.h"

namespace kdrt::trade {
namespace {

Hit MakeHit(float t, uint32_t prim) {
  Hit h;
  h.t = t;
  h.prim = prim;
  return h;
}

TEST(TradeAccuracy, CountsAndPercentilesByHand) {
  // truth: 10 hits at t = 1 (prim i) and 2 misses.
  std::vector<Hit> truth, hits;
  for (uint32_t i = 0; i < 10; ++i) truth.push_back(MakeHit(1.0f, i));
  truth.push_back(Hit{});
  truth.push_back(Hit{});
  hits = truth;
  hits[0] = Hit{};                   // hit -> miss
  hits[10] = MakeHit(3.0f, 5);       // miss -> hit
  hits[1] = MakeHit(1.5f, 1);        // t error 0.5
  hits[2] = MakeHit(1.25f, 7);       // another triangle, t error 0.25
  const std::vector<float> rgb(3 * truth.size(), 0.5f);
  const Accuracy a = CompareWithTruth(hits, truth, rgb, rgb);
  EXPECT_EQ(a.rays, 12u);
  EXPECT_EQ(a.hitmiss, 2u);
  EXPECT_EQ(a.prim, 1u);
  EXPECT_EQ(a.common_hits, 9u);
  // Relative errors over the 9 common hits: seven 0, 0.25, 0.5.
  EXPECT_EQ(a.t_rel_p50, 0.0);
  EXPECT_EQ(a.t_rel_p99, 0.5);
  EXPECT_EQ(a.t_rel_max, 0.5);
  EXPECT_DOUBLE_EQ(a.MismatchFraction(), 3.0 / 12.0);
  EXPECT_TRUE(std::isinf(a.psnr_db));
}

TEST(TradeAccuracy, PsnrOfOneLevelEverywhereIs48Db) {
  // Every 8-bit value off by one: MSE 1, PSNR = 20 log10(255) = 48.13 dB.
  std::vector<float> a(300, 100.0f / 255.0f), b(300, 101.0f / 255.0f);
  EXPECT_NEAR(Psnr8(a, b), 20.0 * std::log10(255.0), 1e-9);
  // Values beyond [0,1] clamp, as in the PNG.
  EXPECT_TRUE(std::isinf(Psnr8(std::vector<float>(3, 2.0f), std::vector<float>(3, 1.0f))));
}

FormatResult Row(fp::Format f, uint64_t mismatches, uint64_t holes, int64_t cells) {
  FormatResult r;
  r.format = f;
  r.accuracy.rays = 1000;
  r.accuracy.hitmiss = mismatches;
  r.holes.holes = holes;
  if (cells > 0) {
    Area a;
    a.cells = cells;
    a.source = "cache";
    r.area = a;
  }
  return r;
}

TEST(TradeRecommend, SmallestFormatThatMeetsTheTargetWithoutHoles) {
  const std::vector<FormatResult> rows = {Row(fp::kFp32, 0, 0, 500), Row(fp::kFp24, 1, 0, 300),
                                          Row(fp::kBf16, 0, 3, 100), Row(fp::kFp16, 5, 0, 120)};
  EXPECT_EQ(Recommend(rows, 1e-3), "fp24");  // bf16 has holes, fp16 5e-3 > 1e-3
  EXPECT_EQ(Recommend(rows, 5e-3), "fp16");
  EXPECT_EQ(Recommend(rows, 0.0), "fp32");
  EXPECT_EQ(Recommend({Row(fp::kBf16, 9, 0, 0)}, 1e-3), "");
  // Equal widths: the smaller area wins.
  EXPECT_EQ(Recommend({Row(fp::kFp16, 0, 0, 120), Row(fp::kBf16, 0, 0, 100)}, 0.0), "bf16");
}

TEST(TradeSvg, OnePointPerFormatAndZeroOnTheLogFloor) {
  PlotSpec spec{"Error", "cells", "mismatch", false, true, "0",
                {{1000, 0.0, "fp32"}, {500, 1e-3, "fp16"}, {300, 0.2, "bf16<&>"}}};
  const std::string svg = ScatterSvg(spec);
  size_t points = 0;
  for (size_t at = svg.find("class=\"point\""); at != std::string::npos; at = svg.find("class=\"point\"", at + 1)) {
    ++points;
  }
  EXPECT_EQ(points, 3u);
  EXPECT_NE(svg.find("bf16&lt;&amp;&gt;"), std::string::npos);  // labels are escaped
  EXPECT_EQ(svg.find("bf16<&>"), std::string::npos);
  EXPECT_NE(svg.find(">0</text>"), std::string::npos);    // the zero's tick on the log axis
  EXPECT_NE(svg.find(">1e-3</text>"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
}

TEST(TradeJsonOutput, IdenticalImageIsNullPsnrAndMissingColumnsAreNull) {
  TradeResult t;
  t.scene = "s";
  FormatResult r = Row(fp::kFp32, 0, 0, 0);
  r.accuracy.psnr_db = std::numeric_limits<double>::infinity();
  t.formats.push_back(r);
  const nlohmann::json j = TradeJson(t);
  const nlohmann::json& f = j["formats"][0];
  EXPECT_TRUE(f["accuracy"]["psnr_db"].is_null());
  EXPECT_TRUE(f["accuracy"]["identical_image"].get<bool>());
  EXPECT_TRUE(f["cycles_per_ray"].is_null());
  EXPECT_TRUE(f["area"].is_null());
  EXPECT_TRUE(j["recommended"].is_null());
  EXPECT_EQ(f["E"], 8);
  EXPECT_EQ(f["M"], 23);
}


// A physical block as kdrt sim writes it (sim/phys.h), with the fields the
// trade report reads.
nlohmann::json Physical(double area_mm2, double clock_ns, double mrays, double per_mm2, double per_mm2_28nm) {
  return {{"library", "osu018"},
          {"clock_ns", clock_ns},
          {"area_mm2", {{"total", area_mm2}}},
          {"mrays_per_s", mrays},
          {"mrays_per_s_per_mm2", per_mm2},
          {"scaled", {{"28nm", {{"mrays_per_s_per_mm2", per_mm2_28nm}}}}}};
}

class TradePhysical : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("kdrt_trade_phys_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    t_.scene = "s";
    t_.formats = {Row(fp::kFp32, 0, 0, 500), Row(fp::kBf16, 2, 0, 300)};
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
  TradeResult t_;
};

TEST_F(TradePhysical, CsvAndPlotCarryTheSynthesizedFormatsAndNameTheOthers) {
  t_.formats[0].physical = Physical(80.5, 20.25, 1.5, 0.0186, 9.75);
  const std::string csv = TradeCsv(t_);
  EXPECT_NE(csv.find("rays_per_cycle_per_kcell,area_mm2,clock_ns,mrays_per_s,mrays_per_s_per_mm2,"
                     "mrays_per_s_per_mm2_28nm,warning"),
            std::string::npos);
  std::istringstream rows(csv);
  std::string header, fp32, bf16;
  std::getline(rows, header);
  std::getline(rows, fp32);
  std::getline(rows, bf16);
  EXPECT_NE(fp32.find(",80.5,20.25,1.5,0.0186,9.75,\""), std::string::npos) << fp32;
  EXPECT_NE(bf16.find(",,,,,\""), std::string::npos) << bf16;

  WriteHtml(t_, dir_.string());
  const std::string svg = kdrt::testing::ReadFile(dir_ / "error-vs-mrays-per-mm2.svg");
  size_t points = 0;
  for (size_t at = svg.find("class=\"point\""); at != std::string::npos; at = svg.find("class=\"point\"", at + 1)) {
    ++points;
  }
  EXPECT_EQ(points, 1u);  // fp32 only
  EXPECT_NE(svg.find("osu018"), std::string::npos);
  const std::string html = kdrt::testing::ReadFile(dir_ / "index.html");
  EXPECT_NE(html.find("error-vs-mrays-per-mm2.svg"), std::string::npos);
  EXPECT_NE(html.find("Not in the Mrays/s per mm^2 plot: bf16"), std::string::npos);
  EXPECT_NE(html.find("<td>0.0186</td><td>9.75</td>"), std::string::npos);
}

TEST_F(TradePhysical, NoSynthesisMeansNoPlotAndASentence) {
  WriteHtml(t_, dir_.string());
  EXPECT_FALSE(std::filesystem::exists(dir_ / "error-vs-mrays-per-mm2.svg"));
  const std::string html = kdrt::testing::ReadFile(dir_ / "index.html");
  EXPECT_EQ(html.find("error-vs-mrays-per-mm2.svg"), std::string::npos);
  EXPECT_NE(html.find("Not in the Mrays/s per mm^2 column (and no plot): fp32, bf16"), std::string::npos);
  EXPECT_FALSE(t_.formats[0].MraysPerSPerMm2().has_value());
}

}  // namespace
}  // namespace kdrt::trade
