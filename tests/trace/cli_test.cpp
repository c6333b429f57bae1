// End-to-end tests of the `kdrt` tool: outputs, and bad input giving a clear
// error (file, line, what), a non-zero exit and no partial output file.
#include <gtest/gtest.h>

#include "tests/common/run_kdrt.h"
#include "fp/format.h"

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/nff_writer.h"
#include "trace/images.h"
#include "trace/rays_file.h"
#include "trace_test_util.h"

namespace kdrt {
namespace {

namespace fs = std::filesystem;

using testing::RunKdrt;
using testing::RunResult;

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("kdrt_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& text) const {
    std::ofstream(Path(name)) << text;
    return Path(name);
  }
  // Nothing but the inputs is left in the directory.
  size_t FileCount() const {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir_)) n += e.is_regular_file();
    return n;
  }
  fs::path dir_;
};

TEST_F(Cli, HelpOnEveryCommand) {
  for (const char* cmd : {"", "render", "info", "gen", "sim", "sweep", "trade"}) {
    const RunResult r = RunKdrt(std::string(cmd) + " --help");
    EXPECT_EQ(r.exit_code, 0) << cmd;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << cmd;
  }
}

TEST_F(Cli, RenderWritesImageHitsAndJson) {
  const RunResult r = RunKdrt("render gen:room:500 --res 40x30 -o " + Path("a.png") + " --hits " + Path("a.exr") +
                          " --json " + Path("a.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Mrays/s"), std::string::npos);
  int w = 0, h = 0;
  const std::vector<Hit> hits = ReadHitBuffer(Path("a.exr"), &w, &h);
  EXPECT_EQ(w, 40);
  EXPECT_EQ(h, 30);
  size_t hit_count = 0;
  for (const Hit& hit : hits) {
    hit_count += hit.IsHit();
    if (!hit.IsHit()) {
      EXPECT_TRUE(std::isinf(hit.t));
    }
  }
  EXPECT_GT(hit_count, hits.size() / 2);  // the camera looks into a closed room
  std::ifstream json(Path("a.json"));
  std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"hits\": " + std::to_string(hit_count)), std::string::npos) << text;
  EXPECT_TRUE(fs::exists(Path("a.png")));
}

TEST_F(Cli, RayFileHitBufferIsInInputOrder) {
  std::vector<Ray> rays;
  for (int i = 0; i < 10; ++i) rays.push_back(Ray{{0.1f * i, 0.5f, 5.0f}, {0, 0, -1}, 0.0f, INFINITY});
  WriteRaysFile(Path("r.bin"), rays);
  const std::string nff = Write("q.nff", "p 4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n");
  const RunResult r = RunKdrt("render " + nff + " --rays " + Path("r.bin") + " --hits " + Path("r.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  int w = 0, h = 0;
  const std::vector<Hit> hits = ReadHitBuffer(Path("r.exr"), &w, &h);
  ASSERT_EQ(w, 10);
  ASSERT_EQ(h, 1);
  for (int i = 0; i < 10; ++i) {
    // x = 0.1 i: inside [0, 1] for i <= 9 (x = 0.9 at most), t = 5.
    EXPECT_TRUE(hits[i].IsHit()) << i;
    EXPECT_EQ(hits[i].t, 5.0f) << i;
  }
}

// The 102,400-triangle sphere of `kdrt rays --size 160`, rays at every vertex
// and edge: in fp16 one ray (|d_y / d_z| = 4e-5) fell through, its shear
// flushed to zero while the traversal kept the component (SetupRay now
// zeroes it). fp16 suffices for the scene, so every ray must hit.
TEST_F(Cli, FlushedShearLeavesNoHoleInAFineSphere) {
  ASSERT_EQ(RunKdrt("rays --mesh sphere --size 160 --scene-out " + Path("s.nff") + " --rays-out " + Path("s.rays"))
                .exit_code,
            0);
  const RunResult r = RunKdrt("render " + Path("s.nff") + " --rays " + Path("s.rays") + " --format fp16 -o " +
                              Path("s.png") + " --json " + Path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(Path("s.json")));
  EXPECT_EQ(j["rays"].get<int>(), 610560);
  EXPECT_EQ(j["hits"], j["rays"]);
  EXPECT_TRUE(j["warnings"].empty()) << j["warnings"];  // fp16 suffices (minimal e5m8)
}

TEST_F(Cli, FormatsRenderAndFp32EqualsDefault) {
  ASSERT_EQ(RunKdrt("render gen:balls:800 --res 32x32 -q --hits " + Path("d.exr")).exit_code, 0);
  ASSERT_EQ(RunKdrt("render gen:balls:800 --res 32x32 -q --format fp32 --hits " + Path("f.exr")).exit_code, 0);
  ASSERT_EQ(RunKdrt("render gen:balls:800 --res 32x32 -q --format fp16 --hits " + Path("h.exr")).exit_code, 0);
  int w, h;
  const auto d = ReadHitBuffer(Path("d.exr"), &w, &h), f = ReadHitBuffer(Path("f.exr"), &w, &h);
  ASSERT_EQ(d.size(), f.size());
  for (size_t i = 0; i < d.size(); ++i) EXPECT_EQ(std::memcmp(&d[i], &f[i], sizeof(Hit)), 0);
}

struct BadInput {
  const char* name;
  const char* file_text;  // written to bad.nff
  const char* extra_args;
  const char* expect;     // substring of the error
};

TEST_F(Cli, BadInputGivesClearErrorAndNoOutput) {
  const BadInput cases[] = {
      {"unknown keyword", "p 3\n0 0 0\n1 0 0\n0 1 0\nzz 1 2\n", "", "bad.nff:5"},
      {"nan coordinate", "p 3\n0 0 0\n1 nan 0\n0 1 0\n", "", "bad.nff:3"},
      {"inf coordinate", "p 3\n0 0 0\n1 0 0\n0 inf 0\n", "", "bad.nff:4"},
      {"truncated polygon", "p 4\n0 0 0\n1 0 0\n0 1 0\n", "", "bad.nff"},
      {"empty scene", "# nothing here\n", "", "bad.nff"},
      {"bad format", "p 3\n0 0 0\n1 0 0\n0 1 0\n", "--format fp99", "fp99"},
      {"bad accel", "p 3\n0 0 0\n1 0 0\n0 1 0\n", "--accel quadtree", "quadtree"},
      {"bad res", "p 3\n0 0 0\n1 0 0\n0 1 0\n", "--res 12by4", "--res"},
      {"bad isect", "p 3\n0 0 0\n1 0 0\n0 1 0\n", "--isect plucker", "plucker"},
      {"missing ray file", "p 3\n0 0 0\n1 0 0\n0 1 0\n", "--rays nonexistent.bin", "nonexistent.bin"},
  };
  for (const BadInput& c : cases) {
    const std::string scene = Write("bad.nff", c.file_text);
    const RunResult r = RunKdrt("render " + scene + " " + c.extra_args + " -o " + Path("out.png") + " --hits " +
                            Path("out.exr") + " --json " + Path("out.json"));
    EXPECT_NE(r.exit_code, 0) << c.name;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << c.name << ": " << r.output;
    EXPECT_EQ(FileCount(), 1u) << c.name << ": output left behind";
  }
}

// An image that cannot be written is named as the user named it (kdrt writes
// a temporary beside it first), and nothing is left behind.
TEST_F(Cli, UnwritableImageIsNamedAsGiven) {
  const std::string bad = Path("image.nosuchformat");
  const RunResult r = RunKdrt("render gen:room:100 --res 8x8 -o " + bad + " --json " + Path("out.json"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("kdrt: error: " + bad + ": cannot write image"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(".tmp"), std::string::npos) << r.output;
  EXPECT_EQ(FileCount(), 0u);
}

TEST_F(Cli, MissingSceneAndUnknownOption) {
  RunResult r = RunKdrt("render " + Path("nope.nff") + " -o " + Path("x.png"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("nope.nff"), std::string::npos) << r.output;
  r = RunKdrt("render gen:room:100 --no-such-option");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("no-such-option"), std::string::npos) << r.output;
  EXPECT_EQ(FileCount(), 0u);
}

TEST_F(Cli, BadRayFiles) {
  const std::string scene = Write("q.nff", "p 3\n0 0 0\n1 0 0\n0 1 0\n");
  auto write_raw = [&](const std::string& bytes) {
    std::ofstream(Path("r.bin"), std::ios::binary) << bytes;
  };
  auto header = [](uint32_t version, uint32_t count) {
    std::string h = "KDRTRAYS";
    h.append(reinterpret_cast<const char*>(&version), 4);
    h.append(reinterpret_cast<const char*>(&count), 4);
    return h;
  };
  auto ray = [](std::array<float, 8> f) { return std::string(reinterpret_cast<const char*>(f.data()), 32); };
  const float nan = NAN, inf = INFINITY;
  const std::pair<std::string, std::string> cases[] = {
      {"NOTRAYS!" + std::string(8, '\0'), "magic"},
      {header(3, 1) + ray({0, 0, 1, 0, 0, -1, 0, inf}), "version"},
      {header(2, 1) + std::string("\x07\0\0\0", 4) + ray({0, 0, 1, 0, 0, -1, 0, inf}), "query 7"},
      {header(2, 1) + std::string("\x01\0\0", 3), "ray file ends inside its header"},
      {header(1, 2) + ray({0, 0, 1, 0, 0, -1, 0, inf}), "bytes"},
      {header(1, 1) + ray({0, nan, 1, 0, 0, -1, 0, inf}), "ray 0: origin"},
      {header(1, 2) + ray({0, 0, 1, 0, 0, -1, 0, inf}) + ray({0, 0, 1, 0, inf, -1, 0, inf}), "ray 1: direction"},
      {header(1, 1) + ray({0, 0, 1, 0, 0, 0, 0, inf}), "zero"},
      {header(1, 1) + ray({0, 0, 1, 0, 0, -1, 5, 1}), "tmax"},
  };
  for (const auto& [bytes, expect] : cases) {
    write_raw(bytes);
    const RunResult r = RunKdrt("render " + scene + " --rays " + Path("r.bin") + " --hits " + Path("o.exr"));
    EXPECT_NE(r.exit_code, 0) << expect;
    EXPECT_NE(r.output.find(expect), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("r.bin"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(Path("o.exr")));
  }
}

TEST_F(Cli, InfoAndGen) {
  RunResult r = RunKdrt("gen tetra --size 300 -o " + Path("t.nff"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = RunKdrt("info " + Path("t.nff") + " --json " + Path("t.json") + " --image " + Path("t.img"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("memory image"), std::string::npos);
  EXPECT_NE(r.output.find("SAH cost"), std::string::npos);
  EXPECT_GT(fs::file_size(Path("t.img")), 128u);
}

// --min-split-gain reaches the builder (a smaller tree on gears, the same in
// render and sim), the JSON names the options, and a value outside [0, 1)
// is refused with a clear error and no output.
TEST_F(Cli, MinSplitGain) {
  // The JSON says which tree its numbers are for ("build").
  auto nodes = [&](const std::string& command, const std::string& extra, float gain) {
    const RunResult r =
        RunKdrt(command + " gen:gears:5000 --res 16x16 -q --json " + Path("g.json") + " " + extra);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    std::ifstream f(Path("g.json"));
    const nlohmann::json j = nlohmann::json::parse(f);
    EXPECT_EQ(j["build"]["min_split_gain"].get<float>(), gain) << command;
    EXPECT_EQ(j["build"]["method"], "sah") << command;
    EXPECT_GE(j["build"]["max_depth"].get<uint32_t>(), j["tree"]["max_depth"].get<uint32_t>()) << command;
    return j["tree"]["nodes"].get<uint64_t>();
  };
  const uint64_t plain = nodes("render", "--min-split-gain 0", 0.0f), gain = nodes("render", "--min-split-gain 0.1", 0.1f);
  EXPECT_LT(gain * 2, plain) << plain << " against " << gain;
  EXPECT_EQ(nodes("sim", "--model fast --min-split-gain 0.1", 0.1f), gain);
  // 0.1 is the default, in render and sim alike.
  EXPECT_EQ(nodes("render", "", 0.1f), gain);
  EXPECT_EQ(nodes("sim", "--model fast", 0.1f), gain);
  fs::remove(Path("g.json"));
  for (const char* bad : {"1", "-0.5", "nan"}) {
    const RunResult r =
        RunKdrt(std::string("render gen:gears:500 --min-split-gain ") + bad + " -o " + Path("x.png"));
    EXPECT_EQ(r.exit_code, 1) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("minimum split gain"), std::string::npos) << r.output;
    EXPECT_EQ(FileCount(), 0u) << bad;
  }
}

// Banded hoops leave large leaves at the depth limit (the levels went to
// empty space): kdrt info names the options that spend fewer or allow more;
// the same scene's tree built with the smaller bonus has few enough of them
// that the hint stays away.
TEST_F(Cli, InfoSaysWhenTheDepthLimitLeavesLargeLeaves) {
  const std::string hint = "of the leaves are large at the depth limit: a smaller --empty-bonus";
  RunResult r = RunKdrt("info gen:hoops:10000 --cone-aspect 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(hint), std::string::npos) << r.output;
  r = RunKdrt("info gen:hoops:10000 --cone-aspect 4 --empty-bonus 0.2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find(hint), std::string::npos) << r.output;
}

// 70,000 copies of one triangle make one leaf of 70,000: more than a packed
// 16-bit format's node can count (docs/memory-image.md). kdrt info says so
// and goes on; render in fp16 refuses with the reason and writes nothing,
// and traces the fp32 image when asked.
TEST_F(Cli, ATreeAPackedFormatCannotHoldIsSaid) {
  std::string nff = "v\nfrom 0.3 0.3 5\nat 0.3 0.3 0\nup 0 1 0\nangle 30\nhither 0.1\nresolution 8 8\n";
  for (int i = 0; i < 70000; ++i) nff += "p 3\n0 0 0\n1 0 0\n0 1 0\n";
  Write("big_leaf.nff", nff);
  RunResult r = RunKdrt("info " + Path("big_leaf.nff") + " --json " + Path("info.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("kdrt: note: no fp16 image: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("16-bit count of a fp16 image node"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" fp16 -"), std::string::npos) << r.output;
  // Why the leaf stays whole: no plane can split 70,000 copies.
  EXPECT_NE(r.output.find("large leaves   1 over 16 triangles: no plane 1 (largest 70000)"), std::string::npos)
      << r.output;
  std::ifstream f(Path("info.json"));
  const nlohmann::json j = nlohmann::json::parse(f);
  EXPECT_EQ(j["tree"]["leaf_causes"]["no_plane"]["largest"].get<uint32_t>(), 70000u);
  EXPECT_EQ(j["tree"]["leaf_causes"]["no_plane"]["large"].get<uint32_t>(), 1u);
  EXPECT_TRUE(j["images"]["bf16"].contains("error"));
  EXPECT_GT(j["images"]["fp24"]["bytes"].get<uint64_t>(), 0u);
  fs::remove(Path("info.json"));
  r = RunKdrt("render " + Path("big_leaf.nff") + " --format fp16 -o " + Path("x.png") + " --json " + Path("x.json"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("16-bit count of a fp16 image node"), std::string::npos) << r.output;
  EXPECT_EQ(FileCount(), 1u);  // the scene alone
  r = RunKdrt("render " + Path("big_leaf.nff") + " --format fp16 --image-format fp32 -q -o " + Path("x.png"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

// --image-format F narrower than --format: the image stores splits and
// vertices in F, the arithmetic stays --format's. A wider image is refused
// with nothing written.
TEST_F(Cli, NarrowerImageFormat) {
  RunResult r = RunKdrt("render gen:balls:800 --res 16x16 --image-format bf16 -o " + Path("a.png") + " --json " +
                        Path("a.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(Path("a.json")));
  EXPECT_EQ(j["format"], "fp32");
  EXPECT_EQ(j["image_format"], "bf16");
  EXPECT_LT(j["image_bytes"].get<uint64_t>(), j["fp32_image_bytes"].get<uint64_t>());
  EXPECT_GT(j["hits"].get<int>(), 0);
  const size_t files = FileCount();
  r = RunKdrt("render gen:balls:800 --res 16x16 --format fp16 --image-format bf16 -o " + Path("b.png"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("image format bf16 is wider than the datapath's fp16"), std::string::npos) << r.output;
  EXPECT_EQ(FileCount(), files);
  r = RunKdrt("render gen:balls:800 --res 16x16 --accel grid --image-format bf16 -o " + Path("c.png"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("only the kd-tree's memory image has a format"), std::string::npos) << r.output;
  EXPECT_EQ(FileCount(), files);
}

TEST_F(Cli, Fp64RendersWithoutWarnings) {
  const RunResult r = RunKdrt("render gen:balls:800 --res 32x32 --format fp64 -o " + Path("a.png") + " --json " +
                              Path("a.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("format         fp64"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(Path("a.json")));
  EXPECT_EQ(j["format"], "fp64");
  EXPECT_GT(j["hits"].get<int>(), 0);
  EXPECT_TRUE(j["warnings"].is_array());
  EXPECT_TRUE(j["warnings"].empty());
}

// A traversal in fp32 beside a test in bf16 or fp16 (model only): the cells
// cull almost as fp32's do, so both formats test far fewer triangles than
// when they traverse in themselves, fp16 within 2x of fp32; a traversal
// format narrower than the test's is refused with nothing written.
TEST_F(Cli, WiderTraversalCullsLikeFp32) {
  auto tests_per_ray = [&](const std::string& options) {
    const std::string json = Path("t.json");
    const RunResult r = RunKdrt("render gen:balls:10000 --res 48x48 -o " + Path("t.png") + " --json " + json + " " +
                                options);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
    EXPECT_GT(j["hits"].get<int>(), 500) << options;
    return std::make_pair(j["per_ray"]["tri_tests"].get<double>(), j["trav_format"].get<std::string>());
  };
  const double fp32 = tests_per_ray("--format fp32").first;
  for (const char* f : {"bf16", "fp16"}) {
    const auto alone = tests_per_ray(std::string("--format ") + f);
    const auto wide = tests_per_ray(std::string("--format ") + f + " --trav-format fp32");
    EXPECT_EQ(alone.second, f);
    EXPECT_EQ(wide.second, "fp32");
    EXPECT_LT(wide.first, alone.first) << f;
    if (std::string(f) == "fp16") {
      EXPECT_LT(wide.first, 2 * fp32);
    }
  }
  const RunResult bad = RunKdrt("render gen:balls:800 --res 8x8 --format fp24 --trav-format bf16 -o " + Path("b.png"));
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("traversal format bf16 does not hold every value of fp24"), std::string::npos)
      << bad.output;
  EXPECT_FALSE(fs::exists(Path("b.png")));
}

// The sphere of `kdrt rays` beside a triangle 1e5 away: its vertices
// collapse in fp16. render warns on stderr and in the JSON, --strict refuses
// with nothing written, fp32 has no warning. Every 16th ray.
TEST_F(Cli, FormatBelowTheRequirementWarnsOrWithStrictFails) {
  const testing::MeshAndRays m = testing::SphereInStadium(1e5);
  std::vector<Ray> some;
  for (size_t i = 0; i < m.rays.size(); i += 16) some.push_back(m.rays[i]);
  WriteNff(m.scene, Path("far.nff"));
  WriteRaysFile(Path("far.bin"), some);
  const std::string base = "render " + Path("far.nff") + " --rays " + Path("far.bin");

  RunResult r = RunKdrt(base + " --format fp16 --hits " + Path("h.exr") + " --json " + Path("h.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string prefix = "kdrt: warning: fp16 cannot represent this scene: ";
  const size_t at = r.output.find(prefix);
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_NE(r.output.find("vertices collapse onto another vertex", at), std::string::npos) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(Path("h.json")));
  ASSERT_EQ(j["warnings"].size(), 1u);
  const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
  EXPECT_EQ("kdrt: warning: " + j["warnings"][0].get<std::string>(), line);
  const std::string minimal = j["precision"]["minimal_format"];
  EXPECT_NE(line.find("(minimal format " + minimal + ")"), std::string::npos) << line;
  EXPECT_GT(j["precision"]["min_mantissa_bits"].get<int>(), fp::kFp16.m);

  const size_t before = FileCount();
  r = RunKdrt(base + " --format fp16 --strict --hits " + Path("s.exr") + " --json " + Path("s.json"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("kdrt: error: fp16 cannot represent this scene: "), std::string::npos) << r.output;
  EXPECT_EQ(FileCount(), before);

  r = RunKdrt(base + " --format fp32 --strict --json " + Path("f.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
  EXPECT_TRUE(nlohmann::json::parse(std::ifstream(Path("f.json")))["warnings"].empty());
}

// Secondary rays start on surfaces: each pass of a shaded frame gets its own
// precision check, named in the warning; --strict refuses it.
TEST_F(Cli, ShadowRaysGetTheirOwnPrecisionCheck) {
  const std::string base = "render gen:room:300 --res 8x8 --format e3m6 --shade -o " + Path("s.png");
  RunResult r = RunKdrt(base + " --json " + Path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(Path("s.json")));
  ASSERT_EQ(j["warnings"].size(), 2u) << r.output;
  const std::string shadow = j["warnings"][1];
  EXPECT_EQ(shadow.substr(shadow.size() - 13), "(shadow rays)") << shadow;
  EXPECT_NE(r.output.find("kdrt: warning: " + shadow), std::string::npos) << r.output;
  std::filesystem::remove(Path("s.png"));
  std::filesystem::remove(Path("s.json"));
  r = RunKdrt(base + " --strict --json " + Path("s.json"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(FileCount(), 0u);
}

TEST_F(Cli, InfoPrintsTheMinimalFormat) {
  const testing::MeshAndRays m = testing::SphereInStadium(1e5);
  WriteNff(m.scene, Path("far.nff"));
  WriteRaysFile(Path("far.bin"), m.rays);
  RunResult r = RunKdrt("info " + Path("far.nff") + " --rays " + Path("far.bin") + " --json " + Path("i.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json p = nlohmann::json::parse(std::ifstream(Path("i.json")))["precision"];
  EXPECT_NE(r.output.find("minimal format  " + p["minimal_format"].get<std::string>() + "\n"), std::string::npos)
      << r.output;
  EXPECT_EQ(p["minimal_format"], "e" + std::to_string(p["min_exponent_bits"].get<int>()) + "m" +
                                     std::to_string(p["min_mantissa_bits"].get<int>()));
  EXPECT_GT(p["min_mantissa_bits"].get<int>(), fp::kFp24.m);
  EXPECT_NE(r.output.find("minimal image   " + p["minimal_image_format"].get<std::string>() + " "),
            std::string::npos)
      << r.output;
  EXPECT_LE(p["min_image_mantissa_bits"].get<int>(), p["min_mantissa_bits"].get<int>());
  EXPECT_EQ(p["rays"], m.rays.size());
  EXPECT_GT(p["criteria"]["vertex_collapse"]["failing"]["fp16"].get<int>(), 0);
  EXPECT_LE(p["criteria"]["vertex_collapse"]["failing"]["fp16"], p["criteria"]["vertex_collapse"]["checked"]);
  // Without --rays: the camera's rays.
  r = RunKdrt("info gen:room:500");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("minimal format  e"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("camera rays"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace kdrt
