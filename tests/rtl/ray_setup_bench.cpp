// Verilator bench of rtl/rt_ray_setup.sv against the model, per preset: the
// world ray mapped into the image's frame (ToFrame, sw/trace/frame.h) and
// then SetupRay on SoftArith (sw/trace/intersect.h). Every output is checked
// (the distance scale k, o, d, 1/d, tmin, tmax, kx, ky, kz, sx, sy, sz, tag),
// with random input bubbles and output backpressure; the first mismatch stops
// the run. The frame is part of each input (the unit samples it with the
// ray), so every ray has its own: origins from 0 to 1e30, scales over the
// whole range -160..160. Cases: every direction whose components come from a
// set of ties, signed zeros and special values, in four frames; then random
// rays (3e5 per preset, 1e7 with KDRT_LONG=1), with direction components
// of any magnitude (subnormal to fp32's largest, mixed within one ray).
// With a traversal wider than the test (TravE, TravM; the configurations
// name:E:M:TE:TM in tests/rtl/CMakeLists.txt) out_inv_o is the model's
// TraversalRay's inv_d (1 / d in the traversal format, of the test's d
// widened, after the flushed-shear rule); every other output is SetupRay's
// in the test format, as before.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "Vrt_ray_setup_bf16.h"
#include "Vrt_ray_setup_bf16t32.h"
#include "Vrt_ray_setup_fp16.h"
#include "Vrt_ray_setup_fp16t24.h"
#include "Vrt_ray_setup_fp16t32.h"
#include "Vrt_ray_setup_fp24.h"
#include "Vrt_ray_setup_fp32.h"
#include "sim/unit_latency.h"
#include "tests/rtl/isect_bench_util.h"
#include "tests/rtl/stream_bench.h"
#include "trace/frame.h"
#include "trace/intersect.h"
#include "trace/traversal.h"

namespace kdrt::rtlbench {
namespace {

using fp::Format;
using fp::SoftArith;

constexpr uint32_t kTagMask = 0xFF;

unsigned DocumentedLatency(Format f, Format trav) { return sim::latency::RaySetup(f, trav); }

constexpr int kScaleWidth = 9;    // kdrt_pkg::FrameScaleWidth
constexpr int kTScaleWidth = 10;  // kdrt_pkg::TScaleWidth

// The unit's outputs in one comparable record.
struct Out {
  std::array<uint32_t, 14> v{};  // o[3], d[3], inv[3], tmin, tmax, sx, sy, sz
  int kx = 0, ky = 0, kz = 0;
  int t_scale = 0;
  uint32_t tag = 0;
  bool operator==(const Out& o) const {
    return v == o.v && kx == o.kx && ky == o.ky && kz == o.kz && t_scale == o.t_scale && tag == o.tag;
  }
};

// How often the mixed runs reach the traversal's cases.
struct Coverage {
  uint64_t inv_inf = 0;    // a zero d (loaded as one or flushed by the shear rule)
  uint64_t flushed = 0;    // the flushed-shear rule zeroed a component
  uint64_t inv_nan = 0;
  uint64_t wider = 0;      // inv_d not a value of the test format (the wide division mattered)
};

// `at` is the traversal's arithmetic (the same format as `a` unless the
// traversal is wider): then inv_d is TraversalRay's.
Out Model(const SoftArith& a, const SoftArith& at, const Ray& world, const Frame& frame, Coverage* cov) {
  const FramedRay framed = ToFrame(world, frame);
  const RaySetup<SoftArith> r = SetupRay(a, framed.ray);
  const bool mixed = a.format() != at.format();
  Out o;
  o.t_scale = framed.t_scale_log2;
  for (int i = 0; i < 3; ++i) {
    o.v[i] = r.o[i];
    o.v[3 + i] = r.d[i];
    o.v[6 + i] = r.inv_d[i];
  }
  if (mixed) {
    const Format ft = at.format(), fi = a.format();
    const RaySetup<SoftArith> t = TraversalRay(at, a, r);
    for (int i = 0; i < 3; ++i) {
      o.v[6 + i] = t.inv_d[i];
      cov->inv_inf += fp::IsInf(ft, t.inv_d[i]);
      cov->inv_nan += fp::IsNaN(ft, t.inv_d[i]);
      cov->flushed += fp::IsZero(fi, r.d[i]) && !fp::IsZero(fi, a.Load(framed.ray.d[i]));
      cov->wider += Widen(at, a, a.Load(at.Store(t.inv_d[i]))) != t.inv_d[i];
    }
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

std::string OutString(Format f, Format trav, const Out& o) {
  static const char* kNames[14] = {"o.x", "o.y", "o.z", "d.x", "d.y",  "d.z", "inv.x",
                                   "inv.y", "inv.z", "tmin", "tmax", "sx", "sy",  "sz"};
  std::string s;
  for (int i = 0; i < 14; ++i) {
    s += std::string(i % 3 == 0 ? "\n    " : "  ") + kNames[i] + " " + Fmt(i >= 6 && i < 9 ? trav : f, o.v[i]);
  }
  s += "\n    kx " + std::to_string(o.kx) + " ky " + std::to_string(o.ky) + " kz " + std::to_string(o.kz);
  s += "  k " + std::to_string(o.t_scale);
  return s;
}

// Direction components that make ties in |d|, signed zeros and specials,
// and small components whose shear flushes.
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
  // Small components beside a unit one, 2^-1 .. 2^-150: in every format some
  // of these shears flush to zero while the component itself does not, and
  // the component must then become a signed zero (SetupRay).
  for (int k = 1; k <= 150; ++k) {
    for (int axis = 0; axis < 3; ++axis) {
      Ray r;
      r.o = {0.5f, -0.25f, 0.125f};
      r.d = {0.75f, -0.75f, 0.75f};
      r.d[axis] = k % 2 ? -1.5f : 1.5f;
      r.d[(axis + 1) % 3] = std::ldexp(k % 3 ? 1.25f : -1.25f, -k);
      r.d[(axis + 2) % 3] = std::ldexp(k % 5 ? -1.0f : 1.0f, -(k + 3) / 2);
      rays.push_back(r);
    }
  }
  return rays;
}

// The frames of the directed rays: the identity, a far offset, and both
// ends of the scale range.
std::vector<Frame> DirectedFrames() {
  return {Frame{{0.0f, 0.0f, 0.0f}, 0}, Frame{{1e7f, -3.0f, 0.5f}, -20}, Frame{{1e-30f, -2e-30f, 0.0f}, 160},
          Frame{{1e30f, 5e29f, -1e30f}, -160}};
}

Frame RandomFrame(Rng& rng) {
  Frame f;
  const double scale = std::pow(10.0, rng.Uniform(-30, 30));
  for (int i = 0; i < 3; ++i) f.origin[i] = rng.Chance(0.1) ? 0.0f : static_cast<float>(rng.Gauss() * scale);
  switch (rng.Below(4)) {
    case 0: f.scale_log2 = rng.Chance(0.5) ? kMaxFrameScaleLog2 : -kMaxFrameScaleLog2; break;
    case 1: f.scale_log2 = static_cast<int32_t>(rng.Below(21)) - 10; break;
    default: f.scale_log2 = static_cast<int32_t>(rng.Below(2 * kMaxFrameScaleLog2 + 1)) - kMaxFrameScaleLog2;
  }
  return f;
}

// A world ray near the frame (offsets and lengths of the frame's size, 2^-s,
// or of any size), with extreme direction magnitudes mixed in.
Ray RandomRay(Rng& rng, const Frame& frame) {
  Ray r;
  const double frame_size = std::ldexp(1.0, -frame.scale_log2);
  const double scale = rng.Chance(0.5) ? frame_size * std::pow(10.0, rng.Uniform(-3, 3))
                                       : std::pow(10.0, rng.Uniform(-38, 38));
  const bool near = rng.Chance(0.7);
  for (int i = 0; i < 3; ++i) {
    r.o[i] = static_cast<float>((near ? frame.origin[i] : 0.0) + rng.Gauss() * scale);
    r.d[i] = static_cast<float>(rng.Gauss() * std::pow(10.0, rng.Uniform(-2, 2)));
  }
  switch (rng.Below(4)) {
    case 0: {  // the whole direction scaled by 2^-160 .. 2^160 (FTZ and overflow included)
      const int e = static_cast<int>(rng.Below(321)) - 160;
      for (int i = 0; i < 3; ++i) r.d[i] = static_cast<float>(std::ldexp(static_cast<double>(r.d[i]), e));
      break;
    }
    case 1:  // one component of any magnitude, the others unchanged
      r.d[rng.Below(3)] = static_cast<float>(rng.Gauss() * std::ldexp(1.0, static_cast<int>(rng.Below(270)) - 140));
      break;
    default: break;
  }
  if (rng.Chance(0.1)) r.d[rng.Below(3)] = 0.0f;
  if (rng.Chance(0.05)) r.d[rng.Below(3)] = r.d[rng.Below(3)] * (rng.Chance(0.5) ? -1.0f : 1.0f);  // ties
  if (rng.Chance(0.02)) r.d[rng.Below(3)] = SpecialF32(rng);
  if (rng.Chance(0.02)) r.o[rng.Below(3)] = SpecialF32(rng);
  const double t_scale = rng.Chance(0.2) ? std::pow(10.0, rng.Uniform(-30, 30)) : 1.0;
  r.tmin = rng.Chance(0.7) ? 0.0f : static_cast<float>(rng.LogUniform(1e-6, 1e6) * t_scale);
  r.tmax = rng.Chance(0.6) ? INFINITY : r.tmin + static_cast<float>(rng.LogUniform(1e-6, 1e6) * t_scale);
  if (rng.Chance(0.01)) r.tmin = SpecialF32(rng);
  if (rng.Chance(0.01)) r.tmax = SpecialF32(rng);
  return r;
}

struct In {
  Ray ray;
  Frame frame;
  uint32_t tag = 0;
};

template <class Dut>
bool RunPreset(Format f, Format trav, uint64_t random_count) {
  const auto start = std::chrono::steady_clock::now();
  const SoftArith a(f), at(trav);
  const bool mixed = f != trav;
  const std::string name = f.Name() + (mixed ? " (traversal " + trav.Name() + ")" : "");
  const int w = f.Width(), tw = trav.Width();
  Coverage cov;
  SimCtrl<Dut> sim;
  sim.top().in_valid_i = 0;
  sim.top().out_ready_i = 1;
  sim.Reset();
  Rng rng(500 + f.m);

  StreamUnit<Dut, In, Out> unit;
  unit.name = "rt_ray_setup " + name;
  unit.drive = [](Dut& dut, const In& in) {
    const Ray& r = in.ray;
    const float words[8] = {r.o[0], r.o[1], r.o[2], r.d[0], r.d[1], r.d[2], r.tmin, r.tmax};
    for (int j = 0; j < 8; ++j) PutBits(dut.in_ray_i, 32 * j, 32, fp::BitsOf(words[j]));
    for (int i = 0; i < 3; ++i) PutBits(dut.frame_origin_i, 32 * i, 32, fp::BitsOf(in.frame.origin[i]));
    dut.frame_scale_i = static_cast<uint32_t>(in.frame.scale_log2) & ((1u << kScaleWidth) - 1);
    dut.in_tag_i = in.tag;
  };
  unit.read = [w, tw](const Dut& dut) {
    Out o;
    for (int i = 0; i < 3; ++i) {
      o.v[i] = static_cast<uint32_t>(GetBits(dut.out_o_o, i * w, w));
      o.v[3 + i] = static_cast<uint32_t>(GetBits(dut.out_d_o, i * w, w));
      o.v[6 + i] = static_cast<uint32_t>(GetBits(dut.out_inv_o, i * tw, tw));
    }
    o.v[9] = dut.out_tmin_o;
    o.v[10] = dut.out_tmax_o;
    o.v[11] = dut.out_sx_o;
    o.v[12] = dut.out_sy_o;
    o.v[13] = dut.out_sz_o;
    o.kx = dut.out_kx_o;
    o.ky = dut.out_ky_o;
    o.kz = dut.out_kz_o;
    o.t_scale = static_cast<int>(static_cast<uint32_t>(dut.out_t_scale_o) << (32 - kTScaleWidth)) >>
                (32 - kTScaleWidth);
    o.tag = dut.out_tag_o;
    return o;
  };
  unit.model = [&](const In& in) {
    Out o = Model(a, at, in.ray, in.frame, &cov);
    o.tag = in.tag;
    return o;
  };
  unit.report = [&](const In& in, const Out& want, const Out& got, uint64_t index) {
    std::printf("FAIL rt_ray_setup %s: first mismatch at ray %llu\n  %s\n  frame origin (%s, %s, %s) scale 2^%d\n"
                "  model (tag %u):%s\n  rtl (tag %u):%s\n",
                name.c_str(), static_cast<unsigned long long>(index), RayString(in.ray).c_str(),
                F32(in.frame.origin[0]).c_str(), F32(in.frame.origin[1]).c_str(), F32(in.frame.origin[2]).c_str(),
                in.frame.scale_log2, want.tag, OutString(f, trav, want).c_str(), got.tag,
                OutString(f, trav, got).c_str());
  };

  // Latency on an idle pipe.
  const unsigned latency = MeasureLatency(sim, unit, In{Ray{{0, 0, 0}, {1, 2, 3}, 0.0f, 1.0f}, Frame{}, 0});
  std::printf("rt_ray_setup %s: latency %u cycles (documented %u)\n", name.c_str(), latency,
              DocumentedLatency(f, trav));
  if (latency != DocumentedLatency(f, trav)) {
    std::printf("FAIL rt_ray_setup %s: latency %u, documented %u\n", name.c_str(), latency,
                DocumentedLatency(f, trav));
    return false;
  }

  const std::vector<Ray> directed_rays = DirectedRays();
  std::vector<In> directed;
  for (const Frame& frame : DirectedFrames()) {
    for (const Ray& ray : directed_rays) directed.push_back(In{ray, frame, 0});
  }
  const uint64_t total = directed.size() + random_count;
  uint64_t issued = 0;
  uint32_t tag = 0;
  Rng stim(99);
  unit.next = [&](In& in) {
    if (issued >= total) return false;
    if (issued < directed.size()) {
      in = directed[issued];
    } else {
      in.frame = RandomFrame(stim);
      in.ray = RandomRay(stim, in.frame);
    }
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
  std::printf("PASS rt_ray_setup %s: %llu rays (%zu directed), %llu cycles, %.1f s\n", name.c_str(),
              static_cast<unsigned long long>(stats.results), directed.size(),
              static_cast<unsigned long long>(stats.cycles), seconds);
  if (mixed) {
    std::printf("  covered (components): inv_d infinite %llu, NaN %llu, of a flushed shear %llu, "
                "not a %s value %llu\n",
                static_cast<unsigned long long>(cov.inv_inf), static_cast<unsigned long long>(cov.inv_nan),
                static_cast<unsigned long long>(cov.flushed), f.Name().c_str(),
                static_cast<unsigned long long>(cov.wider));
  }
  std::fflush(stdout);
  if (mixed && (cov.inv_inf == 0 || cov.inv_nan == 0 || cov.flushed == 0 || cov.wider == 0)) {
    std::printf("FAIL rt_ray_setup %s: a required case was not reached\n", name.c_str());
    return false;
  }
  return stats.results == total;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  using namespace kdrt::fp;
  Verilated::commandArgs(argc, argv);
  uint64_t count = LongRun() ? 10000000ull : 300000ull;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--count") count = std::strtoull(argv[i + 1], nullptr, 10);
  }
  bool ok = RunPreset<Vrt_ray_setup_fp32>(kFp32, kFp32, count);
  ok = RunPreset<Vrt_ray_setup_fp24>(kFp24, kFp24, count) && ok;
  ok = RunPreset<Vrt_ray_setup_bf16>(kBf16, kBf16, count) && ok;
  ok = RunPreset<Vrt_ray_setup_fp16>(kFp16, kFp16, count) && ok;
  // A traversal wider than the test (tests/rtl/CMakeLists.txt, KDRT_TRAV_MIXED_FORMATS).
  ok = RunPreset<Vrt_ray_setup_fp16t32>(kFp16, kFp32, count) && ok;
  ok = RunPreset<Vrt_ray_setup_bf16t32>(kBf16, kFp32, count) && ok;
  ok = RunPreset<Vrt_ray_setup_fp16t24>(kFp16, kFp24, count) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
