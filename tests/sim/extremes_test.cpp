// `kdrt extremes --reduced --sim`: the numerics suite through the reference
// tracer and the RTL core. The core must return the reference's records bit
// for bit on every case in every preset, and fp32 must leave no hole in any
// case: with the scene-relative frame (docs/dataflow.md step 0) the scales
// 1e-30 and 1e30 no longer under- or overflow the watertight test's products.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/common/run_kdrt.h"
#include "tests/common/test_cores.h"

namespace kdrt {
namespace {

namespace fs = std::filesystem;

// Runs `kdrt extremes ARGS -q --json F` (expecting success) and returns F's
// JSON, or no cases when it failed; `tag` keeps the file of each test apart.
nlohmann::json RunExtremes(const std::string& args, const std::string& tag) {
  const fs::path json = fs::temp_directory_path() / ("kdrt_extremes" + tag + "_" + std::to_string(getpid()) + ".json");
  const testing::RunResult r = testing::RunKdrt("extremes " + args + " -q --json " + json.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  if (r.exit_code != 0) return {{"cases", nlohmann::json::array()}};
  std::ifstream f(json);
  const nlohmann::json j = nlohmann::json::parse(f);
  fs::remove(json);
  return j;
}

// One test per preset, so that ctest spreads the RTL runs over its jobs.
class ExtremesSim : public ::testing::TestWithParam<const char*> {};

TEST_P(ExtremesSim, SimMatchesRenderAndNoHolesWithoutAWarning) {
  const std::string format = GetParam();
  // The small core for the presets other than fp32 (tests/common/test_cores.h):
  // its pinned widths fit every case, so one model serves them all. The case
  // with the most rays (12,480 at a dense sphere) takes most of a run's time
  // on the default core and in bf16, whose leaves there are largest: it runs
  // in fp24 and fp16, and in every preset with KDRT_LONG=1.
  const bool all_cases = testing::LongRun() || format == "fp24" || format == "fp16";
  const nlohmann::json j = RunExtremes("--reduced --sim --formats " + format + testing::CoreFor(format) +
                                           (all_cases ? "" : " --cases '^(?!dense sphere)'"),
                                       "_sim_" + format);
  ASSERT_GE(j["cases"].size(), all_cases ? 20u : 19u);
  EXPECT_EQ(std::count_if(j["cases"].begin(), j["cases"].end(),
                          [](const nlohmann::json& c) { return c["case"] == "dense sphere, far rays"; }),
            all_cases ? 1 : 0);
  for (const nlohmann::json& c : j["cases"]) {
    const std::string name = c["case"];
    EXPECT_GT(c["rays"].get<int>(), 0) << name;
    ASSERT_TRUE(c["formats"].contains(format)) << name;
    for (const auto& [f, cell] : c["formats"].items()) {
      EXPECT_EQ(cell["sim_mismatch"].get<int>(), 0) << name << " " << f << ": kdrt sim differs from render";
      // Where the precision analysis says the format suffices, no ray leaks.
      if (cell["warning"].get<std::string>().empty()) {
        EXPECT_EQ(cell["holes"].get<int>(), 0) << name << " " << f;
      }
    }
    if (format == "fp32") {
      EXPECT_EQ(c["formats"]["fp32"]["holes"].get<int>(), 0) << name;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Presets, ExtremesSim, ::testing::Values("fp32", "fp24", "bf16", "fp16"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

// A traversal in fp32 beside a test in a narrower format (model only): its
// slack covers the test's rounding, so no must-hit ray leaks where the
// format suffices.
TEST(Extremes, WiderTraversalLeavesNoHoleWithoutAWarning) {
  const nlohmann::json j = RunExtremes("--reduced --formats fp24,bf16,fp16 --trav-format fp32", "_trav");
  EXPECT_EQ(j["trav_format"], "fp32");
  ASSERT_GE(j["cases"].size(), 20u);
  int checked = 0;
  for (const nlohmann::json& c : j["cases"]) {
    for (const auto& [format, cell] : c["formats"].items()) {
      if (!cell["warning"].get<std::string>().empty()) continue;
      EXPECT_EQ(cell["holes"].get<int>(), 0) << c["case"] << " " << format << " traversed in fp32";
      ++checked;
    }
  }
  EXPECT_GE(checked, 40);
}

// An fp32 datapath reading each narrower preset's image (--datapath, model
// only; kdrt sim --image-format is checked in sim_cli_test): the arithmetic
// is fp32's, so no must-hit ray leaks wherever the stored scene suffices,
// and the warnings name the image's format.
TEST(Extremes, NarrowerImageLeavesNoHoleWithoutAWarning) {
  const nlohmann::json j = RunExtremes("--reduced --formats fp24,bf16,fp16 --datapath fp32", "_img");
  EXPECT_EQ(j["datapath"], "fp32");
  ASSERT_GE(j["cases"].size(), 20u);
  int checked = 0, warned = 0;
  for (const nlohmann::json& c : j["cases"]) {
    for (const auto& [format, cell] : c["formats"].items()) {
      const std::string warning = cell["warning"];
      if (!warning.empty()) {
        EXPECT_EQ(warning.rfind("fp32 with its image in " + format + " cannot represent", 0), 0u) << warning;
        ++warned;
        continue;
      }
      EXPECT_EQ(cell["holes"].get<int>(), 0) << c["case"] << " " << format << " image, fp32 datapath";
      ++checked;
    }
  }
  EXPECT_GE(checked, 40);
  EXPECT_GT(warned, 0);
  const testing::RunResult bad = testing::RunKdrt("extremes --reduced --formats bf16 --datapath fp16 -q");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("image format bf16 is wider than the datapath's fp16"), std::string::npos) << bad.output;
}

TEST(Extremes, RefusesATraversalFormatNarrowerThanTheTest) {
  const testing::RunResult r = testing::RunKdrt("extremes --reduced --formats fp32 --trav-format fp16 -q");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("does not hold every value of fp32"), std::string::npos) << r.output;
  const testing::RunResult s = testing::RunKdrt("extremes --reduced --formats fp16 --trav-format fp64 --sim -q");
  EXPECT_NE(s.exit_code, 0);
  EXPECT_NE(s.output.find("the RTL traverses in at most e8m23 (fp32)"), std::string::npos) << s.output;
}

}  // namespace
}  // namespace kdrt
