// End-to-end tests of `kdrt sim` against `kdrt render`: the RTL core must
// return bit-identical hit records for every generated scene and preset
// format (the harness also checks each ray as it leaves), the memory timing
// may change the cycles but never the answers, and options the scene cannot
// run with are refused before anything is written.
//
// fp32 runs on the default core. The other preset formats, and the options
// whose outcome does not depend on how many rays are in flight (stack depth,
// cache shape, image and traversal formats), run on a small core (SmallCore
// below), whose model compiles and simulates several times faster than the
// default core's. KDRT_LONG=1 renders every scene and preset at 512x512
// instead of 24x24, every preset on the default core.
#include <gtest/gtest.h>

#include "tests/common/read_file.h"
#include "tests/common/run_kdrt.h"
#include "tests/common/test_cores.h"

#include <sys/inotify.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <set>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fp/format.h"
#include "scene/nff_writer.h"
#include "sim/model_runner.h"
#include "tests/common/moved_sphere.h"
#include "tests/trace/trace_test_util.h"
#include "trace/images.h"
#include "trace/rays_file.h"

namespace kdrt {
namespace {

namespace fs = std::filesystem;

using testing::CoreFor;
using testing::CrowdedMemoryCore;
using testing::LongRun;
using testing::RunKdrt;
using testing::RunResult;
using testing::SmallCore;


class SimCli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    dir_ = fs::temp_directory_path() / ("kdrt_sim_" + name + "_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  size_t FileCount() const {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir_)) n += e.is_regular_file();
    return n;
  }

  // Both hit buffers decode to the same bits and are the same bytes.
  void ExpectSameHitBuffers(const std::string& a, const std::string& b) {
    int aw = 0, ah = 0, bw = 0, bh = 0;
    const std::vector<Hit> ha = ReadHitBuffer(a, &aw, &ah);
    const std::vector<Hit> hb = ReadHitBuffer(b, &bw, &bh);
    ASSERT_EQ(aw, bw);
    ASSERT_EQ(ah, bh);
    ASSERT_EQ(ha.size(), hb.size());
    size_t hits = 0;
    for (size_t i = 0; i < ha.size(); ++i) {
      hits += ha[i].IsHit();
      ASSERT_EQ(ha[i].prim, hb[i].prim) << "pixel " << i;
      ASSERT_EQ(fp::BitsOf(ha[i].t), fp::BitsOf(hb[i].t)) << "pixel " << i;
      ASSERT_EQ(fp::BitsOf(ha[i].u), fp::BitsOf(hb[i].u)) << "pixel " << i;
      ASSERT_EQ(fp::BitsOf(ha[i].v), fp::BitsOf(hb[i].v)) << "pixel " << i;
    }
    EXPECT_GT(hits, 0u) << "a test that hits nothing checks little";
    EXPECT_EQ(kdrt::testing::ReadFile(a), kdrt::testing::ReadFile(b)) << "EXR files differ in bytes";
  }

  nlohmann::json ReadJson(const std::string& path) {
    std::ifstream f(path);
    return nlohmann::json::parse(f);
  }

  fs::path dir_;
};

struct SceneCase {
  const char* scene;
  const char* format;
};

void PrintTo(const SceneCase& c, std::ostream* os) { *os << c.scene << " " << c.format; }

// The stall breakdown of a report (docs/simulator.md, "What the report says
// about the core") is made of shares that must add up.
void ExpectConsistentBreakdown(const nlohmann::json& j) {
  double states = 0;
  for (const auto& [name, share] : j["thread_states"].items()) {
    EXPECT_GE(share.get<double>(), 0.0) << name;
    states += share.get<double>();
  }
  EXPECT_NEAR(states, 1.0, 1e-9);
  for (const char* cache : {"node", "list", "tri"}) {
    const auto& w = j["waits"][cache];
    EXPECT_LE(w["wait_in_flight"].get<double>() + w["wait_no_mshr"].get<double>(), w["wait"].get<double>() + 1e-12)
        << cache;
    EXPECT_LE(w["wait"].get<double>(), 1.0) << cache;
    EXPECT_LE(w["merged_misses"].get<uint64_t>(), j["perf_counts"][std::string(cache) + "_miss"].get<uint64_t>())
        << cache;
  }
  for (const char* unit : {"traversal", "intersection"}) {
    EXPECT_GE(j["unit_starve"][unit].get<double>(), 0.0) << unit;
    EXPECT_LE(j["unit_starve"][unit].get<double>(), j["busy"].get<double>()) << unit;
  }
  EXPECT_NEAR(j["memory_bound_cycles_per_ray"].get<double>(),
              j["memory"]["bytes_per_ray"].get<double>() / j["memory"]["bytes_per_cycle"].get<double>(), 1e-9);
}

class SimMatchesRender : public SimCli, public ::testing::WithParamInterface<SceneCase> {};

TEST_P(SimMatchesRender, HitBuffersAreIdentical) {
  const SceneCase c = GetParam();
  const std::string res = LongRun() ? "512x512" : "24x24";
  const std::string common = std::string(c.scene) + " --res " + res + " --format " + c.format;
  const RunResult r = RunKdrt("render " + common + " -q -o " + Path("render.png") + " --hits " + Path("render.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const RunResult s = RunKdrt("sim " + common + CoreFor(c.format) + " -o " + Path("sim.png") + " --hits " +
                              Path("sim.exr") + " --json " + Path("sim.json"));
  ASSERT_EQ(s.exit_code, 0) << s.output;
  ExpectSameHitBuffers(Path("render.exr"), Path("sim.exr"));
  EXPECT_EQ(kdrt::testing::ReadFile(Path("render.png")), kdrt::testing::ReadFile(Path("sim.png")));
  const nlohmann::json j = ReadJson(Path("sim.json"));
  const uint64_t rays = j["rays"];
  EXPECT_EQ(rays, LongRun() ? 512u * 512u : 24u * 24u);
  EXPECT_GT(j["cycles"].get<uint64_t>(), 0u);
  // Every ray went in and came out, as the core's own event counters saw it.
  EXPECT_EQ(j["perf_counts"]["ray_in"].get<uint64_t>(), rays);
  EXPECT_EQ(j["perf_counts"]["ray_out"].get<uint64_t>(), rays);
  EXPECT_EQ(j["overflows"].get<uint64_t>(), 0u);
  EXPECT_TRUE(j["warnings"].is_array());
  EXPECT_EQ(j["precision"]["rays"].get<uint64_t>(), rays);
  // The core cannot beat one node fetch or one test per cycle.
  EXPECT_GE(j["cycles_per_ray"].get<double>(), j["bound_cycles_per_ray"].get<double>());
  ExpectConsistentBreakdown(j);
}

std::string CaseName(const ::testing::TestParamInfo<SceneCase>& info) {
  std::string s = std::string(info.param.scene) + "_" + info.param.format;
  for (char& ch : s) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(
    GeneratedScenes, SimMatchesRender,
    ::testing::Values(SceneCase{"gen:room:600", "fp32"}, SceneCase{"gen:room:600", "fp24"},
                      SceneCase{"gen:room:600", "bf16"}, SceneCase{"gen:room:600", "fp16"},
                      SceneCase{"gen:balls:800", "fp32"}, SceneCase{"gen:balls:800", "fp24"},
                      SceneCase{"gen:balls:800", "bf16"}, SceneCase{"gen:balls:800", "fp16"},
                      SceneCase{"gen:rings:800", "fp32"}, SceneCase{"gen:rings:800", "fp24"},
                      SceneCase{"gen:rings:800", "bf16"}, SceneCase{"gen:rings:800", "fp16"},
                      SceneCase{"gen:tetra:1000", "fp32"}, SceneCase{"gen:tetra:1000", "fp24"},
                      SceneCase{"gen:tetra:1000", "bf16"}, SceneCase{"gen:tetra:1000", "fp16"},
                      SceneCase{"gen:tree:2000", "fp32"}, SceneCase{"gen:tree:2000", "fp24"},
                      SceneCase{"gen:tree:2000", "bf16"}, SceneCase{"gen:tree:2000", "fp16"},
                      SceneCase{"gen:gears:1500", "fp32"}, SceneCase{"gen:gears:1500", "fp24"},
                      SceneCase{"gen:gears:1500", "bf16"}, SceneCase{"gen:gears:1500", "fp16"}),
    CaseName);

// A shaded frame (docs/shading.md): primary, shadow (any-hit), AO (any-hit)
// and bounce rays, each pass run on the RTL and checked ray by ray in the
// model; the image from the RTL's hits is the reference's byte for byte,
// and so are the ray sets built from them.
class ShadedFrameMatchesRender : public SimCli, public ::testing::WithParamInterface<const char*> {};

TEST_P(ShadedFrameMatchesRender, ImageAndRaySetsAreIdentical) {
  const std::string common = std::string("gen:room:600 --res 20x20 --shade --ao 2 --bounce --format ") + GetParam();
  const RunResult r = RunKdrt("render " + common + " -o " + Path("render.png") + " --json " + Path("render.json") +
                              " --write-rays " + Path("render_rays"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string core = CoreFor(GetParam());
  const RunResult s = RunKdrt("sim " + common + core + " -o " + Path("sim.png") + " --json " + Path("sim.json") +
                              " --write-rays " + Path("sim_rays"));
  ASSERT_EQ(s.exit_code, 0) << s.output;
  EXPECT_EQ(kdrt::testing::ReadFile(Path("render.png")), kdrt::testing::ReadFile(Path("sim.png")));
  for (const char* pass : {"primary", "shadow", "ao", "bounce"}) {
    const std::string name = std::string(pass) + ".rays";
    ASSERT_TRUE(fs::exists(Path("render_rays/" + name))) << name;
    EXPECT_EQ(kdrt::testing::ReadFile(Path("render_rays/" + name)), kdrt::testing::ReadFile(Path("sim_rays/" + name))) << name;
  }
  const nlohmann::json j = ReadJson(Path("sim.json"));
  const nlohmann::json rj = ReadJson(Path("render.json"));
  ASSERT_EQ(j["passes"].size(), 4u);
  ASSERT_EQ(rj["passes"].size(), 4u);
  const char* queries[] = {"closest", "any", "any", "closest"};
  uint64_t rays = 0, cycles = 0;
  for (size_t k = 0; k < 4; ++k) {
    const auto& p = j["passes"][k];
    SCOPED_TRACE(p["name"].get<std::string>());
    EXPECT_EQ(p["name"], rj["passes"][k]["name"]);
    EXPECT_EQ(p["query"], queries[k]);
    EXPECT_EQ(p["stats"]["query"], queries[k]);
    EXPECT_EQ(p["rays"], rj["passes"][k]["rays"]);
    EXPECT_EQ(p["hits"], rj["passes"][k]["hits"]);
    EXPECT_EQ(p["stats"]["perf_counts"]["ray_out"], p["rays"]);
    // The default Z-order issues a pass's rays by their pixels (the image
    // and ray sets above are still the reference's: the hits go back in
    // the pass's order).
    EXPECT_EQ(p["stats"]["ray_order"], k == 0 ? "morton:8" : "morton:8 by pixel");
    EXPECT_GE(p["stats"]["cycles_per_ray"].get<double>(), p["stats"]["bound_cycles_per_ray"].get<double>());
    ExpectConsistentBreakdown(p["stats"]);
    rays += p["rays"].get<uint64_t>();
    cycles += p["stats"]["cycles"].get<uint64_t>();
  }
  EXPECT_GT(j["passes"][1]["hits"].get<uint64_t>(), 0u) << "no shadow ray was blocked: the test shows little";
  EXPECT_LT(j["passes"][1]["hits"], j["passes"][1]["rays"]) << "every shadow ray was blocked";
  EXPECT_EQ(j["frame"]["rays"].get<uint64_t>(), rays);
  EXPECT_EQ(j["frame"]["cycles"].get<uint64_t>(), cycles);

  // Three interleaved runs of the Z-order, in every pass: the same image
  // and ray sets, in other cycles.
  const RunResult k = RunKdrt("sim " + common + core + " --ray-order morton:3 -q -o " + Path("k.png") + " --json " +
                              Path("k.json") + " --write-rays " + Path("k_rays"));
  ASSERT_EQ(k.exit_code, 0) << k.output;
  EXPECT_EQ(kdrt::testing::ReadFile(Path("render.png")), kdrt::testing::ReadFile(Path("k.png")));
  for (const char* pass : {"primary", "shadow", "ao", "bounce"}) {
    const std::string name = std::string(pass) + ".rays";
    EXPECT_EQ(kdrt::testing::ReadFile(Path("render_rays/" + name)), kdrt::testing::ReadFile(Path("k_rays/" + name))) << name;
  }
  const nlohmann::json kj = ReadJson(Path("k.json"));
  ASSERT_EQ(kj["passes"].size(), 4u);
  EXPECT_EQ(kj["passes"][0]["stats"]["ray_order"], "morton:3");
  EXPECT_EQ(kj["passes"][1]["stats"]["ray_order"], "morton:3 by pixel");
  EXPECT_NE(kj["frame"]["cycles"], j["frame"]["cycles"]);

  // A written shadow-ray file is an any-hit set for both tracers.
  const std::string file = " --format " + std::string(GetParam()) + " --rays " + Path("render_rays/shadow.rays");
  ASSERT_EQ(RunKdrt("render gen:room:600" + file + " -q --hits " + Path("r_shadow.exr")).exit_code, 0);
  const RunResult fs_run = RunKdrt("sim gen:room:600" + file + core + " --hits " + Path("s_shadow.exr"));
  ASSERT_EQ(fs_run.exit_code, 0) << fs_run.output;
  EXPECT_NE(fs_run.output.find("any-hit queries"), std::string::npos) << fs_run.output;
  ExpectSameHitBuffers(Path("r_shadow.exr"), Path("s_shadow.exr"));
}

INSTANTIATE_TEST_SUITE_P(Presets, ShadedFrameMatchesRender, ::testing::Values("fp32", "fp24", "bf16", "fp16"));

TEST_F(SimCli, ShadingOptionErrorsWriteNothing) {
  RunResult r = RunKdrt("render gen:room:300 --res 8x8 --write-rays " + Path("rays") + " -o " + Path("x.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("--write-rays"), std::string::npos) << r.output;
  ASSERT_EQ(RunKdrt("render gen:room:300 --res 8x8 --shade -q -o " + Path("a.png") + " --write-rays " + Path("rays"))
                .exit_code,
            0);
  r = RunKdrt("sim gen:room:300 --shade --rays " + Path("rays/shadow.rays") + " -o " + Path("y.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("any-hit"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(Path("x.png")));
  EXPECT_FALSE(fs::exists(Path("y.png")));
}

// Several cores (SystemC system model) share an L2 and the memory: the
// records are the reference's whoever traced each ray, every core works,
// and four cores trace more rays per cycle than one.
TEST_F(SimCli, SeveralCoresShareTheL2) {
  const std::string common = "gen:balls:800 --res 32x32";
  ASSERT_EQ(RunKdrt("render " + common + " -q --hits " + Path("render.exr")).exit_code, 0);
  const RunResult one = RunKdrt("sim " + common + " --cores 1 -q --json " + Path("c1.json"));
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const RunResult four = RunKdrt("sim " + common + " --cores 4 --ray-chunk 16 --hits " + Path("c4.exr") +
                                 " --json " + Path("c4.json"));
  ASSERT_EQ(four.exit_code, 0) << four.output;
  EXPECT_NE(four.output.find("core 3"), std::string::npos) << four.output;
  ExpectSameHitBuffers(Path("render.exr"), Path("c4.exr"));
  const nlohmann::json j1 = ReadJson(Path("c1.json")), j4 = ReadJson(Path("c4.json"));
  EXPECT_EQ(j4["cores"].get<int>(), 4);
  EXPECT_EQ(j4["loop"], "systemc");
  ASSERT_EQ(j4["per_core"].size(), 4u);
  uint64_t rays = 0, last = 0;
  for (const auto& c : j4["per_core"]) {
    EXPECT_GT(c["rays"].get<uint64_t>(), 0u);
    rays += c["rays"].get<uint64_t>();
    last = std::max(last, c["cycles"].get<uint64_t>());
  }
  EXPECT_EQ(rays, 32u * 32u);
  EXPECT_EQ(j4["cycles"].get<uint64_t>(), last);
  EXPECT_GT(j4["l2"]["hits"].get<uint64_t>(), 0u);
  EXPECT_LE(j4["memory"]["bytes_read"].get<uint64_t>(), 16 * j4["l2"]["requests"].get<uint64_t>());
  EXPECT_GT(j4["rays_per_cycle"].get<double>(), 1.5 * j1["rays_per_cycle"].get<double>());
  EXPECT_GE(j4["cycles_per_ray"].get<double>(), j4["bound_cycles_per_ray"].get<double>());
  // The rays in flight are the four cores' threads.
  EXPECT_EQ(j4["window_bound"]["rays"].get<uint64_t>(), 4 * j1["window_bound"]["rays"].get<uint64_t>());
  EXPECT_GE(j4["window_bound"]["cycles_per_ray"].get<double>(), j4["bound_cycles_per_ray"].get<double>());
  ExpectConsistentBreakdown(j4);
}

// The fast cycle model (sim/fast_model.h) follows the core register by
// register: the same cycles as the RTL on every generator and preset, the
// reference's hits, and --model fast alone needs no RTL model.
// The fast model's report beside the RTL's (kdrt sim --model both): the
// same cycles and every performance counter, the stall breakdown, the
// thread states, the memory's bytes and the rays in flight, and with
// several cores every core's figures.
void ExpectFastEqualsRtl(const nlohmann::json& j) {
  const nlohmann::json& f = j["fast"]["report"];
  EXPECT_EQ(j["cycle_model"], "rtl");
  EXPECT_EQ(f["cycle_model"], "fast");
  EXPECT_EQ(f["cycles"], j["cycles"]);
  EXPECT_EQ(j["fast"]["error"].get<double>(), 0.0);
  EXPECT_EQ(f["perf_counts"], j["perf_counts"]);
  EXPECT_EQ(f["stalls"], j["stalls"]);
  EXPECT_EQ(f["utilisation"], j["utilisation"]);
  EXPECT_EQ(f["thread_states"], j["thread_states"]);
  EXPECT_EQ(f["memory"]["bytes_read"], j["memory"]["bytes_read"]);
  EXPECT_EQ(f["max_rays_in_flight"], j["max_rays_in_flight"]);
  // The bound of the rays in flight: the same rays in the same order, and
  // never below the whole run's.
  EXPECT_EQ(f["window_bound"], j["window_bound"]);
  EXPECT_GT(j["window_bound"]["rays"].get<uint64_t>(), 0u);
  EXPECT_GE(j["window_bound"]["cycles_per_ray"].get<double>(), j["bound_cycles_per_ray"].get<double>());
  EXPECT_LE(j["window_bound"]["cycles_per_ray"].get<double>(), j["cycles_per_ray"].get<double>() * 1.5);
  EXPECT_EQ(f.contains("per_core"), j.contains("per_core"));
  if (j.contains("per_core")) {
    EXPECT_EQ(f["per_core"], j["per_core"]);
  }
}

class FastModelMatchesRtl : public SimCli, public ::testing::WithParamInterface<SceneCase> {};

TEST_P(FastModelMatchesRtl, SameCyclesAndEvents) {
  const SceneCase c = GetParam();
  const std::string common = std::string(c.scene) + " --res 20x20 --format " + c.format + CoreFor(c.format);
  const RunResult both = RunKdrt("sim " + common + " -o " + Path("b.png") + " --json " + Path("b.json"));
  ASSERT_EQ(both.exit_code, 0) << both.output;
  const RunResult r = RunKdrt("sim " + common + " --model both -q -o " + Path("x.png") + " --json " + Path("x.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = ReadJson(Path("x.json"));
  ExpectFastEqualsRtl(j);
  const RunResult fast = RunKdrt("sim " + common + " --model fast -o " + Path("f.png") + " --json " + Path("f.json"));
  ASSERT_EQ(fast.exit_code, 0) << fast.output;
  EXPECT_NE(fast.output.find("cycle model    fast"), std::string::npos) << fast.output;
  EXPECT_EQ(kdrt::testing::ReadFile(Path("f.png")), kdrt::testing::ReadFile(Path("b.png")));
  EXPECT_EQ(ReadJson(Path("f.json"))["cycles"], j["cycles"]);
}

INSTANTIATE_TEST_SUITE_P(
    GeneratedScenes, FastModelMatchesRtl,
    ::testing::Values(SceneCase{"gen:room:600", "fp32"}, SceneCase{"gen:balls:800", "fp24"},
                      SceneCase{"gen:rings:800", "bf16"}, SceneCase{"gen:tetra:1000", "fp16"},
                      SceneCase{"gen:tree:2000", "fp32"}, SceneCase{"gen:gears:1500", "bf16"}),
    CaseName);

// The list prefetcher (--list-prefetch N: rt_list_unit's ListPrefetch and
// the list cache's prefetch port) cycle for cycle in both models, with few
// miss registers of few targets, small caches and a slow memory so that
// prefetches meet full registers, lines in flight, evictions and demand
// requests joining them; and it changes what the core does: the list lines
// it fetches ahead are hits (or joins) for the list unit, so fewer of its
// requests start a fetch.
TEST_F(SimCli, ListPrefetchMatchesTheFastModel) {
  const std::string common = "sim gen:gears:1500 --res 24x24 --mem-latency 60 -q";
  const RunResult r =
      RunKdrt(common + CrowdedMemoryCore() + " --model both -o " + Path("x.png") + " --json " + Path("x.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = ReadJson(Path("x.json"));
  ExpectFastEqualsRtl(j);
  EXPECT_EQ(j["model"]["ListPrefetch"], 4);
  const RunResult off =
      RunKdrt(common + CrowdedMemoryCore(0) + " --model fast -o " + Path("f.png") + " --json " + Path("f.json"));
  ASSERT_EQ(off.exit_code, 0) << off.output;
  const nlohmann::json jo = ReadJson(Path("f.json"));
  EXPECT_EQ(kdrt::testing::ReadFile(Path("f.png")), kdrt::testing::ReadFile(Path("x.png")));
  const auto own_fetches = [](const nlohmann::json& k) {
    return k["perf_counts"]["list_miss"].get<uint64_t>() - k["perf_counts"]["list_merge"].get<uint64_t>();
  };
  EXPECT_LT(own_fetches(j), own_fetches(jo));
  EXPECT_GT(j["cache_hit_rate"]["list"].get<double>(), jo["cache_hit_rate"]["list"].get<double>());
}

// More than 64 miss registers per cache (the fast model's register masks
// are 128 bits, as the default core has 128 registers per cache): on the
// default core, gears' large leaves and a slow memory keep every triangle
// register in use at once (register 127 taken, seen in the fast model),
// cycle for cycle in both models. The same scene-sized model as
// SimMatchesRender's gears fp32 (the latency is not a parameter of the model).
TEST_F(SimCli, MoreThan64MissRegistersMatchTheFastModel) {
  const RunResult r = RunKdrt("sim gen:gears:1500 --res 24x24 --format fp32 --mem-latency 400 --model both -q -o " +
                              Path("x.png") + " --json " + Path("x.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = ReadJson(Path("x.json"));
  ExpectFastEqualsRtl(j);
  EXPECT_EQ(j["model"]["CacheMshrs"], 128);
  // More beats in flight than 64 lines of the largest kind (3-beat
  // triangle lines) could be.
  EXPECT_GT(j["memory"]["max_outstanding"].get<int>(), 64 * 3);
  const RunResult over = RunKdrt("sim gen:gears:1500 --res 8x8 --cache-mshrs 129 --model fast -q");
  EXPECT_NE(over.exit_code, 0);
  EXPECT_NE(over.output.find("--cache-mshrs"), std::string::npos) << over.output;
}

// Several cores in the fast model (RunFastCores): the SystemC system's
// cycles core by core, the rays each core took, its counters, and the shared
// L2's and the memory's figures, with a ray chunk that does not divide the
// rays, a slow memory and an L2 small enough to evict.
struct CoresCase {
  const char* scene;
  const char* format;
  const char* options;
};

void PrintTo(const CoresCase& c, std::ostream* os) { *os << c.scene << " " << c.format << " " << c.options; }

class FastModelMatchesRtlCores : public SimCli, public ::testing::WithParamInterface<CoresCase> {};

TEST_P(FastModelMatchesRtlCores, SameCyclesPerCore) {
  const CoresCase c = GetParam();
  const std::string common =
      std::string("sim ") + c.scene + " --res 24x24 --format " + c.format + CoreFor(c.format) + " " + c.options + " -q";
  const RunResult r = RunKdrt(common + " --model both -o " + Path("x.png") + " --json " + Path("x.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = ReadJson(Path("x.json"));
  const nlohmann::json& f = j["fast"]["report"];
  ASSERT_TRUE(j.contains("per_core"));
  ExpectFastEqualsRtl(j);
  EXPECT_EQ(f["l2"], j["l2"]);
  // Every core worked, and the fast model alone gives the same image.
  for (const auto& core : f["per_core"]) EXPECT_GT(core["rays"].get<uint64_t>(), 0u);
  const RunResult fast = RunKdrt(common + " --model fast -o " + Path("f.png") + " --json " + Path("f.json"));
  ASSERT_EQ(fast.exit_code, 0) << fast.output;
  EXPECT_EQ(kdrt::testing::ReadFile(Path("f.png")), kdrt::testing::ReadFile(Path("x.png")));
  EXPECT_EQ(ReadJson(Path("f.json"))["per_core"], j["per_core"]);
}

INSTANTIATE_TEST_SUITE_P(
    GeneratedScenes, FastModelMatchesRtlCores,
    ::testing::Values(CoresCase{"gen:balls:800", "fp32", "--cores 4 --ray-chunk 16"},
                      CoresCase{"gen:gears:1500", "bf16", "--cores 3 --ray-chunk 7 --mem-latency 90 --mem-bw 3"},
                      CoresCase{"gen:tree:2000", "fp16", "--cores 2 --l2-kb 4 --l2-ways 2 --l2-latency 3"}),
    [](const ::testing::TestParamInfo<CoresCase>& info) {
      std::string n = std::string(info.param.scene).substr(4) + "_" + info.param.format;
      for (char& ch : n) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      }
      return n;
    });

// Set-associative caches (--cache-ways; pseudo-LRU, rtl/rt_cache.sv): the
// fast model follows the RTL's replacement cycle by cycle, and where the
// working set crowds 16-line caches 4 ways miss less than direct mapping.
TEST_F(SimCli, AssociativeCaches) {
  const std::string common = "sim gen:balls:800 --res 24x24 -q" + CrowdedMemoryCore();
  const RunResult r =
      RunKdrt(common + " --cache-ways 4 --model both -o " + Path("x.png") + " --json " + Path("x.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = ReadJson(Path("x.json"));
  EXPECT_EQ(j["model"]["CacheWays"].get<int>(), 4);
  const nlohmann::json& f = j["fast"]["report"];
  EXPECT_EQ(f["cycles"], j["cycles"]);
  EXPECT_EQ(f["perf_counts"], j["perf_counts"]);
  EXPECT_EQ(f["thread_states"], j["thread_states"]);
  EXPECT_EQ(f["memory"]["bytes_read"], j["memory"]["bytes_read"]);
  const RunResult d =
      RunKdrt(common + " --cache-ways 1 --model fast -o " + Path("d.png") + " --json " + Path("d.json"));
  ASSERT_EQ(d.exit_code, 0) << d.output;
  const nlohmann::json dj = ReadJson(Path("d.json"));
  EXPECT_EQ(dj["model"]["CacheWays"].get<int>(), 1);
  const auto misses = [](const nlohmann::json& k) {
    return k["perf_counts"]["node_miss"].get<uint64_t>() + k["perf_counts"]["list_miss"].get<uint64_t>() +
           k["perf_counts"]["tri_miss"].get<uint64_t>();
  };
  EXPECT_LT(misses(j), misses(dj));
  EXPECT_LT(j["memory"]["bytes_read"].get<uint64_t>(), dj["memory"]["bytes_read"].get<uint64_t>());
  const RunResult bad = RunKdrt(common + " --cache-ways 3 -o " + Path("b.png"));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.output.find("--cache-ways 3: must be a power of two"), std::string::npos) << bad.output;
  const RunResult big =
      RunKdrt("sim gen:balls:800 --res 24x24 --tri-cache-lines 8 --cache-ways 16 -o " + Path("b.png"));
  EXPECT_EQ(big.exit_code, 1);
  EXPECT_NE(big.output.find("more ways than the 8 triangle cache lines"), std::string::npos) << big.output;
  EXPECT_FALSE(fs::exists(Path("b.png")));
}

// --ray-order morton issues the camera's
// rays along the Z-order curve (sim/ray_queue.h): the RTL still returns the
// reference's record for every ray (the hit buffer is the linear run's,
// pixel for pixel), the fast model follows it cycle for cycle on one core and
// on several, the report says which order ran, and a ray file, which has no
// frame, runs in its own order by default and is refused with an explicit
// --ray-order morton.
TEST_F(SimCli, MortonRayOrder) {
  const std::string common = "sim gen:tree:2000 --res 24x20 -q";
  const RunResult lin = RunKdrt(common + " --ray-order linear --model fast -o " + Path("l.png") + " --hits " +
                                Path("l.exr") + " --json " + Path("l.json"));
  ASSERT_EQ(lin.exit_code, 0) << lin.output;
  const RunResult r = RunKdrt(common + " --model both -o " + Path("m.png") + " --hits " + Path("m.exr") +
                              " --json " + Path("m.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameHitBuffers(Path("l.exr"), Path("m.exr"));
  const nlohmann::json j = ReadJson(Path("m.json"));
  const nlohmann::json lj = ReadJson(Path("l.json"));
  EXPECT_EQ(j["ray_order"], "morton:8");  // the default for a camera
  EXPECT_EQ(lj["ray_order"], "linear");
  ExpectFastEqualsRtl(j);
  EXPECT_EQ(j["perf_counts"]["ray_out"].get<uint64_t>(), 24u * 20u);
  // Same rays, same tree: the same work, in another order.
  EXPECT_EQ(j["reference_per_ray"], lj["reference_per_ray"]);
  EXPECT_NE(j["cycles"], lj["cycles"]);
  const RunResult text = RunKdrt("sim gen:tree:2000 --res 24x20 --ray-order morton --model fast -o " + Path("t.png"));
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("(24x20, issued in morton order)"), std::string::npos) << text.output;
  // Several cores take chunks of the Z-order (tiles).
  const RunResult c = RunKdrt(common + " --ray-order morton --cores 2 --ray-chunk 16 --model both -o " +
                              Path("c.png") + " --json " + Path("c.json"));
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const nlohmann::json cj = ReadJson(Path("c.json"));
  ASSERT_TRUE(cj.contains("per_core"));
  ExpectFastEqualsRtl(cj);
  // K interleaved runs of the Z-order: the same records, the fast model
  // still cycle for cycle, and another order than morton's.
  const RunResult k = RunKdrt(common + " --ray-order morton:4 --model both -o " + Path("k.png") + " --hits " +
                              Path("k.exr") + " --json " + Path("k.json"));
  ASSERT_EQ(k.exit_code, 0) << k.output;
  ExpectSameHitBuffers(Path("l.exr"), Path("k.exr"));
  const nlohmann::json kj = ReadJson(Path("k.json"));
  EXPECT_EQ(kj["ray_order"], "morton:4");
  ExpectFastEqualsRtl(kj);
  EXPECT_EQ(kj["reference_per_ray"], lj["reference_per_ray"]);
  EXPECT_NE(kj["cycles"], j["cycles"]);
  const RunResult bad_k = RunKdrt(common + " --ray-order morton:0 --model fast -o " + Path("bk.png"));
  EXPECT_NE(bad_k.exit_code, 0);
  EXPECT_NE(bad_k.output.find("morton:K must be a number from 1 to 256"), std::string::npos) << bad_k.output;
  EXPECT_FALSE(fs::exists(Path("bk.png")));

  const std::string rays = Path("x.rays");
  WriteRaysFile(rays, {Ray{{0, 0, -5}, {0, 0, 1}, 0, 100}, Ray{{0.1f, 0, -5}, {0, 0, 1}, 0, 100}});
  const RunResult own = RunKdrt("sim gen:tree:2000 --rays " + rays + " --model fast -q -o " + Path("f.png") +
                                " --json " + Path("f.json"));
  ASSERT_EQ(own.exit_code, 0) << own.output;
  EXPECT_EQ(ReadJson(Path("f.json"))["ray_order"], "linear");
  const RunResult bad = RunKdrt("sim gen:tree:2000 --rays " + rays + " --ray-order morton -o " + Path("b.png"));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.output.find("a ray file (--rays) is issued in its own order"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(Path("b.png")));
}

// ListStream 1 (the default; rt_list_unit,
// rt_mem_system): the list unit asks for a leaf's entries a list line at a
// time and a line register hands them on one a cycle. The RTL still returns
// the reference's record for every ray (the same hit buffer as the core of
// one request per entry, --list-stream 0), the fast model follows it
// cycle for cycle, on one core and on two, with two triangle records a line
// (fp16), and the list cache sees fewer requests than there are entries.
TEST_F(SimCli, ListStreamMatchesTheFastModel) {
  const std::string common = "sim gen:gears:1500 --res 24x24 --format fp16 -q" + CoreFor("fp16");
  const RunResult d = RunKdrt(common + " --list-stream 0 --model fast -o " + Path("d.png") + " --hits " + Path("d.exr") +
                              " --json " + Path("d.json"));
  ASSERT_EQ(d.exit_code, 0) << d.output;
  const RunResult r = RunKdrt(common + " --model both -o " + Path("s.png") + " --hits " +
                              Path("s.exr") + " --json " + Path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ExpectSameHitBuffers(Path("d.exr"), Path("s.exr"));
  const nlohmann::json j = ReadJson(Path("s.json"));
  const nlohmann::json dj = ReadJson(Path("d.json"));
  EXPECT_EQ(j["model"]["ListStream"].get<int>(), 1);
  EXPECT_EQ(dj["model"]["ListStream"].get<int>(), 0);
  ExpectFastEqualsRtl(j);
  const auto requests = [](const nlohmann::json& k, const std::string& cache) {
    return k["perf_counts"][cache + "_hit"].get<uint64_t>() + k["perf_counts"][cache + "_miss"].get<uint64_t>();
  };
  // Every entry still goes to the triangle cache once; the list cache is
  // asked once per line instead of once per entry.
  EXPECT_EQ(requests(j, "tri"), requests(dj, "tri"));
  EXPECT_EQ(requests(dj, "list"), requests(dj, "tri"));
  EXPECT_LT(requests(j, "list"), requests(j, "tri"));
  const RunResult c = RunKdrt(common + " --cores 2 --ray-chunk 16 --model both -o " + Path("c.png") +
                              " --json " + Path("c.json"));
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const nlohmann::json cj = ReadJson(Path("c.json"));
  ASSERT_TRUE(cj.contains("per_core"));
  ExpectFastEqualsRtl(cj);
  const RunResult bad = RunKdrt(common + " --list-stream 2 -o " + Path("b.png"));
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_FALSE(fs::exists(Path("b.png")));
}

// Rays lying in the kd-tree's split planes (a NaN split distance: both
// children, and no early stop while the far child waits on the stack,
// InPlane in trace/traversal.h and rtl/rt_leaf_exit.sv): the RTL returns the
// reference's records (kdrt sim checks every ray and fails on the first
// difference) and the fast model the RTL's cycles, in every preset.
class InPlaneRays : public SimCli, public ::testing::WithParamInterface<const char*> {};

TEST_P(InPlaneRays, SimMatchesTheReference) {
  const testing::Prepared p(GenerateScene("gears", 1500));
  const std::vector<Ray> rays = testing::SplitPlaneRays(p.view(), 5);
  ASSERT_GE(rays.size(), 200u);
  WriteRaysFile(Path("plane.rays"), rays);
  const RunResult r = RunKdrt("sim gen:gears:1500 --rays " + Path("plane.rays") + " --format " + GetParam() +
                              CoreFor(GetParam()) + " --model both -q -o " + Path("x.png") + " --json " +
                              Path("x.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = ReadJson(Path("x.json"));
  EXPECT_EQ(j["rays"].get<size_t>(), rays.size());
  EXPECT_GT(j["hits"].get<size_t>(), rays.size() / 10);
  EXPECT_EQ(j["fast"]["error"].get<double>(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Presets, InPlaneRays, ::testing::Values("fp32", "fp24", "bf16", "fp16"));

TEST_F(SimCli, FastModelOptionErrors) {
  for (const std::string& bad : std::vector<std::string>{"--model slow", "--model fast --trace " + Path("w.fst"),
                                                          "--model fast --systemc"}) {
    const RunResult r = RunKdrt("sim gen:room:300 --res 8x8 -o " + Path("x.png") + " " + bad);
    EXPECT_EQ(r.exit_code, 1) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--model"), std::string::npos) << r.output;
  }
  EXPECT_EQ(FileCount(), 0u);
}

// Coherent primary rays ask for the same node lines at once: the node cache
// merges those misses into one fetch (rtl/rt_cache.sv, CacheTargets), and
// the report counts them.
TEST_F(SimCli, CoherentRaysMergeNodeMisses) {
  const RunResult s = RunKdrt("sim gen:balls:800 --res 32x32 -q -o " + Path("sim.png") + " --json " + Path("sim.json"));
  ASSERT_EQ(s.exit_code, 0) << s.output;
  const nlohmann::json j = ReadJson(Path("sim.json"));
  EXPECT_EQ(j["model"]["CacheTargets"].get<int>(), 4);
  EXPECT_GT(j["waits"]["node"]["merged_misses"].get<uint64_t>(), 0u);
  ExpectConsistentBreakdown(j);
}

// Rays aimed at the vertices and edges of a closed mesh, through a ray file.
TEST_F(SimCli, RayFileMatchesRender) {
  ASSERT_EQ(RunKdrt("rays --mesh sphere --size 6 --scene-out " + Path("sphere.nff") + " --rays-out " + Path("rays.bin"))
                .exit_code,
            0);
  for (const char* format : {"fp32", "bf16"}) {
    const std::string common = Path("sphere.nff") + " --rays " + Path("rays.bin") + " --format " + format;
    const RunResult r = RunKdrt("render " + common + " -q --hits " + Path("render.exr"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const RunResult s = RunKdrt("sim " + common + CoreFor(format) + " -q --hits " + Path("sim.exr"));
    ASSERT_EQ(s.exit_code, 0) << s.output;
    ExpectSameHitBuffers(Path("render.exr"), Path("sim.exr"));
  }
}

// Slower, narrower memory: other cycles, the same answers.
TEST_F(SimCli, MemoryTimingChangesCyclesNotHits) {
  const std::string common = "gen:balls:500 --res 16x16 -q -o " + Path("x.png");
  ASSERT_EQ(RunKdrt("sim " + common + " --hits " + Path("a.exr") + " --json " + Path("a.json")).exit_code, 0);
  const RunResult slow = RunKdrt("sim " + common + " --mem-latency 80 --mem-bw 2.5 --hits " + Path("b.exr") +
                             " --json " + Path("b.json"));
  ASSERT_EQ(slow.exit_code, 0) << slow.output;
  ExpectSameHitBuffers(Path("a.exr"), Path("b.exr"));
  const nlohmann::json a = ReadJson(Path("a.json")), b = ReadJson(Path("b.json"));
  EXPECT_GT(b["cycles"].get<uint64_t>(), a["cycles"].get<uint64_t>());
  EXPECT_EQ(b["memory"]["latency"].get<int>(), 80);
  EXPECT_LE(b["memory"]["bytes_per_cycle_used"].get<double>(), 2.5 + 1e-9);
}

// The memory answers one 16-byte beat a cycle: a wider --mem-bw runs as 16,
// and the run says so (stderr and JSON) and counts its memory bound at 16.
TEST_F(SimCli, BandwidthAboveThePortWarns) {
  const std::string common = "sim gen:balls:500 --res 16x16 --model fast -q -o " + Path("x.png");
  ASSERT_EQ(RunKdrt(common + " --json " + Path("a.json")).exit_code, 0);
  const RunResult wide = RunKdrt(common + " --mem-bw 64 --json " + Path("b.json"));
  ASSERT_EQ(wide.exit_code, 0) << wide.output;
  EXPECT_NE(wide.output.find("kdrt: warning: --mem-bw 64: the memory answers one 16-byte beat a cycle"),
            std::string::npos)
      << wide.output;
  const nlohmann::json a = ReadJson(Path("a.json")), b = ReadJson(Path("b.json"));
  EXPECT_EQ(b["cycles"], a["cycles"]);
  EXPECT_EQ(b["memory"]["bytes_per_cycle"].get<double>(), 64.0);
  EXPECT_EQ(b["memory"]["bytes_per_cycle_effective"].get<double>(), 16.0);
  EXPECT_DOUBLE_EQ(b["memory_bound_cycles_per_ray"].get<double>(), a["memory_bound_cycles_per_ray"].get<double>());
  ASSERT_EQ(b["warnings"].size(), 1u);
  EXPECT_NE(b["warnings"][0].get<std::string>().find("--mem-bw 64"), std::string::npos);
  EXPECT_TRUE(a["warnings"].empty());
}

// --trav-format on kdrt sim: a core whose ray setup, clip and traversal unit
// compute in fp32 beside an fp16 test (rt_core TravE, TravM), its own model.
// Its hit records are kdrt render --trav-format's bit for bit (the harness
// checks every ray), it tests fewer triangles than fp16 traversing in
// itself, the fast model follows it cycle for cycle, and no warning is given
// (it is not an estimate). A traversal narrower than the test, or wider than
// fp32, is refused with nothing written.
TEST_F(SimCli, WiderTraversalRunsInTheRtl) {
  const std::string common = "gen:balls:2000 --res 24x24 --format fp16 -q";
  const RunResult sim = RunKdrt("sim " + common + SmallCore() + " --model both --trav-format fp32 -o " + Path("a.png") +
                                " --hits " + Path("a.exr") + " --json " + Path("a.json"));
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  ASSERT_EQ(RunKdrt("render " + common + " --trav-format fp32 -o " + Path("r.png") + " --hits " + Path("r.exr"))
                .exit_code,
            0);
  ExpectSameHitBuffers(Path("a.exr"), Path("r.exr"));
  ASSERT_EQ(RunKdrt("sim " + common + SmallCore() + " --model fast -o " + Path("b.png") + " --json " + Path("b.json"))
                .exit_code,
            0);
  const nlohmann::json a = ReadJson(Path("a.json")), b = ReadJson(Path("b.json"));
  EXPECT_EQ(a["model"]["TravE"], 8);
  EXPECT_EQ(a["model"]["TravM"], 23);
  EXPECT_EQ(a["model"]["E"], 5);
  EXPECT_EQ(b["model"]["TravE"], 5);
  EXPECT_EQ(b["model"]["TravM"], 10);
  EXPECT_TRUE(a["warnings"].empty()) << a["warnings"];
  EXPECT_EQ(a["cycle_model"], "rtl");
  EXPECT_EQ(a["fast"]["error"].get<double>(), 0.0);
  EXPECT_LT(a["reference_per_ray"]["tri_tests"].get<double>(), b["reference_per_ray"]["tri_tests"].get<double>());
  for (const std::string& bad : {std::string("--trav-format bf16"), std::string("--trav-format fp64")}) {
    const RunResult r = RunKdrt("sim " + common + " " + bad + " -o " + Path("c.png"));
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_NE(r.output.find(bad == "--trav-format bf16" ? "does not hold every value of fp16" : "at most e8m23"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(Path("c.png"))) << bad;
  }
}

// --image-format on kdrt sim: an fp32 core reading a bf16 image (rt_core
// ImgE, ImgM: splits and vertices stored in 16 bits, widened exactly on
// load), its own model. Its hit records are kdrt render --image-format bf16's
// bit for bit (the harness checks every ray), they differ from the fp32
// image's (the geometry moved), it reads fewer bytes than the fp32 core, and
// the fast model follows it cycle for cycle. An image wider than the core's
// format is refused with nothing written.
TEST_F(SimCli, NarrowerImageRunsInTheRtl) {
  const std::string common = "gen:balls:2000 --res 24x24 -q";
  const RunResult sim = RunKdrt("sim " + common + SmallCore() + " --model both --image-format bf16 -o " + Path("a.png") +
                                " --hits " + Path("a.exr") + " --json " + Path("a.json"));
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  ASSERT_EQ(RunKdrt("render " + common + " --image-format bf16 -o " + Path("r.png") + " --hits " + Path("r.exr"))
                .exit_code,
            0);
  ExpectSameHitBuffers(Path("a.exr"), Path("r.exr"));
  ASSERT_EQ(RunKdrt("sim " + common + SmallCore() + " --model fast -o " + Path("b.png") + " --hits " + Path("b.exr") +
                    " --json " + Path("b.json"))
                .exit_code,
            0);
  const nlohmann::json a = ReadJson(Path("a.json")), b = ReadJson(Path("b.json"));
  EXPECT_EQ(a["model"]["E"], 8);
  EXPECT_EQ(a["model"]["M"], 23);
  EXPECT_EQ(a["model"]["ImgE"], 8);
  EXPECT_EQ(a["model"]["ImgM"], 7);
  EXPECT_EQ(b["model"]["ImgM"], 23);
  EXPECT_EQ(a["image_format"], "bf16");
  EXPECT_EQ(a["format"], "fp32");
  EXPECT_EQ(a["fast"]["error"].get<double>(), 0.0);
  EXPECT_LT(a["requirements"]["image_bytes"].get<double>(), b["requirements"]["image_bytes"].get<double>());
  EXPECT_LT(a["memory"]["bytes_read"].get<double>(), b["memory"]["bytes_read"].get<double>());
  // The hits moved with the geometry: some t differs from the fp32 image's.
  int w = 0, h = 0;
  const std::vector<Hit> ha = ReadHitBuffer(Path("a.exr"), &w, &h), hb = ReadHitBuffer(Path("b.exr"), &w, &h);
  ASSERT_EQ(ha.size(), hb.size());
  size_t moved = 0;
  for (size_t i = 0; i < ha.size(); ++i) moved += fp::BitsOf(ha[i].t) != fp::BitsOf(hb[i].t);
  EXPECT_GT(moved, 0u);
  for (const std::string& bad : {std::string("--format fp16 --image-format bf16"),
                                 std::string("--format bf16 --image-format fp32")}) {
    const RunResult r = RunKdrt("sim " + common + " " + bad + " -o " + Path("c.png"));
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_NE(r.output.find("is wider than the datapath's"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(Path("c.png"))) << bad;
  }
}

// The SystemC top ticks the same core and memory model: same hits, same cycles.
TEST_F(SimCli, SystemCLoopGivesTheSameCyclesAndHits) {
  const std::string common = "gen:tetra:300 --res 12x12 --format bf16 -o " + Path("x.png") + CoreFor("bf16");
  const RunResult plain = RunKdrt("sim " + common + " -q --hits " + Path("a.exr") + " --json " + Path("a.json"));
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  const RunResult sc = RunKdrt("sim " + common + " --systemc --hits " + Path("b.exr") + " --json " + Path("b.json"));
  ASSERT_EQ(sc.exit_code, 0) << sc.output;
  EXPECT_EQ(sc.output.find("Copyright"), std::string::npos) << "no SystemC banner";
  ExpectSameHitBuffers(Path("a.exr"), Path("b.exr"));
  const nlohmann::json a = ReadJson(Path("a.json")), b = ReadJson(Path("b.json"));
  EXPECT_EQ(a["loop"], "verilator");
  EXPECT_EQ(b["loop"], "systemc");
  EXPECT_EQ(a["cycles"], b["cycles"]);
  EXPECT_EQ(a["perf_counts"], b["perf_counts"]);
}

// The checker stops at the first record that differs from the (here
// deliberately falsified) reference and says what it knows.
TEST_F(SimCli, MismatchStopsTheRunWithTheRayAndThePath) {
  const RunResult s = RunKdrt("sim gen:room:300 --res 8x8 --corrupt-reference 27 -o " + Path("x.png") +
                              " --hits " + Path("x.exr"));
  EXPECT_EQ(s.exit_code, 3) << s.output;
  EXPECT_NE(s.output.find("co-simulation mismatch"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("ray 27\n"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("model node path"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("RTL:"), std::string::npos) << s.output;
  EXPECT_EQ(FileCount(), 0u);
}

TEST_F(SimCli, TimeoutNamesTheRaysInFlight) {
  // No ray can come back within 5 cycles (the memory alone takes 20).
  const RunResult s = RunKdrt("sim gen:room:300 --res 4x4 --timeout 5 -o " + Path("x.png"));
  EXPECT_EQ(s.exit_code, 3) << s.output;
  EXPECT_NE(s.output.find("timeout: no hit record for 5 cycles"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("rays in flight: 0"), std::string::npos) << s.output;
  EXPECT_EQ(FileCount(), 0u);
}

TEST_F(SimCli, StackSmallerThanTheTreeIsRefused) {
  const RunResult s = RunKdrt("sim gen:balls:500 --res 8x8 --stack-depth 2 -o " + Path("x.png") + " --hits " +
                          Path("x.exr") + " --json " + Path("x.json"));
  EXPECT_NE(s.exit_code, 0);
  EXPECT_NE(s.output.find("--stack-depth >="), std::string::npos) << s.output;
  EXPECT_EQ(FileCount(), 0u);
}

// With --allow-overflow a stack smaller than the tree ends a ray at the push
// that meets the full stack (rt_thread_fsm: TRAV -> DONE). The reference
// does the same with the core's stack, so every record is compared, the
// overflowed rays included, and both must overflow the same rays; the fast
// model gives the RTL's cycles and events.
TEST_F(SimCli, StackOverflowMatchesTheReferenceAndTheFastModel) {
  // fp32 (one model, shared with the mismatch below); KDRT_LONG=1 adds bf16.
  std::vector<const char*> formats = {"fp32"};
  if (LongRun()) formats.push_back("bf16");
  for (const char* format : formats) {
    SCOPED_TRACE(format);
    const RunResult r = RunKdrt(std::string("sim gen:rings:800 --res 16x16 --stack-depth 3 --allow-overflow ") +
                                "--model both -q --format " + format + SmallCore(false) + " -o " + Path("x.png") +
                                " --json " + Path("x.json"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("rays overflowed the traversal stack (StackDepth 3"), std::string::npos) << r.output;
    const nlohmann::json j = ReadJson(Path("x.json"));
    const nlohmann::json& f = j["fast"]["report"];
    EXPECT_GT(j["overflows"].get<uint64_t>(), 0u);
    EXPECT_LT(j["overflows"].get<uint64_t>(), j["rays"].get<uint64_t>());
    EXPECT_EQ(j["perf_counts"]["overflow"], j["overflows"]);
    EXPECT_EQ(f["overflows"], j["overflows"]);
    EXPECT_EQ(f["cycles"], j["cycles"]);
    EXPECT_EQ(f["perf_counts"], j["perf_counts"]);
    EXPECT_EQ(f["thread_states"], j["thread_states"]);
    // ctest builds it as a quick build (KDRT_QUICK_MODELS), and the report says so.
    if (sim::QuickModels()) {
      EXPECT_EQ(j["model_build"], "quick");
    }
  }
  // A reference that disagrees on an overflowed ray's record (ray 150 of
  // these camera rays overflows) is caught.
  const RunResult bad = RunKdrt("sim gen:rings:800 --res 16x16 --stack-depth 3 --allow-overflow -q" + SmallCore(false) +
                                " -o " + Path("y.png") + " --corrupt-reference 150");
  EXPECT_EQ(bad.exit_code, 3) << bad.output;
  EXPECT_NE(bad.output.find("co-simulation mismatch"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("ray 150"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find(", overflow 1"), std::string::npos) << bad.output;
}

TEST_F(SimCli, SceneLargerThanTheMemoryIsRefused) {
  // A memory one cache line smaller than the scene's image.
  const RunResult info = RunKdrt("info gen:balls:500 --json " + Path("info.json"));
  ASSERT_EQ(info.exit_code, 0) << info.output;
  const std::string json = kdrt::testing::ReadFile(Path("info.json"));
  const size_t at = json.find("\"image_bytes\": ");
  ASSERT_NE(at, std::string::npos) << json;
  const uint64_t image_bytes = std::stoull(json.substr(at + 15));
  fs::remove(Path("info.json"));
  const RunResult s = RunKdrt("sim gen:balls:500 --res 8x8 --mem-size " + std::to_string(image_bytes - 64) +
                              " -o " + Path("x.png"));
  EXPECT_NE(s.exit_code, 0);
  EXPECT_NE(s.output.find("memory image needs"), std::string::npos) << s.output;
  const RunResult a = RunKdrt("sim gen:balls:500 --res 8x8 --addr-width 12 -o " + Path("x.png"));
  EXPECT_NE(a.exit_code, 0);
  EXPECT_NE(a.output.find("address width 12 is too small"), std::string::npos) << a.output;
  EXPECT_EQ(FileCount(), 0u);
}

// KDRT_SIM_MODEL_BINARY (the profile training's hook, sim/pgo_train.sh) runs
// the binary it names in place of the model kdrt sim would pick, and a name
// that is no file is an error that writes nothing.
TEST_F(SimCli, ModelBinaryOverrideRunsThatBinaryOrRefuses) {
  const std::string fp32 = std::string(KDRT_MODEL_DIR) + "/kdrt-sim-fp32";
  const RunResult which =
      testing::RunCommand("KDRT_SIM_MODEL_BINARY=" + fp32 + " " + KDRT_BIN + " sim gen:room:300 --which-model");
  ASSERT_EQ(which.exit_code, 0) << which.output;
  EXPECT_NE(which.output.find("executable     " + fp32), std::string::npos) << which.output;
  const RunResult missing = testing::RunCommand("KDRT_SIM_MODEL_BINARY=" + Path("none") + " " + KDRT_BIN +
                                                " sim gen:room:300 --res 4x4 -o " + Path("m.png"));
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find("KDRT_SIM_MODEL_BINARY names no file"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(Path("m.png")));
}

// A core reads the image of its own format: the fp32 model refuses an fp16
// image (as `kdrt info --format fp16 --image` writes it), and the fp16 model
// runs it.
TEST_F(SimCli, ModelRefusesAnImageOfAnotherFormat) {
  ASSERT_EQ(RunKdrt("rays --mesh sphere --size 4 --scene-out " + Path("s.nff") + " --rays-out " + Path("r.bin"))
                .exit_code,
            0);
  ASSERT_EQ(RunKdrt("info " + Path("s.nff") + " --format fp16 --image " + Path("fp16.img")).exit_code, 0);
  const std::string model_dir = KDRT_MODEL_DIR;
  const std::string args = " --image " + Path("fp16.img") + " --rays " + Path("r.bin") + " --hits-out " +
                           Path("h.exr") + " --report-out " + Path("r.json");
  const RunResult wrong = testing::RunCommand(model_dir + "/kdrt-sim-fp32" + args);
  EXPECT_EQ(wrong.exit_code, 1) << wrong.output;
  EXPECT_NE(wrong.output.find("an e5m10 image, but this core computes in fp32"), std::string::npos) << wrong.output;
  EXPECT_FALSE(fs::exists(Path("h.exr")));
  // The fp16 model: the small core's (a run builds it if no other test has).
  ASSERT_EQ(RunKdrt("sim gen:room:300 --res 4x4 --format fp16 -q" + SmallCore() + " -o " + Path("w.png")).exit_code, 0);
  const RunResult which = RunKdrt("sim gen:room:300 --format fp16" + SmallCore() + " --which-model");
  const size_t at = which.output.find("executable     ");
  ASSERT_NE(at, std::string::npos) << which.output;
  const std::string fp16_model = which.output.substr(at + 15, which.output.find(' ', at + 15) - (at + 15));
  const RunResult right = testing::RunCommand(fp16_model + args);
  EXPECT_EQ(right.exit_code, 0) << right.output;
  EXPECT_TRUE(fs::exists(Path("h.exr")));
}

TEST_F(SimCli, Fp64IsRefused) {
  const RunResult s = RunKdrt("sim gen:balls:200 --res 8x8 --format fp64 -o " + Path("x.png") + " --json " +
                              Path("x.json"));
  EXPECT_EQ(s.exit_code, 1) << s.output;
  EXPECT_NE(s.output.find("kdrt: error: "), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("no RTL model computes in fp64"), std::string::npos) << s.output;
  EXPECT_EQ(FileCount(), 0u);
}

// The sphere of `kdrt rays` beside a triangle 1e5 away (docs/precision.md):
// fp16 cannot hold it. The front end warns (stderr and JSON) and runs the
// model, or with --strict refuses before building or running one.
TEST_F(SimCli, FormatBelowTheRequirementWarnsOrWithStrictFails) {
  const testing::MeshAndRays m = testing::SphereInStadium(1e5);
  std::vector<Ray> some;  // every 64th: each walks the whole tree in fp16
  for (size_t i = 0; i < m.rays.size(); i += 64) some.push_back(m.rays[i]);
  WriteNff(m.scene, Path("far.nff"));
  WriteRaysFile(Path("far.bin"), some);
  const std::string base = "sim " + Path("far.nff") + " --rays " + Path("far.bin") + " --format fp16 -q" + CoreFor("fp16");

  RunResult s = RunKdrt(base + " --strict --hits " + Path("s.exr") + " --json " + Path("s.json"));
  EXPECT_EQ(s.exit_code, 1) << s.output;
  EXPECT_NE(s.output.find("kdrt: error: fp16 cannot represent this scene: "), std::string::npos) << s.output;
  EXPECT_EQ(FileCount(), 2u);  // the inputs

  s = RunKdrt(base + " --hits " + Path("w.exr") + " --json " + Path("w.json"));
  ASSERT_EQ(s.exit_code, 0) << s.output;
  const size_t at = s.output.find("kdrt: warning: fp16 cannot represent this scene: ");
  ASSERT_NE(at, std::string::npos) << s.output;
  const nlohmann::json j = ReadJson(Path("w.json"));
  ASSERT_EQ(j["warnings"].size(), 1u);
  EXPECT_EQ("kdrt: warning: " + j["warnings"][0].get<std::string>(),
            s.output.substr(at, s.output.find('\n', at) - at));
  EXPECT_LT(j["hits"].get<uint64_t>(), some.size() / 2);  // most rays miss, and the warning says why
}

// A quick build (KDRT_QUICK_MODELS) lives beside the optimised model of the
// same key, never in its place; the prebuilt models are always optimised.
TEST_F(SimCli, QuickModelsAreKeptApartAndMarked) {
  const std::string args = "sim gen:room:300 --node-cache-lines 128 --which-model";
  const RunResult quick = testing::RunCommand("env KDRT_QUICK_MODELS=1 " + std::string(KDRT_BIN) + " " + args);
  const RunResult full = testing::RunCommand("env KDRT_QUICK_MODELS=0 " + std::string(KDRT_BIN) + " " + args);
  ASSERT_EQ(quick.exit_code, 0) << quick.output;
  ASSERT_EQ(full.exit_code, 0) << full.output;
  EXPECT_NE(quick.output.find(".quick/kdrt-sim"), std::string::npos) << quick.output;
  EXPECT_NE(quick.output.find("a quick build, one unit at -O1"), std::string::npos) << quick.output;
  EXPECT_EQ(full.output.find(".quick"), std::string::npos) << full.output;
  EXPECT_EQ(full.output.find("quick build"), std::string::npos) << full.output;
  const RunResult prebuilt = testing::RunCommand("env KDRT_QUICK_MODELS=1 " + std::string(KDRT_BIN) +
                                        " sim gen:room:300 --res 4x4 -q -o " + Path("x.png") + " --json " +
                                        Path("x.json"));
  ASSERT_EQ(prebuilt.exit_code, 0) << prebuilt.output;
  EXPECT_EQ(ReadJson(Path("x.json"))["model_build"], "optimised");
}

// tests/sim/test_models.txt, the quick models `make test` builds before
// ctest, are the models of the tests' cores (tests/common/test_cores.h): a
// core missing from it would be built inside a test, a model no test uses
// would be built for nothing.
TEST(TestModels, ListIsTheTestsCores) {
  std::set<std::string> listed;
  {
    std::ifstream f(std::string(KDRT_SOURCE_DIR) + "/tests/sim/test_models.txt");
    ASSERT_TRUE(f.good());
    std::string line;
    while (std::getline(f, line)) {
      if (!line.empty() && line[0] != '#') listed.insert(line.substr(0, line.find(' ')));
    }
  }
  std::set<std::string> asked;
  for (const std::string& core : testing::TestModelCores()) {
    const RunResult r = testing::RunCommand("env KDRT_QUICK_MODELS=1 " + std::string(KDRT_BIN) +
                                            " sim gen:rings:800 --which-model " + core);
    ASSERT_EQ(r.exit_code, 0) << core << "\n" << r.output;
    const size_t end = r.output.find("/kdrt-sim");
    const size_t begin = r.output.rfind("sim-models/", end);
    ASSERT_TRUE(end != std::string::npos && begin != std::string::npos) << core << "\n" << r.output;
    asked.insert(r.output.substr(begin + 11, end - begin - 11));
  }
  EXPECT_EQ(listed, asked);
}

TEST_F(SimCli, ModelChoiceFollowsTheScene) {
  const RunResult def = RunKdrt("sim gen:room:300 --which-model");
  ASSERT_EQ(def.exit_code, 0) << def.output;
  EXPECT_NE(def.output.find("(prebuilt)"), std::string::npos) << def.output;
  // A cache override needs a model of its own, sized for the scene.
  const RunResult own = RunKdrt("sim gen:room:300 --node-cache-lines 128 --which-model");
  ASSERT_EQ(own.exit_code, 0) << own.output;
  EXPECT_NE(own.output.find("scene-sized"), std::string::npos) << own.output;
  EXPECT_NE(own.output.find("c128.64.256"), std::string::npos) << own.output;
}

TEST_F(SimCli, TraceWritesAnFstWaveform) {
  const std::string common = "gen:room:300 --res 4x4 -q -o " + Path("x.png");
  ASSERT_EQ(RunKdrt("sim " + common + " --trace " + Path("all.fst")).exit_code, 0);
  ASSERT_EQ(RunKdrt("sim " + common + " --trace " + Path("one.fst") + " --trace-ray 5").exit_code, 0);
  const std::string all = kdrt::testing::ReadFile(Path("all.fst")), one = kdrt::testing::ReadFile(Path("one.fst"));
  ASSERT_GT(all.size(), 64u);
  ASSERT_GT(one.size(), 64u);
  EXPECT_EQ(all[0], 0) << "an FST file starts with its header block (type 0)";
  EXPECT_LT(one.size(), all.size()) << "one ray's window is a part of the whole run";
  EXPECT_NE(RunKdrt("sim " + common + " --trace-ray 5").exit_code, 0) << "--trace-ray needs --trace";
}

// The scene file is opened once per run (by the front end; the model gets
// the memory image): inotify counts the opens of the file while kdrt runs.
TEST_F(SimCli, SceneFileIsOpenedOnce) {
  const std::string scene = Path("scene.nff");
  {
    std::ifstream in(std::string(KDRT_SOURCE_DIR) + "/scenes/simple.nff");
    std::ofstream out(scene);
    out << in.rdbuf();
  }
  const int fd = inotify_init1(IN_NONBLOCK);
  ASSERT_GE(fd, 0);
  ASSERT_GE(inotify_add_watch(fd, scene.c_str(), IN_OPEN), 0);
  const RunResult s = RunKdrt("sim " + scene + " --res 8x8 -q -o " + Path("x.png"));
  ASSERT_EQ(s.exit_code, 0) << s.output;
  int opens = 0;
  alignas(inotify_event) char buf[4096];
  ssize_t n;
  while ((n = read(fd, buf, sizeof buf)) > 0) {
    for (char* p = buf; p < buf + n; p += sizeof(inotify_event) + reinterpret_cast<inotify_event*>(p)->len) {
      opens += (reinterpret_cast<inotify_event*>(p)->mask & IN_OPEN) != 0;
    }
  }
  close(fd);
  EXPECT_EQ(opens, 1);
}

TEST_F(SimCli, CompareReportsTheFirstDifference) {
  const std::string common = "gen:room:300 --res 8x8 -q -o " + Path("x.png");
  ASSERT_EQ(RunKdrt("render " + common + " --hits " + Path("a.exr")).exit_code, 0);
  ASSERT_EQ(RunKdrt("render " + common + " --hits " + Path("b.exr")).exit_code, 0);
  const RunResult same = RunKdrt("compare " + Path("a.exr") + " " + Path("b.exr"));
  EXPECT_EQ(same.exit_code, 0);
  EXPECT_NE(same.output.find("identical"), std::string::npos);
  int w = 0, h = 0;
  std::vector<Hit> hits = ReadHitBuffer(Path("b.exr"), &w, &h);
  hits[3 * w + 5].t = hits[3 * w + 5].t * 2.0f + 1.0f;
  WriteHitBuffer(Path("c.exr"), w, h, hits);
  const RunResult diff = RunKdrt("compare " + Path("a.exr") + " " + Path("c.exr"));
  EXPECT_NE(diff.exit_code, 0);
  EXPECT_NE(diff.output.find("pixel (5, 3)"), std::string::npos) << diff.output;
}

}  // namespace
}  // namespace kdrt
