// End-to-end tests of `kdrt trade`: its accuracy numbers against an
// independent computation from the hit buffers `kdrt render` writes, its
// cycles against `kdrt sim`, its refusal of bad input with nothing written,
// and its page as a person sees it (a headless Chromium screenshot).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "scenes/gen/generators.h"
#include "tests/common/run_kdrt.h"
#include "trace/images.h"

namespace kdrt {
namespace {

namespace fs = std::filesystem;
using testing::RunKdrt;
using testing::RunResult;

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream f(path);
  return nlohmann::json::parse(f);
}

class TradeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    dir_ = fs::temp_directory_path() / ("kdrt_trade_" + name + "_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  size_t FileCount() const { return std::distance(fs::directory_iterator(dir_), fs::directory_iterator()); }
  fs::path dir_;
};

struct Direct {
  uint64_t hitmiss = 0, prim = 0, common = 0;
  double t_rel_max = 0;
};

// The oracle: the two hit buffers compared here, without trade's code.
Direct CompareBuffers(const std::string& a_path, const std::string& truth_path) {
  int w = 0, h = 0, tw = 0, th = 0;
  const std::vector<Hit> a = ReadHitBuffer(a_path, &w, &h);
  const std::vector<Hit> truth = ReadHitBuffer(truth_path, &tw, &th);
  EXPECT_EQ(a.size(), truth.size());
  Direct d;
  for (size_t i = 0; i < std::min(a.size(), truth.size()); ++i) {
    if (a[i].IsHit() != truth[i].IsHit()) {
      ++d.hitmiss;
    } else if (a[i].IsHit()) {
      ++d.common;
      if (a[i].prim != truth[i].prim) ++d.prim;
      d.t_rel_max = std::max(d.t_rel_max, std::fabs(double(a[i].t) - truth[i].t) / std::fabs(double(truth[i].t)));
    }
  }
  return d;
}

// Every generator: fp32's hit/miss disagreement with fp64 is at most 1e-4,
// and the bf16 and fp16 rows are what a direct comparison of their hit
// buffers with the fp64 buffer gives.
TEST_F(TradeCli, AccuracyAgreesWithDirectHitBufferComparisonOnEveryGenerator) {
  const std::vector<std::string> gens = GeneratorNames();
  for (size_t g = 0; g < gens.size(); ++g) {
    const std::string& gen = gens[g];
    SCOPED_TRACE(gen);
    const std::string scene = "gen:" + gen + ":3000", res = "--res 112x112";
    const RunResult r =
        RunKdrt("trade " + scene + " " + res + " --formats fp32,bf16,fp16 --no-area -q --json " + Path("t.json"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json j = ReadJson(Path("t.json"));
    ASSERT_EQ(j["formats"].size(), 3u);
    ASSERT_EQ(RunKdrt("render " + scene + " " + res + " --format fp64 -q -o " + Path("fp64.png") + " --hits " +
                      Path("fp64.exr"))
                  .exit_code,
              0);
    for (size_t k = 0; k < j["formats"].size(); ++k) {
      const nlohmann::json& row = j["formats"][k];
      const std::string f = row["format"];
      SCOPED_TRACE(f);
      ASSERT_EQ(RunKdrt("render " + scene + " " + res + " --format " + f + " -q -o " + Path(f + ".png") +
                        " --hits " + Path(f + ".exr"))
                    .exit_code,
                0);
      const Direct d = CompareBuffers(Path(f + ".exr"), Path("fp64.exr"));
      const nlohmann::json& acc = row["accuracy"];
      EXPECT_EQ(acc["hitmiss_rays"].get<uint64_t>(), d.hitmiss);
      EXPECT_EQ(acc["prim_rays"].get<uint64_t>(), d.prim);
      EXPECT_EQ(acc["common_hits"].get<uint64_t>(), d.common);
      EXPECT_DOUBLE_EQ(acc["hitmiss_mismatch"].get<double>(), double(d.hitmiss) / j["rays"].get<double>());
      EXPECT_NEAR(acc["t_rel_max"].get<double>(), d.t_rel_max, 1e-12 + 1e-9 * d.t_rel_max);
      if (f == "fp32") {
        EXPECT_LE(acc["hitmiss_mismatch"].get<double>(), 1e-4);
      }
      // The memory column is the format's own image, as kdrt info sizes it
      // (one format per generator, in turn: kdrt info builds the tree again).
      if (k != g % j["formats"].size()) continue;
      ASSERT_EQ(RunKdrt("info " + scene + " --format " + f + " --json " + Path("info.json")).exit_code, 0);
      EXPECT_EQ(row["memory_bytes"].get<uint64_t>(), ReadJson(Path("info.json"))["image_bytes"].get<uint64_t>());
    }
  }
}

// With --sim and no subsample, the cycle columns are kdrt sim's on the same
// rays; with --sim-rays the subsample is said on stderr and in the JSON.
// The simulated configuration is kdrt sim's; with no synthesis of it (an
// empty KDRT_PHYS_DIR) there is no physical cost, and a note names its key.
TEST_F(TradeCli, CyclesAreKdrtSimsAndASubsampleIsSaid) {
  const std::string scene = "gen:balls:800 --res 24x24";
  fs::create_directories(Path("phys"));
  const std::string env = "env KDRT_PHYS_DIR=" + Path("phys") + " " + KDRT_BIN + " ";
  RunResult r =
      testing::RunCommand(env + "trade " + scene + " --formats fp32 --no-area --sim -q --json " + Path("t.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = testing::RunCommand(env + "sim " + scene + " --format fp32 -q -o " + Path("s.png") + " --json " + Path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json t = ReadJson(Path("t.json")), s = ReadJson(Path("s.json"));
  EXPECT_EQ(t["formats"][0]["model"]["key"], s["model"]["key"]);
  EXPECT_TRUE(t["formats"][0]["physical"].is_null());
  EXPECT_TRUE(s["physical"].is_null());
  bool no_synthesis = false;
  for (const auto& note : t["notes"]) {
    no_synthesis |= note.get<std::string>().find("no synthesis of the simulated core of fp32 (" +
                                                 s["model"]["key"].get<std::string>() + ")") != std::string::npos;
  }
  EXPECT_TRUE(no_synthesis) << t["notes"].dump();
  EXPECT_EQ(t["formats"][0]["cycles_per_ray"].get<double>(), s["cycles_per_ray"].get<double>());
  EXPECT_EQ(t["formats"][0]["efficiency"].get<double>(), s["efficiency"].get<double>());
  EXPECT_EQ(t["formats"][0]["bytes_per_ray"].get<double>(), s["memory"]["bytes_per_ray"].get<double>());
  EXPECT_EQ(t["sim_stride"].get<int>(), 1);

  r = RunKdrt("trade " + scene + " --formats fp32 --no-area --sim --sim-rays 100 -q --json " + Path("u.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("subsample"), std::string::npos) << r.output;
  const nlohmann::json u = ReadJson(Path("u.json"));
  EXPECT_EQ(u["sim_stride"].get<int>(), 6);  // ceil(576 / 100)
  EXPECT_EQ(u["formats"][0]["sim_rays"].get<int>(), 96);
  bool said = false;
  for (const auto& note : u["notes"]) said |= note.get<std::string>().find("subsample") != std::string::npos;
  EXPECT_TRUE(said) << u["notes"].dump();
}

TEST_F(TradeCli, RefusesBadInputWithExitOneAndWritesNothing) {
  fs::create_directories(Path("full"));
  std::ofstream(Path("full/keep.txt")) << "user data\n";
  std::ofstream(Path("afile")) << "x\n";
  const std::string base = "trade gen:balls:200 --res 8x8 --no-area -q --json " + Path("out.json") + " ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--formats fp99", "fp99"},
      {"--formats e9m5", "e9m5"},
      {"--formats e5m24", "e5m24"},
      {"--formats fp32,fp32", "twice"},
      {"--formats ,", "empty"},
      {"--target-mismatch 2", "fraction"},
      {"--csv /nonexistent-dir/t.csv", "does not exist"},
      {"--html " + Path("afile"), "not a directory"},
      {"--html " + Path("full"), "refusing"},
      {"--html /nonexistent-dir/page", "does not exist"},
  };
  const size_t before = FileCount();
  for (const auto& [option, message] : cases) {
    SCOPED_TRACE(option);
    const RunResult r = RunKdrt(base + option);
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(Path("out.json")));
    EXPECT_EQ(FileCount(), before);
  }
  EXPECT_TRUE(fs::exists(Path("full/keep.txt")));
}

// A format whose packed image cannot hold the tree (a leaf of 70,000
// triangles: more than a 16-bit format's node counts) is left out with a
// note; the others are still traded. With nothing left, it is an error.
TEST_F(TradeCli, AFormatThatCannotPackIsLeftOutAndSaid) {
  std::string nff = "v\nfrom 0.3 0.3 5\nat 0.3 0.3 0\nup 0 1 0\nangle 30\nhither 0.1\nresolution 8 8\n";
  for (int i = 0; i < 70000; ++i) nff += "p 3\n0 0 0\n1 0 0\n0 1 0\n";
  std::ofstream(Path("big_leaf.nff")) << nff;
  const std::string base = "trade " + Path("big_leaf.nff") + " --res 4x4 --no-area -q --json " + Path("t.json");
  RunResult r = RunKdrt(base + " --formats fp24,fp16");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("kdrt: note: fp16 is left out: "), std::string::npos) << r.output;
  std::ifstream f(Path("t.json"));
  const nlohmann::json j = nlohmann::json::parse(f);
  ASSERT_EQ(j["formats"].size(), 1u);
  EXPECT_EQ(j["formats"][0]["format"], "fp24");
  bool noted = false;
  for (const auto& n : j["notes"]) noted |= n.get<std::string>().rfind("fp16 is left out", 0) == 0;
  EXPECT_TRUE(noted) << j["notes"];
  fs::remove(Path("t.json"));
  r = RunKdrt(base + " --formats fp16");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("no format to compare"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(Path("t.json")));
}

// A second run replaces the page of the first, and leaves no temporaries.
TEST_F(TradeCli, HtmlPageIsWrittenWholeAndReplacesAnEarlierPage) {
  const std::string cmd = "trade gen:room:300 --res 16x16 --formats fp32,fp16 --no-area -q --html " + Path("page");
  ASSERT_EQ(RunKdrt(cmd).exit_code, 0);
  std::ofstream(Path("page/stale.txt")) << "from before\n";
  ASSERT_EQ(RunKdrt(cmd).exit_code, 0);
  for (const char* f : {"index.html", "fp64.png", "fp32.png", "fp16.png", "fp32-diff.png", "fp16-diff.png",
                        "error-vs-area.svg", "cycles-vs-area.svg"}) {
    EXPECT_TRUE(fs::exists(Path("page") + "/" + f)) << f;
  }
  EXPECT_FALSE(fs::exists(Path("page/stale.txt")));
  EXPECT_EQ(FileCount(), 1u);  // only page/: no temporary directories beside it
}

// Counts the pixels of one colour (within 2 of each channel) in an RGB(A) PNG.
size_t CountColour(const std::string& png, int r, int g, int b) {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> px;
  try {
    px = ReadImage8(png, &width, &height, &channels);
  } catch (const InputError&) {
    return 0;
  }
  size_t n = 0;
  for (size_t i = 0; i + 2 < px.size(); i += channels) {
    n += std::abs(px[i] - r) <= 2 && std::abs(px[i + 1] - g) <= 2 && std::abs(px[i + 2] - b) <= 2;
  }
  return n;
}

std::string Screenshot(const std::string& page, const std::string& png) {
  const std::string cmd = "chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1500,2200 "
                          "--screenshot=" + png + " file://" + page + " > /dev/null 2>&1";
  return std::system(cmd.c_str()) == 0 && fs::exists(png) ? "" : "chromium failed: " + cmd;
}

// The page as a person sees it: the table's header colour, the plots'
// background and their points appear in a headless Chromium screenshot. With
// the plot files removed, the same check fails (the test can fail).
TEST_F(TradeCli, ChromiumScreenshotShowsTheTableAndThePlots) {
  ASSERT_EQ(system("command -v chromium > /dev/null"), 0) << "chromium is missing: run scripts/install-deps.sh";
  const RunResult r = RunKdrt("trade gen:balls:500 --res 32x32 --formats fp32,bf16,fp16 -q --html " + Path("page"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string page = fs::absolute(Path("page/index.html")).string();
  ASSERT_EQ(Screenshot(page, Path("shot.png")), "");
  EXPECT_GT(CountColour(Path("shot.png"), 0x1f, 0x4e, 0x79), 2000u) << "table header";
  EXPECT_GT(CountColour(Path("shot.png"), 0xf4, 0xf8, 0xfc), 20000u) << "plot backgrounds";
  EXPECT_GT(CountColour(Path("shot.png"), 0xd6, 0x27, 0x28), 3 * 2 * 50u) << "plot points";

  fs::remove(Path("page/error-vs-area.svg"));
  fs::remove(Path("page/cycles-vs-area.svg"));
  ASSERT_EQ(Screenshot(page, Path("shot2.png")), "");
  EXPECT_LT(CountColour(Path("shot2.png"), 0xf4, 0xf8, 0xfc), 100u);
  EXPECT_LT(CountColour(Path("shot2.png"), 0xd6, 0x27, 0x28), 10u);
}

}  // namespace
}  // namespace kdrt
