// `kdrt extremes --reduced --sim`: the numerics suite through the reference
// tracer and the RTL core. The core must return the reference's records bit
// for bit on every case in every preset, and fp32 must leave no hole in any
// case: with the scene-relative frame (docs/dataflow.md step 0) the scales
// 1e-30 and 1e30 no longer under- or overflow the watertight test's products.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/common/run_kdrt.h"

namespace kdrt {
namespace {

namespace fs = std::filesystem;

TEST(Extremes, SimMatchesRenderAndNoHolesWithoutAWarning) {
  const fs::path json = fs::temp_directory_path() / ("kdrt_extremes_" + std::to_string(getpid()) + ".json");
  const testing::RunResult r = testing::RunKdrt("extremes --reduced --sim -q --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream f(json);
  const nlohmann::json j = nlohmann::json::parse(f);
  fs::remove(json);
  ASSERT_GE(j["cases"].size(), 20u);
  for (const nlohmann::json& c : j["cases"]) {
    const std::string name = c["case"];
    EXPECT_GT(c["rays"].get<int>(), 0) << name;
    for (const auto& [format, cell] : c["formats"].items()) {
      EXPECT_EQ(cell["sim_mismatch"].get<int>(), 0) << name << " " << format << ": kdrt sim differs from render";
      // Where the precision analysis says the format suffices, no ray leaks.
      if (!cell.contains("warning")) {
        EXPECT_EQ(cell["holes"].get<int>(), 0) << name << " " << format;
      }
    }
    EXPECT_EQ(c["formats"]["fp32"]["holes"].get<int>(), 0) << name;
  }
}

}  // namespace
}  // namespace kdrt
