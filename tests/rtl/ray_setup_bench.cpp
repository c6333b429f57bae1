// Verilator bench of rtl/rt_ray_setup.sv against the model's SetupRay on
// SoftArith (sw/trace/intersect.h), per preset. Every output is checked (o,
// d, 1/d, tmin, tmax, kx, ky, kz, sx, sy, sz, tag), with random input bubbles
// and output backpressure; the first mismatch stops the run. Cases: every
// direction whose components come from a set of ties, signed zeros and
// special values, then random rays (1e6 per preset, 1e7 with KDRT_LONG=1).
#include <array>
#include <chrono>
#include <cstdio>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "Vrt_ray_setup_bf16.h"
#include "Vrt_ray_setup_fp16.h"
#include "Vrt_ray_setup_fp24.h"
#include "Vrt_ray_setup_fp32.h"
#include "tests/rtl/isect_bench_util.h"
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
  bool operator==(const Out& o) const { return v == o.v && kx == o.kx && ky == o.ky && kz == o.kz; }
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

template <class Dut>
bool RunPreset(Format f, uint64_t random_count) {
  const auto start = std::chrono::steady_clock::now();
  const SoftArith a(f);
  const int w = f.Width();
  Dut dut;
  Rng rng(500 + f.m);
  auto tick = [&] {
    dut.clk_i = 0;
    dut.eval();
    dut.clk_i = 1;
    dut.eval();
  };
  auto drive = [&](const Ray& r, uint32_t tag) {
    float words[8] = {r.o[0], r.o[1], r.o[2], r.d[0], r.d[1], r.d[2], r.tmin, r.tmax};
    for (int j = 0; j < 8; ++j) PutBits(dut.in_ray_i, 32 * j, 32, fp::BitsOf(words[j]));
    dut.in_tag_i = tag;
  };
  auto read = [&]() {
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
    return o;
  };
  dut.clk_i = 0;
  dut.rst_ni = 0;
  dut.in_valid_i = 0;
  dut.out_ready_i = 1;
  dut.eval();
  dut.rst_ni = 1;
  dut.eval();

  // Latency on an idle pipe.
  drive(Ray{{0, 0, 0}, {1, 2, 3}, 0.0f, 1.0f}, 0);
  dut.in_valid_i = 1;
  tick();
  dut.in_valid_i = 0;
  unsigned latency = 1;
  while (!dut.out_valid_o && latency < 1000) {
    tick();
    ++latency;
  }
  tick();
  std::printf("rt_ray_setup %s: latency %u cycles (documented %u)\n", f.Name().c_str(), latency,
              DocumentedLatency(f));
  if (latency != DocumentedLatency(f)) {
    std::printf("FAIL rt_ray_setup %s: latency %u, documented %u\n", f.Name().c_str(), latency,
                DocumentedLatency(f));
    return false;
  }

  const std::vector<Ray> directed = DirectedRays();
  const uint64_t total = directed.size() + random_count;
  uint64_t issued = 0, checked = 0, cycles = 0;
  Rng stim(99);
  struct InFlight {
    Ray ray;
    Out want;
    uint32_t tag;
  };
  std::deque<InFlight> flight;
  Ray cur;
  bool have = false, offering = false, waiting_out = false;
  Out last_out;
  uint32_t last_tag = 0, tag = 0;
  double p_ready = 1.0, p_gap = 0.0;
  for (;; ++cycles) {
    if (cycles % 512 == 0) {
      p_ready = std::array<double, 4>{1.0, 0.9, 0.5, 0.1}[rng.Below(4)];
      p_gap = std::array<double, 3>{0.0, 0.2, 0.7}[rng.Below(3)];
    }
    if (!have && issued < total) {
      cur = issued < directed.size() ? directed[issued] : RandomRay(stim);
      ++issued;
      have = true;
    }
    if (!have && flight.empty()) break;
    if (!offering && have && !rng.Chance(p_gap)) {
      offering = true;
      drive(cur, tag);
    }
    dut.in_valid_i = offering;
    dut.out_ready_i = rng.Chance(p_ready);
    dut.clk_i = 0;
    dut.eval();
    const Out got = read();
    const uint32_t got_tag = dut.out_tag_o;
    if (waiting_out && (!dut.out_valid_o || !(got == last_out) || got_tag != last_tag)) {
      std::printf("FAIL rt_ray_setup %s: output changed while out_ready_i was low\n", f.Name().c_str());
      return false;
    }
    waiting_out = dut.out_valid_o && !dut.out_ready_i;
    last_out = got;
    last_tag = got_tag;
    const bool in_fire = offering && dut.in_ready_o;
    if (dut.out_valid_o && dut.out_ready_i) {
      if (flight.empty()) {
        std::printf("FAIL rt_ray_setup %s: a result with no ray in flight\n", f.Name().c_str());
        return false;
      }
      const InFlight& x = flight.front();
      if (!(got == x.want) || got_tag != x.tag) {
        std::printf("FAIL rt_ray_setup %s: first mismatch at ray %llu\n  %s\n  model (tag %u):%s\n  rtl (tag %u):%s\n",
                    f.Name().c_str(), static_cast<unsigned long long>(checked), RayString(x.ray).c_str(), x.tag,
                    OutString(f, x.want).c_str(), got_tag, OutString(f, got).c_str());
        return false;
      }
      flight.pop_front();
      ++checked;
    }
    dut.clk_i = 1;
    dut.eval();
    if (in_fire) {
      flight.push_back({cur, Model(a, cur), tag});
      tag = (tag + 1) & kTagMask;
      have = offering = false;
    }
  }
  dut.final();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("PASS rt_ray_setup %s: %llu rays (%zu directed), %llu cycles, %.1f s\n", f.Name().c_str(),
              static_cast<unsigned long long>(checked), directed.size(), static_cast<unsigned long long>(cycles),
              seconds);
  std::fflush(stdout);
  return checked == total;
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
