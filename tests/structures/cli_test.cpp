// The command line of the software structures: `kdrt render --accel` with
// each of them gives the kd-tree's hit buffer, options they cannot honour are
// refused with a clear error and no output, and `kdrt compare-accel` reports
// every structure with consistent numbers.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/common/run_kdrt.h"

namespace kdrt {
namespace {

namespace fs = std::filesystem;
using testing::RunKdrt;

std::string TempDir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("kdrt_structures_cli_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream f(path);
  return nlohmann::json::parse(f);
}

class RenderAccel : public ::testing::TestWithParam<const char*> {};

TEST_P(RenderAccel, SameHitBufferAsTheKdTree) {
  const std::string accel = GetParam();
  const std::string dir = TempDir(accel);
  const std::string common = " gen:balls:3000 --res 64x64 --threads 2 -q";
  auto kd = RunKdrt("render" + common + " --accel sah -o " + dir + "/kd.png --hits " + dir + "/kd.exr");
  ASSERT_EQ(kd.exit_code, 0) << kd.output;
  auto s = RunKdrt("render" + common + " --accel " + accel + " -o " + dir + "/s.png --hits " + dir + "/s.exr --json " +
                   dir + "/s.json");
  ASSERT_EQ(s.exit_code, 0) << s.output;
  auto cmp = RunKdrt("compare " + dir + "/kd.exr " + dir + "/s.exr");
  EXPECT_EQ(cmp.exit_code, 0) << cmp.output;
  EXPECT_NE(cmp.output.find("identical"), std::string::npos) << cmp.output;

  const nlohmann::json j = ReadJson(dir + "/s.json");
  EXPECT_EQ(j["accel"], accel);
  ASSERT_TRUE(j.contains("structure")) << j.dump();
  EXPECT_FALSE(j.contains("tree"));
  EXPECT_GT(j["structure"]["nodes"].get<double>(), 0);
  EXPECT_GT(j["structure"]["memory_bytes"].get<double>(), 0);
  EXPECT_GT(j["per_ray"]["tri_tests"].get<double>(), 0);
  EXPECT_EQ(j["per_ray"]["mailbox_hits"].is_number(), accel != "bvh") << j["per_ray"].dump();

  // Shading traces the secondary passes through the same structure.
  auto shaded = RunKdrt("render" + common + " --accel " + accel + " --ao 1 -o " + dir + "/shaded.png --json " + dir +
                        "/shaded.json");
  ASSERT_EQ(shaded.exit_code, 0) << shaded.output;
  const nlohmann::json sj = ReadJson(dir + "/shaded.json");
  ASSERT_TRUE(sj.contains("passes"));
  EXPECT_GE(sj["passes"].size(), 3u);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Structures, RenderAccel, ::testing::Values("grid", "hgrid", "octree", "bvh"));

struct Refusal {
  const char* name;
  const char* args;
  const char* message;
};

class StructureOptionErrors : public ::testing::TestWithParam<Refusal> {};

TEST_P(StructureOptionErrors, RefusedWithoutOutput) {
  const Refusal& r = GetParam();
  const std::string dir = TempDir(std::string("err_") + r.name);
  std::string args = r.args;
  const size_t at = args.find("OUT");
  if (at != std::string::npos) args.replace(at, 3, dir + "/out");
  auto run = RunKdrt(args);
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find(r.message), std::string::npos) << run.output;
  EXPECT_TRUE(fs::is_empty(dir)) << "output left behind";
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, StructureOptionErrors,
    ::testing::Values(
        Refusal{"fp16", "render gen:balls:500 --accel grid --format fp16 -o OUT.png", "fp32 or fp64 only"},
        Refusal{"moller", "render gen:balls:500 --accel bvh --isect moller -o OUT.png", "watertight test only"},
        Refusal{"unknown", "render gen:balls:500 --accel kdgrid -o OUT.png", "expected sah, median, midpoint"},
        Refusal{"density", "render gen:balls:500 --accel grid --grid-density 0 -o OUT.png", "--grid-density"},
        Refusal{"density_nan", "render gen:balls:500 --accel hgrid --grid-density nan -o OUT.png", "--grid-density"},
        Refusal{"sim", "sim gen:balls:500 --accel octree --json OUT.json", "the software structures are for"},
        Refusal{"compare_format", "compare-accel gen:balls:500 --format bf16 --json OUT.json", "fp32 or fp64 only"},
        Refusal{"compare_kind", "compare-accel gen:balls:500 --accel sah,quadtree --json OUT.json", "quadtree"},
        Refusal{"compare_scene", "compare-accel gen:balls:500 /nonexistent/scene.nff --json OUT.json",
                "/nonexistent/scene.nff"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(CompareAccel, ReportsEveryStructureConsistently) {
  const std::string dir = TempDir("compare");
  auto run = RunKdrt("compare-accel gen:balls:2000 gen:tree:2000 --res 48x48 --json " + dir + "/c.json --html " + dir +
                     "/html");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const char* name : {"sah", "median", "midpoint", "grid", "hgrid", "octree", "bvh", "x best"}) {
    EXPECT_NE(run.output.find(name), std::string::npos) << name << "\n" << run.output;
  }
  const nlohmann::json j = ReadJson(dir + "/c.json");
  ASSERT_EQ(j["scenes"].size(), 2u);
  for (const auto& scene : j["scenes"]) {
    ASSERT_EQ(scene["rows"].size(), 7u);
    int best = 0;
    for (const auto& row : scene["rows"]) {
      const std::string s = row["structure"];
      EXPECT_EQ(row["mismatches"], 0) << s;
      EXPECT_EQ(row["rays"], 48 * 48) << s;
      EXPECT_GT(row["per_ray"]["tri_tests"].get<double>(), 0) << s;
      EXPECT_GT(row["memory_bytes"].get<double>(), 0) << s;
      EXPECT_GE(row["time_ratio_to_best"].get<double>(), 1.0) << s;
      best += row["time_ratio_to_best"].get<double>() == 1.0;
      const bool mailbox = s == "grid" || s == "hgrid" || s == "octree";
      EXPECT_EQ(row["per_ray"]["mailbox_hits"].is_number(), mailbox) << s;
    }
    EXPECT_GE(best, 1);
  }
  // The kd-tree row counts what kdrt render counts on the same rays.
  auto render = RunKdrt("render gen:balls:2000 --res 48x48 -q -o " + dir + "/r.png --json " + dir + "/r.json");
  ASSERT_EQ(render.exit_code, 0) << render.output;
  const nlohmann::json r = ReadJson(dir + "/r.json");
  EXPECT_DOUBLE_EQ(r["per_ray"]["tri_tests"].get<double>(),
                   j["scenes"][0]["rows"][0]["per_ray"]["tri_tests"].get<double>());
  EXPECT_EQ(r["hits"], j["scenes"][0]["rows"][0]["hits"]);

  std::ifstream html(dir + "/html/index.html");
  const std::string page((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
  for (const char* name : {"octree", "hgrid", "<svg", "balls"}) EXPECT_NE(page.find(name), std::string::npos) << name;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace kdrt
