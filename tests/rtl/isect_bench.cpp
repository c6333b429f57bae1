// Verilator bench of rtl/rt_isect_unit.sv against the model's watertight
// test (IntersectWatertight on SoftArith, sw/trace/intersect.h), per preset.
// Every output is checked (hit; t, u, v bits when hit, zeros otherwise; tag;
// triangle id); the first mismatch stops the run with the ray, the triangle
// and both results. The stream has random input bubbles and random output
// backpressure. Cases: random (ray, triangle) pairs, most aimed at the
// triangle (3e5 per preset, 1e7 with KDRT_LONG=1), directed corner cases,
// and the watertightness rays of two closed meshes against every triangle,
// whose misses are tabulated for the model and the RTL.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "Vrt_isect_unit_bf16.h"
#include "Vrt_isect_unit_fp16.h"
#include "Vrt_isect_unit_fp24.h"
#include "Vrt_isect_unit_fp32.h"
#include "sim/unit_latency.h"
#include "tests/rtl/isect_bench_util.h"
#include "tests/rtl/stream_bench.h"
#include "trace/intersect.h"
#include "trace/watertight.h"

namespace kdrt::rtlbench {
namespace {

using fp::Format;
using fp::SoftArith;
using Setup = RaySetup<SoftArith>;

constexpr uint32_t kTagMask = 0xFF;  // TagWidth = 8, the unit's default

unsigned DocumentedLatency(Format f) { return sim::latency::Isect(f); }

struct Case {
  Ray ray;
  img::TriangleRecord tri{};
  float leaf_tmax = INFINITY;  // the unit's tmax input, loaded into the format
  uint32_t id = 0;
  int32_t group = -1;  // watertightness: the ray's index
};

struct Outcome {
  bool hit = false;
  uint32_t t = 0, u = 0, v = 0;
  bool operator==(const Outcome& o) const { return hit == o.hit && t == o.t && u == o.u && v == o.v; }
};

Outcome Model(const SoftArith& a, const Case& c) {
  const Setup r = SetupRay(a, c.ray);
  const Candidate<SoftArith> k = IntersectWatertight(a, r, c.tri, a.Load(c.leaf_tmax));
  // The unit's t, u, v are zeros unless hit.
  return k.hit ? Outcome{true, k.t, k.u, k.v} : Outcome{};
}

img::TriangleRecord Record(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  img::TriangleRecord t{};
  for (int i = 0; i < 3; ++i) {
    t.v0[i] = a[i];
    t.v1[i] = b[i];
    t.v2[i] = c[i];
  }
  return t;
}

float* Coord(img::TriangleRecord& t, int j) {
  float* const vertices[3] = {t.v0, t.v1, t.v2};
  return &vertices[j / 3][j % 3];
}

glm::dvec3 RandomDir(Rng& rng) {
  glm::dvec3 d;
  do {
    d = {rng.Gauss(), rng.Gauss(), rng.Gauss()};
  } while (glm::length(d) < 1e-3);
  return glm::normalize(d);
}

// A ray from `dist` away through `target`, with |d| scaled by a power of two
// so that the target lies at t = 2^-k.
Ray Aim(Rng& rng, const glm::dvec3& target, double dist, float* t_target) {
  Ray r;
  r.o = glm::vec3(target + RandomDir(rng) * dist);
  const int k = static_cast<int>(rng.Below(9)) - 4;
  r.d = (glm::vec3(target) - r.o) * std::ldexp(1.0f, k);
  if (r.d == glm::vec3(0.0f)) r.d = {0.0f, 0.0f, 1.0f};
  *t_target = std::ldexp(1.0f, -k);
  r.tmin = 0.0f;
  r.tmax = INFINITY;
  return r;
}

// ------------------------------------------------------------ random cases
// Triangles of all sizes and places; rays aimed at a point inside or near
// the triangle, so that a good fraction hits; tmin/tmax sometimes cut the
// hit off; sometimes axis-parallel rays and special values.
Case RandomCase(Rng& rng) {
  Case c;
  const double scale = std::pow(10.0, rng.Uniform(-2.0, 1.5));
  const glm::dvec3 center = glm::dvec3(rng.Uniform(-5, 5), rng.Uniform(-5, 5), rng.Uniform(-5, 5)) * scale;
  const double size = scale * std::pow(10.0, rng.Uniform(-1.5, 0.5));
  glm::dvec3 v[3];
  for (glm::dvec3& p : v) p = center + glm::dvec3(rng.Gauss(), rng.Gauss(), rng.Gauss()) * size;
  if (rng.Chance(0.1)) {  // on a grid: axis-aligned edges, coplanar points, exact ties
    const double step = size / 4;
    for (glm::dvec3& p : v) p = glm::round(p / step) * step;
  }
  c.tri = Record(glm::vec3(v[0]), glm::vec3(v[1]), glm::vec3(v[2]));
  double w1 = rng.Unit(), w2 = rng.Unit();
  if (rng.Chance(0.6)) {
    if (w1 + w2 > 1) {
      w1 = 1 - w1;
      w2 = 1 - w2;
    }
  } else {
    w1 = rng.Uniform(-0.3, 1.3);
    w2 = rng.Uniform(-0.3, 1.3);
  }
  const glm::dvec3 target = (1 - w1 - w2) * v[0] + w1 * v[1] + w2 * v[2];
  float t_target;
  c.ray = Aim(rng, target, size * rng.LogUniform(0.1, 100.0), &t_target);
  if (rng.Chance(0.1)) {  // axis-parallel in one or two axes
    c.ray.d[rng.Below(3)] = 0.0f;
    if (rng.Chance(0.3)) c.ray.d[rng.Below(3)] = 0.0f;
    if (c.ray.d == glm::vec3(0.0f)) c.ray.d[rng.Below(3)] = 1.0f;
  }
  if (rng.Chance(0.3)) c.ray.tmin = static_cast<float>(t_target * rng.Uniform(0.0, 1.3));
  if (rng.Chance(0.4)) c.ray.tmax = std::max(c.ray.tmin, static_cast<float>(t_target * rng.Uniform(0.7, 2.0)));
  c.leaf_tmax = rng.Chance(0.75) ? c.ray.tmax : static_cast<float>(t_target * rng.Uniform(0.5, 1.5));
  if (rng.Chance(0.05)) *Coord(c.tri, static_cast<int>(rng.Below(9))) = SpecialF32(rng);
  if (rng.Chance(0.01)) c.ray.o[rng.Below(3)] = SpecialF32(rng);
  if (rng.Chance(0.01)) c.ray.d[rng.Below(3)] = SpecialF32(rng);
  if (rng.Chance(0.01)) c.leaf_tmax = SpecialF32(rng);
  c.id = rng.Bits32();
  return c;
}

// ------------------------------------------------------------ directed cases
std::vector<Case> DirectedCases(const SoftArith& a, uint64_t seed) {
  Rng rng(seed);
  std::vector<Case> out;
  auto add = [&](const Ray& ray, const img::TriangleRecord& tri, float leaf_tmax) {
    Case c;
    c.ray = ray;
    c.tri = tri;
    c.leaf_tmax = leaf_tmax;
    c.id = static_cast<uint32_t>(out.size());
    out.push_back(c);
  };
  auto random_point = [&](double s) {
    return glm::dvec3(rng.Uniform(-s, s), rng.Uniform(-s, s), rng.Uniform(-s, s));
  };
  float tt;

  // Shared edges: (a, b, c) and (b, a, d) share edge ab with opposite
  // directions; rays through the edge's ends, midpoint and random points.
  for (int i = 0; i < 3000; ++i) {
    const double s = std::pow(10.0, rng.Uniform(-1, 1));
    const glm::dvec3 pa = random_point(s), pb = random_point(s), pc = random_point(s);
    const glm::dvec3 pd = 0.5 * (pa + pb) - (pc - 0.5 * (pa + pb)) + random_point(0.2 * s);
    const img::TriangleRecord t1 = Record(glm::vec3(pa), glm::vec3(pb), glm::vec3(pc));
    const img::TriangleRecord t2 = Record(glm::vec3(pb), glm::vec3(pa), glm::vec3(pd));
    for (double w : {0.0, 1.0, 0.5, rng.Unit()}) {
      const glm::dvec3 target = glm::dvec3(glm::vec3(pa)) * (1 - w) + glm::dvec3(glm::vec3(pb)) * w;
      const Ray ray = Aim(rng, target, s * rng.LogUniform(0.5, 50.0), &tt);
      add(ray, t1, INFINITY);
      add(ray, t2, INFINITY);
    }
  }
  // Shared vertices: a fan of five triangles around p; rays at p and at the
  // midpoints of the spokes, against every triangle of the fan.
  for (int i = 0; i < 300; ++i) {
    const double s = std::pow(10.0, rng.Uniform(-1, 1));
    const glm::dvec3 p = random_point(s), n = RandomDir(rng);
    const glm::dvec3 u = glm::normalize(glm::cross(n, RandomDir(rng))), v = glm::cross(n, u);
    glm::vec3 q[5];
    for (int k = 0; k < 5; ++k) {
      const double ang = 2 * M_PI * (k + rng.Uniform(-0.3, 0.3)) / 5;
      q[k] = glm::vec3(p + s * (std::cos(ang) * u + std::sin(ang) * v) + 0.1 * s * rng.Gauss() * n);
    }
    std::vector<glm::dvec3> targets = {glm::dvec3(glm::vec3(p))};
    for (int k = 0; k < 5; ++k) targets.push_back(0.5 * (glm::dvec3(glm::vec3(p)) + glm::dvec3(q[k])));
    for (const glm::dvec3& target : targets) {
      const Ray ray = Aim(rng, target, s * rng.LogUniform(0.5, 50.0), &tt);
      for (int k = 0; k < 5; ++k) add(ray, Record(glm::vec3(p), q[k], q[(k + 1) % 5]), INFINITY);
    }
  }
  // Rays parallel to the triangle's plane: in it and beside it.
  for (int i = 0; i < 1000; ++i) {
    const double s = std::pow(10.0, rng.Uniform(-1, 1));
    const float zc = static_cast<float>(rng.Uniform(-s, s));
    glm::vec3 v[3];
    for (glm::vec3& p : v) p = {static_cast<float>(rng.Uniform(-s, s)), static_cast<float>(rng.Uniform(-s, s)), zc};
    const int axis = static_cast<int>(rng.Below(3));  // the plane's normal axis
    for (glm::vec3& p : v) std::swap(p[2], p[axis]);
    Ray ray;
    ray.o = glm::vec3(random_point(2 * s));
    ray.o[axis] = rng.Chance(0.5) ? zc : zc + static_cast<float>(rng.Uniform(-0.01, 0.01) * s);
    ray.d = glm::vec3(RandomDir(rng));
    ray.d[axis] = 0.0f;
    if (ray.d == glm::vec3(0.0f)) ray.d[(axis + 1) % 3] = 1.0f;
    add(ray, Record(v[0], v[1], v[2]), INFINITY);
    // In a tilted plane: along an edge, from behind its start.
    const glm::vec3 e = v[1] - v[0];
    add(Ray{v[0] - e, e, 0.0f, INFINITY}, Record(v[0], v[1], v[2]), INFINITY);
  }
  // Degenerate triangles: repeated vertices and collinear vertices.
  for (int i = 0; i < 800; ++i) {
    const double s = std::pow(10.0, rng.Uniform(-1, 1));
    const glm::vec3 p(random_point(s)), q(random_point(s));
    const glm::vec3 step = rng.Chance(0.5) ? glm::vec3(1, 2, 0) * static_cast<float>(s / 8) : (q - p) * 0.25f;
    const img::TriangleRecord tris[6] = {Record(p, p, q), Record(p, q, q),     Record(p, q, p),
                                         Record(p, p, p), Record(p, p + step, p + 2.0f * step),
                                         Record(p + 2.0f * step, p, p + step)};
    const glm::dvec3 targets[3] = {glm::dvec3(p), glm::dvec3(q), glm::dvec3(p + step)};
    for (const img::TriangleRecord& t : tris) {
      add(Aim(rng, targets[rng.Below(3)], s * rng.LogUniform(0.5, 50.0), &tt), t, INFINITY);
    }
  }
  // Hits at exactly t = tmin and t = tmax, and one format ulp either side.
  const Format f = a.format();
  int found = 0;
  for (int i = 0; found < 3000 && i < 200000; ++i) {
    Case c = RandomCase(rng);
    c.ray.tmin = 0.0f;
    c.ray.tmax = c.leaf_tmax = INFINITY;
    const Outcome hit = Model(a, c);
    if (!hit.hit || fp::IsZero(f, hit.t) || fp::IsInf(f, hit.t) || fp::IsNaN(f, hit.t)) continue;
    ++found;
    for (int ulp = -1; ulp <= 1; ++ulp) {
      const float t = fp::ToFloat(f, hit.t + ulp);  // t > 0: +-1 on the bits is +-1 ulp
      Ray r = c.ray;
      r.tmin = t;
      add(r, c.tri, INFINITY);
      add(c.ray, c.tri, t);
      r.tmax = t;
      add(r, c.tri, t);
    }
  }
  // Huge and tiny coordinates: hitting cases scaled by 1e30, 1e20, 1e-20, 1e-30.
  found = 0;
  for (int i = 0; found < 2000 && i < 200000; ++i) {
    Case c = RandomCase(rng);
    if (!Model(a, c).hit) continue;
    ++found;
    const float scale = std::pow(10.0f, static_cast<float>(std::array<int, 4>{30, 20, -20, -30}[found % 4]));
    for (int j = 0; j < 9; ++j) *Coord(c.tri, j) *= scale;
    c.ray.o *= scale;
    c.ray.d *= scale;
    add(c.ray, c.tri, c.leaf_tmax);
  }
  // NaN and infinities in each vertex coordinate of hitting cases.
  found = 0;
  for (int i = 0; found < 300 && i < 200000; ++i) {
    const Case c = RandomCase(rng);
    if (!Model(a, c).hit) continue;
    ++found;
    for (int j = 0; j < 9; ++j) {
      for (float special : {NAN, INFINITY, -INFINITY}) {
        img::TriangleRecord t = c.tri;
        *Coord(t, j) = special;
        add(c.ray, t, c.leaf_tmax);
      }
    }
  }
  return out;
}

// ------------------------------------------------------------ the harness
struct Stats {
  uint64_t tests = 0;
  uint64_t hits = 0;
  uint64_t cycles = 0;
};

// A test in flight: the case and its tag; a result: outcome, tag and id.
struct In {
  Case c;
  uint32_t tag = 0;
};
struct Out {
  Outcome o;
  uint32_t tag = 0, id = 0;
  bool operator==(const Out& x) const { return o == x.o && tag == x.tag && id == x.id; }
};

template <class Dut>
class Harness {
 public:
  Harness(Format f, uint64_t seed) : f_(f), a_(f), w_(f.Width()), rng_(seed) {
    sim_.top().in_valid_i = 0;
    sim_.top().out_ready_i = 1;
    sim_.Reset();
    unit_.name = "rt_isect_unit " + f.Name();
    unit_.drive = [this](Dut& dut, const In& in) { Drive(dut, in); };
    unit_.idle = [this](Dut& dut) { Garbage(dut); };  // the payload is don't-care while in_valid_i is low
    unit_.read = [](const Dut& dut) {
      return Out{Outcome{dut.out_hit_o != 0, static_cast<uint32_t>(dut.out_t_o), static_cast<uint32_t>(dut.out_u_o),
                         static_cast<uint32_t>(dut.out_v_o)},
                 dut.out_tag_o, dut.out_id_o};
    };
    unit_.model = [this](const In& in) { return Out{Model(a_, in.c), in.tag, in.c.id}; };
    unit_.report = [this](const In& in, const Out& want, const Out& got, uint64_t index) {
      Report(in.c, want, got, index);
    };
  }

  // Enabled cycles from acceptance to the result, measured on an idle pipe.
  unsigned MeasureLatency() {
    In in;
    in.c.ray = Ray{{0, 0, 1}, {0, 0, -1}, 0.0f, INFINITY};
    in.c.tri = Record({-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
    return rtlbench::MeasureLatency(sim_, unit_, in);
  }

  // Streams the cases from `next` through the unit; `on_result` sees each
  // case with the unit's hit flag. Returns false at the first mismatch.
  bool Run(const std::function<bool(Case&)>& next, const std::function<void(const Case&, bool)>& on_result,
           Stats* stats) {
    unit_.next = [&](In& in) {
      if (!next(in.c)) return false;
      in.tag = next_tag_;
      next_tag_ = (next_tag_ + 1) & kTagMask;
      return true;
    };
    unit_.on_result = [&](const In& in, const Out& got) {
      on_result(in.c, got.o.hit);
      stats->hits += got.o.hit;
    };
    // Backpressure comes in regimes: the chance of out_ready_i and of an
    // input bubble change every few hundred cycles.
    StreamTraffic traffic;
    traffic.ready = {1.0, 0.9, 0.5, 0.1};
    traffic.gap = {0.0, 0.2, 0.7};
    traffic.garbage = 0.1;
    StreamStats run;
    run.results = stats->tests;
    const bool ok = RunStream(sim_, rng_, traffic, unit_, &run);
    stats->tests = run.results;
    stats->cycles += run.cycles;
    return ok;
  }

 private:
  void Drive(Dut& dut, const In& in) {
    const Case& c = in.c;
    const Setup r = SetupRay(a_, c.ray);
    dut.in_tag_i = in.tag;
    dut.in_id_i = c.id;
    for (int i = 0; i < 3; ++i) PutBits(dut.in_o_i, i * w_, w_, r.o[i]);
    dut.in_kx_i = static_cast<uint8_t>(r.kx);
    dut.in_ky_i = static_cast<uint8_t>(r.ky);
    dut.in_kz_i = static_cast<uint8_t>(r.kz);
    dut.in_sx_i = r.sx;
    dut.in_sy_i = r.sy;
    dut.in_sz_i = r.sz;
    dut.in_tmin_i = r.tmin;
    dut.in_tmax_i = a_.Load(c.leaf_tmax);
    uint32_t words[9];
    std::memcpy(words, &c.tri, sizeof words);
    for (int j = 0; j < 9; ++j) PutBits(dut.in_tri_i, 32 * j, 32, words[j]);
  }

  void Garbage(Dut& dut) {
    const uint32_t mask = f_.WidthMask();
    dut.in_tag_i = rng_.Bits32() & kTagMask;
    dut.in_id_i = rng_.Bits32();
    for (int i = 0; i < 3; ++i) PutBits(dut.in_o_i, i * w_, w_, rng_.Bits32());
    dut.in_kx_i = static_cast<uint8_t>(rng_.Below(4));
    dut.in_sx_i = rng_.Bits32() & mask;
    dut.in_tmax_i = rng_.Bits32() & mask;
    for (int j = 0; j < 9; ++j) PutBits(dut.in_tri_i, 32 * j, 32, rng_.Bits32());
  }

  void Report(const Case& c, const Out& want, const Out& got, uint64_t index) const {
    std::printf("FAIL rt_isect_unit %s: first mismatch at test %llu\n", f_.Name().c_str(),
                static_cast<unsigned long long>(index));
    std::printf("  %s\n  leaf tmax = %s\n  %s\n", RayString(c.ray).c_str(), F32(c.leaf_tmax).c_str(),
                TriangleString(c.tri).c_str());
    auto show = [&](const char* who, const Out& x) {
      std::printf("  %-5s hit %d  t %s  u %s  v %s  tag %u  id %u\n", who, x.o.hit, Fmt(f_, x.o.t).c_str(),
                  Fmt(f_, x.o.u).c_str(), Fmt(f_, x.o.v).c_str(), x.tag, x.id);
    };
    show("model", want);
    show("rtl", got);
  }

  Format f_;
  SoftArith a_;
  int w_;
  Rng rng_;
  SimCtrl<Dut> sim_;
  StreamUnit<Dut, In, Out> unit_;
  uint32_t next_tag_ = 0;
};

// ------------------------------------------------------------ per preset
struct MeshResult {
  std::string mesh;
  size_t rays = 0;
  size_t model_misses = 0;
  size_t rtl_misses = 0;
};

struct PresetResult {
  Format f;
  bool ok = false;
  unsigned latency = 0;
  Stats random, directed, watertight;
  double seconds = 0;
  std::vector<MeshResult> meshes;
};

template <class Dut>
PresetResult RunPreset(Format f, uint64_t random_count) {
  PresetResult res;
  res.f = f;
  const auto start = std::chrono::steady_clock::now();
  const SoftArith a(f);
  Harness<Dut> h(f, 1000 + f.m);
  res.latency = h.MeasureLatency();
  std::printf("rt_isect_unit %s: latency %u cycles (documented %u)\n", f.Name().c_str(), res.latency,
              DocumentedLatency(f));
  std::fflush(stdout);
  if (res.latency != DocumentedLatency(f)) {
    std::printf("FAIL rt_isect_unit %s: latency %u, documented %u\n", f.Name().c_str(), res.latency,
                DocumentedLatency(f));
    return res;
  }
  auto ignore = [](const Case&, bool) {};

  Rng rng(42);
  uint64_t issued = 0;
  auto random = [&](Case& c) {
    if (issued >= random_count) return false;
    ++issued;
    c = RandomCase(rng);
    return true;
  };
  if (!h.Run(random, ignore, &res.random)) return res;

  const std::vector<Case> directed = DirectedCases(a, 7);
  size_t di = 0;
  auto from_list = [&](Case& c) {
    if (di >= directed.size()) return false;
    c = directed[di++];
    return true;
  };
  if (!h.Run(from_list, ignore, &res.directed)) return res;

  // Watertightness: every ray against every triangle of the mesh.
  const Scene meshes[2] = {ClosedSphereMesh(6, 12), ClosedCubeMesh(3)};
  for (const Scene& mesh : meshes) {
    const std::vector<Ray> rays = WatertightRays(mesh, 1);
    std::vector<img::TriangleRecord> tris;
    for (const Triangle& t : mesh.triangles) tris.push_back(Record(t.v0, t.v1, t.v2));
    std::vector<char> rtl_hit(rays.size(), 0), model_hit(rays.size(), 0);
    size_t ri = 0, ti = 0;
    auto all_pairs = [&](Case& c) {
      if (ri >= rays.size()) return false;
      c.ray = rays[ri];
      c.tri = tris[ti];
      c.leaf_tmax = rays[ri].tmax;
      c.id = static_cast<uint32_t>(ti);
      c.group = static_cast<int32_t>(ri);
      if (++ti == tris.size()) {
        ti = 0;
        ++ri;
      }
      return true;
    };
    auto tally = [&](const Case& c, bool hit) {
      rtl_hit[c.group] |= hit;
      model_hit[c.group] |= Model(a, c).hit;
    };
    if (!h.Run(all_pairs, tally, &res.watertight)) return res;
    MeshResult m;
    m.mesh = mesh.source;
    m.rays = rays.size();
    for (size_t i = 0; i < rays.size(); ++i) {
      m.model_misses += !model_hit[i];
      m.rtl_misses += !rtl_hit[i];
    }
    res.meshes.push_back(m);
  }
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  auto line = [](const char* what, const Stats& s) {
    std::printf("  %-10s %9llu tests, %5.1f %% hits, %9llu cycles\n", what,
                static_cast<unsigned long long>(s.tests), s.tests ? 100.0 * s.hits / s.tests : 0.0,
                static_cast<unsigned long long>(s.cycles));
  };
  line("random", res.random);
  line("directed", res.directed);
  line("watertight", res.watertight);
  std::printf("  %.1f s\n", res.seconds);
  res.ok = true;
  std::printf("PASS rt_isect_unit %s\n", f.Name().c_str());
  std::fflush(stdout);
  return res;
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
  std::vector<PresetResult> results;
  results.push_back(RunPreset<Vrt_isect_unit_fp32>(kFp32, count));
  results.push_back(RunPreset<Vrt_isect_unit_fp24>(kFp24, count));
  results.push_back(RunPreset<Vrt_isect_unit_bf16>(kBf16, count));
  results.push_back(RunPreset<Vrt_isect_unit_fp16>(kFp16, count));

  bool ok = true;
  for (const PresetResult& r : results) ok = ok && r.ok;
  std::printf("\nwatertightness: rays that hit no triangle (brute force over the mesh), model / rtl\n");
  std::printf("  %-28s %6s", "mesh", "rays");
  for (const PresetResult& r : results) std::printf(" %11s", r.f.Name().c_str());
  std::printf("\n");
  if (!results.empty() && results[0].meshes.size() == 2) {
    for (size_t m = 0; m < 2; ++m) {
      std::printf("  %-28s %6zu", results[0].meshes[m].mesh.c_str(), results[0].meshes[m].rays);
      for (const PresetResult& r : results) {
        if (r.meshes.size() != 2) {
          std::printf(" %11s", "-");
          continue;
        }
        char cell[32];
        std::snprintf(cell, sizeof cell, "%zu / %zu", r.meshes[m].model_misses, r.meshes[m].rtl_misses);
        std::printf(" %11s", cell);
        ok = ok && r.meshes[m].model_misses == r.meshes[m].rtl_misses;
      }
      std::printf("\n");
    }
  }
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
