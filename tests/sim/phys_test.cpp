// The physical cost in `kdrt sim`'s report and `kdrt synth` (sim/phys.h):
// a configuration without a synthesis reports none (never another
// configuration's figures), a broken core.json is refused naming the file,
// `kdrt synth` computes the model key kdrt sim runs, and the physical
// block's arithmetic (Mrays/s, per mm^2, node scaling) from its inputs.
//
// Every test points KDRT_PHYS_DIR at its own temporary directory, so none
// reads or writes the build's phys/ cache.
//
// KDRT_LONG=1 adds two real syntheses (scripts/synth-core.sh, minutes each
// on 2 cores): a small core with 4 and with 8 threads must report different
// unit parameters and areas.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "sim/core_params.h"
#include "sim/phys.h"
#include "tests/common/run_kdrt.h"

namespace kdrt {
namespace {

namespace fs = std::filesystem;

using testing::RunResult;

bool LongRun() {
  const char* v = std::getenv("KDRT_LONG");
  return v && std::string(v) == "1";
}

nlohmann::json ReadJsonFile(const std::string& path) {
  std::ifstream f(path);
  return nlohmann::json::parse(f);
}

class PhysCli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    dir_ = fs::temp_directory_path() / ("kdrt_phys_" + name + "_" + std::to_string(getpid()));
    fs::create_directories(dir_ / "phys");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string PhysDir() const { return Path("phys"); }
  // kdrt with KDRT_PHYS_DIR at this test's directory.
  RunResult Kdrt(const std::string& args) const {
    return testing::RunCommand("env KDRT_PHYS_DIR=" + PhysDir() + " " + std::string(KDRT_BIN) + " " + args);
  }
  // The model key `kdrt sim SCENE OPTS --which-model` names ("" and a test
  // failure when it names none).
  std::string SimModelKey(const std::string& scene_and_opts) const {
    const RunResult w = Kdrt("sim " + scene_and_opts + " --which-model");
    EXPECT_EQ(w.exit_code, 0) << w.output;
    const size_t at = w.output.find("model          ");
    if (at == std::string::npos) {
      ADD_FAILURE() << "no model line: " << w.output;
      return "";
    }
    return w.output.substr(at + 15, w.output.find(' ', at + 15) - at - 15);
  }
  // The path kdrt sim reads the synthesis of KEY from, its directory made.
  std::string CoreJsonPath(const std::string& key) const {
    fs::create_directories(fs::path(PhysDir()) / key);
    return (fs::path(PhysDir()) / key / "core.json").string();
  }
  fs::path dir_;
};

const char* const kScene = "gen:room:300 --res 8x8";

// A well-formed core.json of CONFIG's parameters: one unit, clock 5.1 ns.
nlohmann::json MinimalCoreJson(const sim::CoreConfig& config) {
  nlohmann::json j = {{"library", "osu018"},
                      {"clock_ns", 5.1},
                      {"critical_unit", "rt_x"},
                      {"area_um2", {{"logic", 1}, {"sram", 0}, {"total", 1}}},
                      {"units", {{{"unit", "rt_x"}, {"count", 1}, {"area_um2", 1}, {"flip_flops", 0},
                                  {"crit_ns", 5.1}}}}};
  for (int i = 0; i < sim::kParamCount; ++i) j["params"][sim::kCoreParams[i].sv_name] = config.value[i];
  return j;
}

// No synthesis of the configuration: "physical": null, and the table and
// stderr say which key has none and how to make it; nothing is written
// into the phys directory.
TEST_F(PhysCli, NoSynthesisReportsNull) {
  const RunResult r = Kdrt(std::string("sim ") + kScene + " --model fast -o " + Path("x.png") + " --json " +
                           Path("x.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = ReadJsonFile(Path("x.json"));
  ASSERT_TRUE(j.contains("physical"));
  EXPECT_TRUE(j["physical"].is_null());
  const std::string key = j["model"]["key"].get<std::string>();
  const std::string line = "physical: no synthesis of this configuration (" + key + ")";
  // Once in the table, once on stderr.
  const size_t first = r.output.find(line);
  ASSERT_NE(first, std::string::npos) << r.output;
  EXPECT_NE(r.output.find(line, first + 1), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("kdrt sim --synth"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_empty(PhysDir()));
}

// A core.json that is cut short, lacks a field, or belongs to another
// configuration stops kdrt sim before it runs: exit 1, the file named, no
// image written.
TEST_F(PhysCli, BrokenCoreJsonIsRefused) {
  const std::string key = SimModelKey(kScene);
  ASSERT_FALSE(key.empty());
  const std::string core = CoreJsonPath(key);
  const std::string params = "\"params\": {\"E\": 8, \"M\": 23}";
  const std::pair<std::string, std::string> cases[] = {
      {"{\"library\": \"osu018\", \"clock_ns\": 5.1, \"units\": [", "not valid JSON"},
      {"{\"library\": \"osu018\", \"critical_unit\": \"rt_x\", \"area_um2\": {\"logic\": 1, \"sram\": 0, \"total\": 1}, "
       "\"units\": []}",
       "no \"clock_ns\""},
      {"{\"library\": \"osu018\", \"clock_ns\": 5.1, \"critical_unit\": \"rt_x\", \"area_um2\": {\"logic\": 1, "
       "\"sram\": 0, \"total\": 1}, " + params + ", \"units\": [{\"unit\": \"rt_x\"}]}",
       "\"params\" has no integer"},
  };
  for (const auto& [text, message] : cases) {
    std::ofstream(core) << text;
    const RunResult r = Kdrt(std::string("sim ") + kScene + " --model fast -q -o " + Path("x.png"));
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find(core), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(Path("x.png")));
  }
  // The same params as the key but one: the figures of another configuration.
  nlohmann::json other = MinimalCoreJson(sim::DefaultConfig(fp::Format{8, 23}));
  other["params"]["Threads"] = 7;
  std::ofstream(core) << other.dump();
  const RunResult r = Kdrt(std::string("sim ") + kScene + " --model fast -q -o " + Path("x.png"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("synthesized with"), std::string::npos) << r.output;
}

// A core.json of this configuration made from other sources (its
// sources_fnv1a64 is not this tree's) is another design's figures: "physical"
// is null, the line says why, kdrt synth --which says so; with this tree's
// hash the same file is reported. The script and kdrt hash alike.
TEST_F(PhysCli, SynthesisOfOtherSourcesIsNotReported) {
  const std::string key = SimModelKey(kScene);
  ASSERT_FALSE(key.empty());
  const std::string core = CoreJsonPath(key);
  nlohmann::json j = MinimalCoreJson(sim::DefaultConfig(fp::Format{8, 23}));
  const std::string tree = sim::SourcesHash();
  ASSERT_EQ(tree.size(), 16u);
  for (const std::string& hash : {tree, std::string("0123456789abcdef"), std::string()}) {
    if (hash.empty()) {
      j.erase("sources_fnv1a64");
    } else {
      j["sources_fnv1a64"] = hash;
    }
    std::ofstream(core) << j.dump();
    const RunResult r = Kdrt(std::string("sim ") + kScene + " --model fast -o " + Path("x.png") + " --json " +
                             Path("x.json"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json out = ReadJsonFile(Path("x.json"));
    const RunResult y = Kdrt("synth gen:room:300 --which");
    ASSERT_EQ(y.exit_code, 0) << y.output;
    if (hash == tree) {
      ASSERT_TRUE(out["physical"].is_object()) << r.output;
      EXPECT_DOUBLE_EQ(out["physical"]["clock_ns"].get<double>(), 5.1);
      EXPECT_NE(y.output.find("(synthesized)"), std::string::npos) << y.output;
    } else {
      EXPECT_TRUE(out["physical"].is_null()) << hash;
      EXPECT_NE(r.output.find(core + ") was made from other sources"), std::string::npos) << r.output;
      EXPECT_NE(y.output.find("(made from other sources than this tree's)"), std::string::npos) << y.output;
    }
  }
  const RunResult py = testing::RunCommand(
      "python3 -B -c 'import sys; sys.path.insert(0, \"" KDRT_SOURCE_DIR "/scripts\"); import synth_core; "
      "print(synth_core.sources_hash())'");
  ASSERT_EQ(py.exit_code, 0) << py.output;
  EXPECT_EQ(py.output, tree + "\n");
}

// A synthesis whose sources changed while it ran (or since) is refused
// after the run with the file and what to do, not reported: kdrt synth ends
// with exit status 1 instead of printing another design's figures.
TEST_F(PhysCli, SynthesisOfChangedSourcesIsAnError) {
  const sim::CoreConfig config = sim::DefaultConfig(fp::Format{8, 23});
  ASSERT_EQ(setenv("KDRT_PHYS_DIR", PhysDir().c_str(), 1), 0);
  EXPECT_NO_THROW(sim::RequireSynthesisOfThisTree(config));  // none yet
  const std::string core = CoreJsonPath(config.Key());
  nlohmann::json j = MinimalCoreJson(config);
  j["sources_fnv1a64"] = sim::SourcesHash();
  std::ofstream(core) << j.dump();
  EXPECT_NO_THROW(sim::RequireSynthesisOfThisTree(config));
  j["sources_fnv1a64"] = "0123456789abcdef";
  std::ofstream(core) << j.dump();
  try {
    sim::RequireSynthesisOfThisTree(config);
    ADD_FAILURE() << "a synthesis of other sources was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(core + ": made from other sources"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("run 'kdrt synth' again"), std::string::npos) << e.what();
  }
  unsetenv("KDRT_PHYS_DIR");
}

// kdrt synth takes kdrt sim's scene and core options and arrives at the same
// model key (the one a synthesis is stored under), scene-sized or not.
TEST_F(PhysCli, SynthComputesTheKeyKdrtSimRuns) {
  for (const std::string opts : {"", " --threads 32 --cache-mshrs 16", " --format fp16 --node-cache-lines 64"}) {
    const std::string sim_key = SimModelKey(kScene + opts);
    ASSERT_FALSE(sim_key.empty());
    // kdrt synth takes no --res: the image size does not change the core.
    const RunResult y = Kdrt("synth gen:room:300" + opts + " --which");
    ASSERT_EQ(y.exit_code, 0) << y.output;
    const size_t b = y.output.find("model          ");
    ASSERT_NE(b, std::string::npos);
    const std::string synth_key = y.output.substr(b + 15, y.output.find('\n', b + 15) - b - 15);
    EXPECT_EQ(sim_key, synth_key) << opts;
    EXPECT_NE(y.output.find(PhysDir() + "/" + synth_key + "/core.json (none yet)"), std::string::npos) << y.output;
  }
  EXPECT_TRUE(fs::is_empty(PhysDir()));
}

// The physical block's arithmetic, from a core.json built here (figures of
// no real synthesis: the unit-level function alone).
TEST(PhysArithmetic, RatesAreaAndScaling) {
  const sim::CoreConfig c = sim::DefaultConfig(fp::Format{5, 10});
  nlohmann::json core = {{"library", "osu018"},
                         {"period_target_ns", 5},
                         {"scope", "per_unit"},
                         {"clock_ns", 8.0},
                         {"critical_unit", "rt_thread_fsm"},
                         {"area_um2", {{"logic", 2.0e6}, {"sram", 0.5e6}, {"total", 2.5e6}}},
                         {"units",
                          {{{"unit", "rt_thread_fsm"}, {"count", 1}, {"area_um2", 1.0e6}, {"flip_flops", 900},
                            {"crit_ns", 8.0}},
                           {{"unit", "rt_mem_system"}, {"count", 1}, {"area_um2", 1.5e6}, {"flip_flops", 100},
                            {"crit_ns", 4.0}, {"estimated", true}, {"method", "fit over smaller MSHR counts"}}}},
                         {"notes", {"per-unit"}}};
  for (int i = 0; i < sim::kParamCount; ++i) core["params"][sim::kCoreParams[i].sv_name] = c.value[i];
  const nlohmann::json p = sim::PhysicalBlock(core, "core.json", c, 4.0);
  EXPECT_DOUBLE_EQ(p["clock_ns"].get<double>(), 8.0);
  EXPECT_DOUBLE_EQ(p["area_mm2"]["total"].get<double>(), 2.5);
  EXPECT_DOUBLE_EQ(p["area_mm2"]["sram"].get<double>(), 0.5);
  // 1e3 / 8 ns / 4 cycles per ray.
  EXPECT_DOUBLE_EQ(p["mrays_per_s"].get<double>(), 31.25);
  EXPECT_DOUBLE_EQ(p["mrays_per_s_per_mm2"].get<double>(), 12.5);
  ASSERT_EQ(p["estimated_units"].size(), 1u);
  EXPECT_EQ(p["estimated_units"][0]["unit"], "rt_mem_system");
  EXPECT_EQ(p["estimated_units"][0]["method"], "fit over smaller MSHR counts");

  // Stillmaker & Baas: the 180 nm row of the area table, and the delay
  // polynomials at nominal Vdd (180 nm at 1.8 V, 45 nm HP at 1.0 V, 7 nm HP at 0.7 V).
  const double d180 = 97.09 * 1.8 * 1.8 - 356.7 * 1.8 + 406.5;
  const double d45 = -501.6 + 1567 - 1619 + 566.1;
  const double d7 = -28.58 * 0.343 + 76.6 * 0.49 - 70.26 * 0.7 + 24.69;
  const nlohmann::json& s45 = p["scaled"]["45nm"];
  EXPECT_EQ(s45["method"], "scaled");
  EXPECT_DOUBLE_EQ(s45["area_factor"].get<double>(), 0.053);
  EXPECT_NEAR(s45["delay_factor"].get<double>(), d45 / d180, 1e-12);
  EXPECT_NEAR(s45["delay_factor"].get<double>(), 0.16, 0.01);  // the anchor: 180 -> 45 nm about x0.16
  EXPECT_NEAR(s45["clock_ns"].get<double>(), 8.0 * d45 / d180, 1e-9);
  EXPECT_NEAR(s45["mrays_per_s"].get<double>(), 1e3 / (8.0 * d45 / d180) / 4.0, 1e-9);
  EXPECT_NEAR(s45["mrays_per_s_per_mm2"].get<double>(), 1e3 / (8.0 * d45 / d180) / 4.0 / (2.5 * 0.053), 1e-6);
  const nlohmann::json& s7 = p["scaled"]["7nm"];
  EXPECT_DOUBLE_EQ(s7["area_factor"].get<double>(), 0.0032);
  EXPECT_NEAR(s7["delay_factor"].get<double>(), d7 / d180, 1e-12);
  // 45 -> 7 nm in the paper's own 45 nm row is x0.059; the 180 nm row's
  // ratio agrees to its two digits.
  EXPECT_NEAR(0.0032 / 0.053, 0.059, 0.002);
  // 28 nm: between the paper's 32 and 20 nm, log-log.
  const nlohmann::json& s28 = p["scaled"]["28nm"];
  EXPECT_EQ(s28["interpolated_from_nm"], nlohmann::json({32, 20}));
  const double t = std::log(32.0 / 28) / std::log(32.0 / 20);
  EXPECT_NEAR(s28["area_factor"].get<double>(), std::exp(std::log(0.025) + t * (std::log(0.011) - std::log(0.025))),
              1e-12);
  EXPECT_LT(s28["area_factor"].get<double>(), 0.025);
  EXPECT_GT(s28["area_factor"].get<double>(), 0.011);
  EXPECT_NEAR(s28["mrays_per_s_per_mm2"].get<double>(),
              1e3 / (8.0 * s28["delay_factor"].get<double>()) / 4.0 / (2.5 * s28["area_factor"].get<double>()), 1e-6);
}

TEST(PhysArithmetic, MalformedFieldsNameTheFile) {
  const sim::CoreConfig c = sim::DefaultConfig(fp::Format{8, 23});
  nlohmann::json core = {{"library", "osu018"},
                         {"clock_ns", -1.0},
                         {"critical_unit", "rt_x"},
                         {"area_um2", {{"logic", 1}, {"sram", 0}, {"total", 1}}},
                         {"units", {{{"unit", "rt_x"}, {"count", 1}, {"area_um2", 1}, {"flip_flops", 0},
                                     {"crit_ns", 1}}}}};
  for (int i = 0; i < sim::kParamCount; ++i) core["params"][sim::kCoreParams[i].sv_name] = c.value[i];
  try {
    sim::PhysicalBlock(core, "/x/core.json", c, 4.0);
    FAIL() << "a negative clock was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/x/core.json: \"clock_ns\" is not a positive number"), std::string::npos)
        << e.what();
  }
}

// Two real syntheses: more threads, other unit parameters and areas. A
// small fp16 core (4 or 8 threads, 16-line caches, 4 miss registers) still
// takes scripts/synth-core.sh many minutes (36 for both on 2 shared cores:
// the tag width follows Threads, so few units come from the shared unit
// cache the second time), so KDRT_LONG only.
TEST_F(PhysCli, ThreadsChangeTheSynthesis) {
  if (!LongRun()) GTEST_SKIP() << "two syntheses of minutes each: KDRT_LONG=1 (make test-long)";
  const std::string common = std::string("sim ") + kScene +
                             " --format fp16 --cache-mshrs 4 --node-cache-lines 16 --list-cache-lines 16 "
                             "--tri-cache-lines 16 --list-prefetch 0 --model fast --synth -q";
  const RunResult a = Kdrt(common + " --threads 4 -o " + Path("a.png") + " --json " + Path("a.json"));
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const RunResult b = Kdrt(common + " --threads 8 -o " + Path("b.png") + " --json " + Path("b.json"));
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const nlohmann::json ja = ReadJsonFile(Path("a.json")), jb = ReadJsonFile(Path("b.json"));
  ASSERT_TRUE(ja["physical"].is_object());
  ASSERT_TRUE(jb["physical"].is_object());
  EXPECT_NE(ja["model"]["key"], jb["model"]["key"]);
  // The units rt_core sizes by Threads carry it in their parameters: 4 in
  // one synthesis, 8 in the other, and more area with more threads.
  auto threads_units = [](const nlohmann::json& j, int threads) {
    double area = 0;
    int units = 0;
    for (const auto& u : j["physical"]["units"]) {
      if (!u.contains("params") || !u["params"].contains("Threads")) continue;
      EXPECT_EQ(u["params"]["Threads"].get<int>(), threads) << u.dump();
      area += u["area_um2"].get<double>() * u["count"].get<double>();
      ++units;
    }
    EXPECT_GT(units, 0) << "no unit with a Threads parameter";
    return area;
  };
  EXPECT_LT(threads_units(ja, 4), threads_units(jb, 8));
  EXPECT_LT(ja["physical"]["area_mm2"]["total"].get<double>(), jb["physical"]["area_mm2"]["total"].get<double>());
  for (const nlohmann::json* j : {&ja, &jb}) {
    const auto& p = (*j)["physical"];
    EXPECT_NEAR(p["mrays_per_s"].get<double>(),
                1e3 / p["clock_ns"].get<double>() / (*j)["cycles_per_ray"].get<double>(), 1e-9);
  }
}

}  // namespace
}  // namespace kdrt
