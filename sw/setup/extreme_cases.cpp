#include "setup/extreme_cases.h"

#include <cmath>
#include <cstdio>
#include <random>

#include <glm/geometric.hpp>

#include "trace/watertight.h"

namespace kdrt {
namespace {

using glm::dvec3;

dvec3 D(const glm::vec3& v) { return dvec3(v); }
glm::vec3 F(const dvec3& v) { return glm::vec3(v); }  // one rounding per component

std::string Pow10Name(const char* what, int k) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s 1e%d", what, k);
  return buf;
}

// Every vertex v becomes round(v * scale + offset), computed in double: a
// shared vertex maps to one float, so a closed mesh stays closed.
Scene Mapped(const Scene& mesh, double scale, const dvec3& offset, const dvec3& axis_scale = dvec3(1.0)) {
  Scene s = mesh;
  for (Triangle& t : s.triangles) {
    for (glm::vec3* v : {&t.v0, &t.v1, &t.v2}) *v = F(D(*v) * axis_scale * scale + offset);
  }
  return s;
}

// Rays aimed at every vertex and edge midpoint of every `stride`-th triangle
// (at most `max_triangles` of them), from center + reach (target - center)
// plus a jitter of up to 5 % of `size`: each passes through the target into
// the interior of a closed mesh around `center`, so each must hit. Origin
// and direction are rounded once.
void AddAimedRays(ExtremeCase& c, const dvec3& center, double size, uint32_t seed, size_t max_triangles = SIZE_MAX,
                  size_t stride = 1, double reach = 3.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  const size_t n = std::min(max_triangles, (c.scene.triangles.size() + stride - 1) / stride);
  for (size_t i = 0; i < n; ++i) {
    const Triangle& t = c.scene.triangles[i * stride];
    const dvec3 v[3] = {D(t.v0), D(t.v1), D(t.v2)};
    const dvec3 targets[6] = {v[0], v[1], v[2], (v[0] + v[1]) * 0.5, (v[1] + v[2]) * 0.5, (v[2] + v[0]) * 0.5};
    for (const dvec3& target : targets) {
      const dvec3 o = center + reach * (target - center) + size * dvec3(jitter(rng), jitter(rng), jitter(rng));
      c.rays.push_back(Ray{F(o), F(target - o), 0.0f, INFINITY});
      c.must_hit.push_back(1);
    }
  }
}

ExtremeCase Case(const std::string& name, const std::string& group, Scene scene) {
  ExtremeCase c;
  c.name = name;
  c.group = group;
  c.scene = std::move(scene);
  c.scene.source = "extremes: " + name;
  return c;
}

// A closed cone: apex at (0, 0, height), base circle of `radius` at z = 0
// fanned from its first vertex; `segments` side triangles share the apex.
Scene ClosedCone(int segments, double radius, double height) {
  Scene s;
  s.colors = {{1.0f, 1.0f, 1.0f}};
  std::vector<glm::vec3> rim(segments);
  for (int j = 0; j < segments; ++j) {
    const double phi = 2.0 * M_PI * j / segments;
    rim[j] = F(dvec3(radius * std::cos(phi), radius * std::sin(phi), 0.0));
  }
  const glm::vec3 apex = F(dvec3(0.0, 0.0, height));
  for (int j = 0; j < segments; ++j) s.triangles.push_back({rim[j], rim[(j + 1) % segments], apex});
  for (int j = 1; j + 1 < segments; ++j) s.triangles.push_back({rim[0], rim[j + 1], rim[j]});
  s.material.assign(s.triangles.size(), 0);
  return s;
}

}  // namespace

std::vector<ExtremeCase> MakeExtremeCases(bool reduced) {
  std::vector<ExtremeCase> cases;
  const Scene sphere = reduced ? ClosedSphereMesh(6, 12) : ClosedSphereMesh(12, 24);
  const Scene cube = ClosedCubeMesh(reduced ? 2 : 4);

  auto aimed = [&](const std::string& name, const std::string& group, Scene s, const dvec3& center, double size) {
    ExtremeCase c = Case(name, group, std::move(s));
    AddAimedRays(c, center, size, 1);
    cases.push_back(std::move(c));
  };

  aimed("unit sphere", "unit", sphere, dvec3(0.0), 1.0);
  aimed("unit cube", "unit", cube, dvec3(0.0), 1.0);

  // The mesh far from the origin: the translation costs the format's
  // mantissa bits (a world-space datapath loses them all at large offsets).
  for (int k = 0; k <= 7; k += reduced ? 2 : 1) {
    const dvec3 offset = std::pow(10.0, k) * dvec3(1.0, 0.5, 0.25);
    aimed(Pow10Name("offset", k), "offset", Mapped(sphere, 1.0, offset), offset, 1.0);
  }
  // Tiny and huge scenes: the exponent range of coordinates and of the
  // products in the watertight test.
  for (int k = -30; k <= 30; k += reduced ? 15 : 5) {
    const double s = std::pow(10.0, k);
    aimed(Pow10Name("scale", k), "scale", Mapped(sphere, s, dvec3(0.0)), dvec3(0.0), s);
  }
  // The same rays with directions scaled by 2^k (exact): t scales, the
  // triangle hit must not change.
  {
    ExtremeCase base = Case("", "direction", sphere);
    AddAimedRays(base, dvec3(0.0), 1.0, 2);
    for (int k = -100; k <= 100; k += reduced ? 50 : 20) {
      ExtremeCase c = base;
      c.name = "direction 2^" + std::to_string(k);
      c.scene.source = "extremes: " + c.name;
      for (Ray& r : c.rays) r.d = F(D(r.d) * std::ldexp(1.0, k));
      cases.push_back(std::move(c));
    }
  }
  // Axis-aligned rays, the other components +0 or -0, aimed at the vertices
  // and edge midpoints of each face of the cube from outside that face.
  {
    ExtremeCase c = Case("axis-aligned +-0", "axis", cube);
    size_t i = 0;
    for (const Triangle& t : c.scene.triangles) {
      const dvec3 v[3] = {D(t.v0), D(t.v1), D(t.v2)};
      const dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
      int axis = 0;
      for (int a = 1; a < 3; ++a) axis = std::fabs(n[a]) > std::fabs(n[axis]) ? a : axis;
      const double out = n[axis] > 0 ? 1.0 : -1.0;  // outward: the cube is around the origin
      for (const dvec3& target : {v[0], v[1], v[2], (v[0] + v[1]) * 0.5, (v[1] + v[2]) * 0.5}) {
        glm::vec3 d(0.0f);
        for (int a = 0; a < 3; ++a) d[a] = (i++ % 2) ? -0.0f : 0.0f;
        d[axis] = static_cast<float>(-out);
        dvec3 o = target;
        o[axis] += 3.0 * out;
        c.rays.push_back(Ray{F(o), d, 0.0f, INFINITY});
        c.must_hit.push_back(1);
      }
    }
    cases.push_back(std::move(c));
  }
  // Rays that start on the surface (at each vertex, towards the centre) and
  // inside the mesh (near the centre, in every direction).
  {
    ExtremeCase c = Case("start on surface / inside", "surface", sphere);
    std::mt19937 rng(3);
    std::normal_distribution<double> g(0.0, 1.0);
    for (const Triangle& t : c.scene.triangles) {
      c.rays.push_back(Ray{t.v0, F(-D(t.v0)), 0.0f, INFINITY});
      c.must_hit.push_back(1);
      const dvec3 o = 0.1 * dvec3(g(rng), g(rng), g(rng)), d(g(rng), g(rng), g(rng));
      c.rays.push_back(Ray{F(o), F(d), 0.0f, INFINITY});
      c.must_hit.push_back(1);
    }
    cases.push_back(std::move(c));
  }
  // Rays in the plane of a cube face, across it: they touch the mesh only
  // along its surface, so hit or miss are both right; only agreement counts.
  {
    ExtremeCase c = Case("grazing in a face plane", "grazing", cube);
    for (int k = 0; k < 64; ++k) {
      const float y = -1.0f + 2.0f * static_cast<float>(k) / 63.0f;
      c.rays.push_back(Ray{{-3.0f, y, 1.0f}, {1.0f, 0.0f, 0.0f}, 0.0f, INFINITY});
      c.rays.push_back(Ray{{y, -3.0f, 1.0f}, {0.0f, 1.0f, -0.0f}, 0.0f, INFINITY});
      c.must_hit.insert(c.must_hit.end(), 2, 0);
    }
    cases.push_back(std::move(c));
  }
  // A finely tessellated sphere seen from 30 radii: the tree's cells near
  // the surface are a small fraction of the distance t, so a traversal
  // whose cells are not conservative by the rounding error of t skips the
  // cell of the triangle that the intersection test hits.
  {
    ExtremeCase c = Case("dense sphere, far rays", "dense",
                         reduced ? ClosedSphereMesh(40, 80) : ClosedSphereMesh(100, 200));
    AddAimedRays(c, dvec3(0.0), 1.0, 7, SIZE_MAX, reduced ? 3 : 10, 30.0);
    cases.push_back(std::move(c));
  }
  // Slivers: a box of aspect 10^6 (10^3 x 10^-3 x 1) split into triangles.
  aimed("slivers (aspect 1e6)", "sliver", Mapped(cube, 1.0, dvec3(0.0), dvec3(1e3, 1e-3, 1.0)), dvec3(0.0), 1e-3);
  // Needles: a closed cone 10^3 long with a base of radius 10^-3.
  aimed("needles (cone 1e3 x 1e-3)", "needle", ClosedCone(32, 1e-3, 1e3), dvec3(0.0, 0.0, 1.0), 1e-3);
  // Degenerate (zero-area) and duplicated triangles added to a closed cube:
  // ties at equal t go to the smaller id in every format.
  {
    Scene s = cube;
    const size_t n = s.triangles.size();
    for (size_t i = 0; i < n; i += 3) s.triangles.push_back(s.triangles[i]);  // duplicates
    for (size_t i = 0; i < n; i += 5) {
      const Triangle& t = s.triangles[i];
      s.triangles.push_back({t.v0, t.v0, t.v1});                        // a repeated vertex
      s.triangles.push_back({t.v0, F((D(t.v0) + D(t.v1)) * 0.5), t.v1});  // collinear
    }
    s.material.assign(s.triangles.size(), 0);
    ExtremeCase c = Case("degenerate + duplicated", "degenerate", std::move(s));
    AddAimedRays(c, dvec3(0.0), 1.0, 4, n);
    cases.push_back(std::move(c));
  }
  // Many triangles through one point (the apex of a pyramid-like cone): the
  // kd-tree cannot separate them, so it reaches its maximal depth there.
  {
    const int n = reduced ? 300 : 600;
    ExtremeCase c = Case(std::to_string(n) + " triangles through one point", "one-point", ClosedCone(n, 1.0, 1.0));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const dvec3 apex(0.0, 0.0, 1.0), center(0.0, 0.0, 0.3);
    for (int k = 0; k < 256; ++k) {  // at the apex, from above
      const dvec3 o = apex + dvec3(u(rng), u(rng), 1.0 + 0.5 * u(rng));
      c.rays.push_back(Ray{F(o), F(apex - o + 0.01 * (center - apex)), 0.0f, INFINITY});
      c.must_hit.push_back(1);
    }
    AddAimedRays(c, center, 1.0, 6, 512);  // edges and vertices of the first side triangles
    cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace kdrt
