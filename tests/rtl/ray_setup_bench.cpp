// Verilator bench of rtl/rt_ray_setup.sv against the model's SetupRay on
// SoftArith (sw/trace/intersect.h), per preset. Every output is checked (o,
// d, 1/d, tmin, tmax, kx, ky, kz, sx, sy, sz, tag), with random input bubbles
// and output backpressure; the first mismatch stops the run. Cases: every
// direction whose components come from a set of ties, signed zeros and
// special values, then random rays (1e6 per preset, 1e7 with KDRT_LONG=1).
#include <array>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "Vrt_ray_setup_bf16.h"
#include "Vrt_ray_setup_fp16.h"
#include "Vrt_ray_setup_fp24.h"
#include "Vrt_ray_setup_fp32.h"
#include "tests/rtl/isect_bench_util.h"
#include "tests/rtl/stream_bench.h"
#include "trace/intersect.h"

namespace kdrt::rtlbench {
namespace {

using fp::Format;
using fp::SoftArith;

constexpr uint32_t kTagMask = 0xFF;

// docs/isect-unit.md: load 1, compare 1, divide M + 4.
unsigned DocumentedLatency(Format f) { return 6 + static_cast<unsigned>(f.m); }

// The unit's outputs in one comparable record.
struct Out {
  std::array<uint32_t, 14> v{};  // o[3], d[3], inv[3], tmin, tmax, sx, sy, sz
  int kx = 0, ky = 0, kz = 0;
  uint32_t tag = 0;
  bool operator==(const Out& o) const {
    return v == o.v && kx == o.kx && ky == o.ky && kz == o.kz && tag == o.tag;
  }
};

Out Model(const SoftArith& a, const Ray& ray) {
  const RaySetup<SoftArith> r = SetupRay(a, ray);
  Out o;
  for (int i = 0; i < 3; ++i) {
    o.v[i] = r.o[i];
    o.v[3 + i] = r.d[i];
    o.v[6 + i] = r.inv_d[i];
  }
  o.v[9] = r.tmin;
  o.v[10] = r.tmax;
  o.v[11] = r.sx;
  o.v[12] = r.sy;
  o.v[13] = r.sz;
  o.kx = r.kx;
  o.ky = r.ky;
  o.kz = r.kz;
  return o;
}

std::string OutString(Format f, const Out& o) {
  static const char* kNames[14] = {"o.x", "o.y", "o.z", "d.x", "d.y",  "d.z", "inv.x",
                                   "inv.y", "inv.z", "tmin", "tmax", "sx", "sy",  "sz"};
  std::string s;
  for (int i = 0; i < 14; ++i) s += std::string(i % 3 == 0 ? "\n    " : "  ") + kNames[i] + " " + Fmt(f, o.v[i]);
  s += "\n    kx " + std::to_string(o.kx) + " ky " + std::to_string(o.ky) + " kz " + std::to_string(o.kz);
  return s;
}

// Direction components that make ties in |d|, signed zeros and specials.
std::vector<Ray> DirectedRays() {
  const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, -2.0f, 0.5f, 1.0000001f, -0.99999994f,
                          NAN, INFINITY, -INFINITY, 1e-40f, -1e-40f, 1e30f, 3e-30f};
  std::vector<Ray> rays;
  for (float x : values) {
    for (float y : values) {
      for (float z : values) {
        Ray r;
        r.o = {x, -y, 0.25f};
        r.d = {x, y, z};
        r.tmin = y;
        r.tmax = z;
        rays.push_back(r);
      }
    }
  }
  return rays;
}

Ray RandomRay(Rng& rng) {
  Ray r;
  const double scale = std::pow(10.0, rng.Uniform(-3, 3));
  for (int i = 0; i < 3; ++i) {
    r.o[i] = static_cast<float>(rng.Gauss() * scale);
    r.d[i] = static_cast<float>(rng.Gauss() * std::pow(10.0, rng.Uniform(-2, 2)));
  }
  if (rng.Chance(0.1)) r.d[rng.Below(3)] = 0.0f;
  if (rng.Chance(0.05)) r.d[rng.Below(3)] = r.d[rng.Below(3)] * (rng.Chance(0.5) ? -1.0f : 1.0f);  // ties
  if (rng.Chance(0.02)) r.d[rng.Below(3)] = SpecialF32(rng);
  if (rng.Chance(0.02)) r.o[rng.Below(3)] = SpecialF32(rng);
  r.tmin = rng.Chance(0.7) ? 0.0f : static_cast<float>(rng.LogUniform(1e-6, 1e6));
  r.tmax = rng.Chance(0.6) ? INFINITY : r.tmin + static_cast<float>(rng.LogUniform(1e-6, 1e6));
  if (rng.Chance(0.01)) r.tmin = SpecialF32(rng);
  if (rng.Chance(0.01)) r.tmax = SpecialF32(rng);
  return r;
}

struct In {
  Ray ray;
  uint32_t tag = 0;
};

template <class Dut>
bool RunPreset(Format f, uint64_t random_count) {
  const auto start = std::chrono::steady_clock::now();
  const SoftArith a(f);
  const int w = f.Width();
  SimCtrl<Dut> sim;
  sim.top().in_valid_i = 0;
  sim.top().out_ready_i = 1;
  sim.Reset();
  Rng rng(500 + f.m);

  StreamUnit<Dut, In, Out> unit;
  unit.name = "rt_ray_setup " + f.Name();
  unit.drive = [](Dut& dut, const In& in) {
    const Ray& r = in.ray;
    const float words[8] = {r.o[0], r.o[1], r.o[2], r.d[0], r.d[1], r.d[2], r.tmin, r.tmax};
    for (int j = 0; j < 8; ++j) PutBits(dut.in_ray_i, 32 * j, 32, fp::BitsOf(words[j]));
    dut.in_tag_i = in.tag;
  };
  unit.read = [w](const Dut& dut) {
    Out o;
    for (int i = 0; i < 3; ++i) {
      o.v[i] = static_cast<uint32_t>(GetBits(dut.out_o_o, i * w, w));
      o.v[3 + i] = static_cast<uint32_t>(GetBits(dut.out_d_o, i * w, w));
      o.v[6 + i] = static_cast<uint32_t>(GetBits(dut.out_inv_o, i * w, w));
    }
    o.v[9] = dut.out_tmin_o;
    o.v[10] = dut.out_tmax_o;
    o.v[11] = dut.out_sx_o;
    o.v[12] = dut.out_sy_o;
    o.v[13] = dut.out_sz_o;
    o.kx = dut.out_kx_o;
    o.ky = dut.out_ky_o;
    o.kz = dut.out_kz_o;
    o.tag = dut.out_tag_o;
    return o;
  };
  unit.model = [&](const In& in) {
    Out o = Model(a, in.ray);
    o.tag = in.tag;
    return o;
  };
  unit.report = [&](const In& in, const Out& want, const Out& got, uint64_t index) {
    std::printf("FAIL rt_ray_setup %s: first mismatch at ray %llu\n  %s\n  model (tag %u):%s\n  rtl (tag %u):%s\n",
                f.Name().c_str(), static_cast<unsigned long long>(index), RayString(in.ray).c_str(), want.tag,
                OutString(f, want).c_str(), got.tag, OutString(f, got).c_str());
  };

  // Latency on an idle pipe.
  const unsigned latency = MeasureLatency(sim, unit, In{Ray{{0, 0, 0}, {1, 2, 3}, 0.0f, 1.0f}, 0});
  std::printf("rt_ray_setup %s: latency %u cycles (documented %u)\n", f.Name().c_str(), latency,
              DocumentedLatency(f));
  if (latency != DocumentedLatency(f)) {
    std::printf("FAIL rt_ray_setup %s: latency %u, documented %u\n", f.Name().c_str(), latency,
                DocumentedLatency(f));
    return false;
  }

  const std::vector<Ray> directed = DirectedRays();
  const uint64_t total = directed.size() + random_count;
  uint64_t issued = 0;
  uint32_t tag = 0;
  Rng stim(99);
  unit.next = [&](In& in) {
    if (issued >= total) return false;
    in.ray = issued < directed.size() ? directed[issued] : RandomRay(stim);
    in.tag = tag;
    tag = (tag + 1) & kTagMask;
    ++issued;
    return true;
  };
  StreamTraffic traffic;
  traffic.ready = {1.0, 0.9, 0.5, 0.1};
  traffic.gap = {0.0, 0.2, 0.7};
  StreamStats stats;
  if (!RunStream(sim, rng, traffic, unit, &stats)) return false;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("PASS rt_ray_setup %s: %llu rays (%zu directed), %llu cycles, %.1f s\n", f.Name().c_str(),
              static_cast<unsigned long long>(stats.results), directed.size(),
              static_cast<unsigned long long>(stats.cycles), seconds);
  std::fflush(stdout);
  return stats.results == total;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  using namespace kdrt::fp;
  Verilated::commandArgs(argc, argv);
  uint64_t count = LongRun() ? 10000000ull : 1000000ull;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--count") count = std::strtoull(argv[i + 1], nullptr, 10);
  }
  bool ok = RunPreset<Vrt_ray_setup_fp32>(kFp32, count);
  ok = RunPreset<Vrt_ray_setup_fp24>(kFp24, count) && ok;
  ok = RunPreset<Vrt_ray_setup_bf16>(kBf16, count) && ok;
  ok = RunPreset<Vrt_ray_setup_fp16>(kFp16, count) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
