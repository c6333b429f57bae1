// The core parameter table (sim/core_params.def) against what it describes:
// rt_core.sv's own defaults, and the prebuilt models, which report the
// parameters they were really built with (`kdrt-sim-<fmt> --config`).
#include <gtest/gtest.h>

#include <cstdio>
#include <cctype>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "sim/core_params.h"
#include "tests/common/read_file.h"

namespace kdrt::sim {
namespace {

TEST(CoreParams, TableDefaultsAreTheRtlDefaults) {
  const std::string sv = kdrt::testing::ReadFile(std::string(KDRT_SOURCE_DIR) + "/rtl/rt_core.sv");
  ASSERT_FALSE(sv.empty());
  // A default may name an earlier parameter (the traversal's format is E, M).
  std::map<std::string, int> defaults;
  for (const CoreParam& p : kCoreParams) {
    const std::regex decl("parameter int unsigned " + std::string(p.sv_name) +
                          R"( /\*verilator public\*/ = (\d+|[A-Za-z]+))");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(sv, m, decl)) << p.sv_name << " is not a public parameter of rt_core";
    const std::string value = m[1];
    const int v = std::isdigit(static_cast<unsigned char>(value[0])) ? std::stoi(value) : defaults.at(value);
    EXPECT_EQ(v, p.default_value) << p.sv_name;
    defaults[p.sv_name] = v;
  }
}

TEST(CoreParams, KeyNamesEveryParameter) {
  CoreConfig c = DefaultConfig(fp::kFp32);
  EXPECT_EQ(c.Key(), "e8m23v8.23p8.23-t128-s32-n24-i24-a28-c512.64.256-r128-g4-w4-l1-f16");
  EXPECT_EQ(DefaultConfig(fp::kFp16).Key(), "e5m10v5.10p5.10-t128-s32-n24-i24-a28-c512.64.256-r128-g4-w4-l1-f16");
  c[kTriCacheLines] = 1024;
  c[kListCacheLines] = 256;
  EXPECT_EQ(c.Key(), "e8m23v8.23p8.23-t128-s32-n24-i24-a28-c512.256.1024-r128-g4-w4-l1-f16");
  EXPECT_EQ(c.Json()["TriCacheLines"], 1024);
  EXPECT_EQ(c.VerilatorDefines()[kTriCacheLines], "-GTriCacheLines=1024");
  c[kCacheTargets] = 1;
  EXPECT_EQ(c.Key(), "e8m23v8.23p8.23-t128-s32-n24-i24-a28-c512.256.1024-r128-g1-w4-l1-f16");
  EXPECT_EQ(c.VerilatorDefines()[kCacheTargets], "-GCacheTargets=1");
  c[kCacheWays] = 2;
  EXPECT_EQ(c.Key(), "e8m23v8.23p8.23-t128-s32-n24-i24-a28-c512.256.1024-r128-g1-w2-l1-f16");
  EXPECT_EQ(c.VerilatorDefines()[kCacheWays], "-GCacheWays=2");
  c[kListStream] = 0;
  EXPECT_EQ(c.Key(), "e8m23v8.23p8.23-t128-s32-n24-i24-a28-c512.256.1024-r128-g1-w2-l0-f16");
  EXPECT_EQ(c.VerilatorDefines()[kListStream], "-GListStream=0");
  EXPECT_EQ(c.Json()["ListStream"], 0);
  c[kListPrefetch] = 0;
  EXPECT_EQ(c.Key(), "e8m23v8.23p8.23-t128-s32-n24-i24-a28-c512.256.1024-r128-g1-w2-l0-f0");
  EXPECT_EQ(c.VerilatorDefines().back(), "-GListPrefetch=0");
  EXPECT_EQ(c.Json()["ListPrefetch"], 0);
}

// --image-format: a narrower image is its own model (the key's p part); the
// format's own image changes nothing; a wider one is refused.
TEST(CoreParams, ImageFormatOverridesImgEAndImgM) {
  ConfigOverrides ov;
  OverrideImageFormat(fp::kFp32, fp::kFp32, &ov);
  EXPECT_FALSE(ov.Has(kImgE));
  EXPECT_FALSE(ov.Has(kImgM));
  OverrideImageFormat(fp::kFp32, fp::kBf16, &ov);
  EXPECT_EQ(ov.value[kImgE], 8);
  EXPECT_EQ(ov.value[kImgM], 7);
  SceneRequirements req;
  const ConfigChoice c = ChooseConfig(fp::kFp32, req, ov, 0, false);
  EXPECT_FALSE(c.prebuilt);
  EXPECT_EQ(c.config.ImageFormat(), fp::kBf16);
  EXPECT_EQ(c.config.Format(), fp::kFp32);
  EXPECT_NE(c.config.Key().find("p8.7-"), std::string::npos) << c.config.Key();
  ConfigOverrides bad;
  EXPECT_THROW(OverrideImageFormat(fp::kFp16, fp::kBf16, &bad), InputError);  // more exponent bits
  EXPECT_THROW(OverrideImageFormat(fp::kBf16, fp::kFp32, &bad), InputError);
  CoreConfig wider = DefaultConfig(fp::kFp16);
  wider[kImgM] = 23;
  EXPECT_THROW(CheckConfigCovers(wider, req, 1u << 28, false), InputError);
}

// make build compiles the fp32 model; another preset's is checked when a run
// has built it (kdrt sim builds it on first use).
TEST(CoreParams, PrebuiltModelsAreBuiltWithTheDefaults) {
  for (const fp::Format& f : fp::Presets()) {
    const std::string model = std::string(KDRT_MODEL_DIR) + "/kdrt-sim-" + f.Name();
    if (f.Name() != "fp32" && !std::filesystem::exists(model)) continue;
    // The variable keeps a SystemC model from printing its banner on stdout.
    const std::string cmd = "SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1 " + model + " --config";
    FILE* pipe = popen(cmd.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string out;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
    ASSERT_EQ(pclose(pipe), 0) << cmd;
    EXPECT_EQ(nlohmann::json::parse(out), DefaultConfig(f).Json()) << cmd;
  }
}

}  // namespace
}  // namespace kdrt::sim
