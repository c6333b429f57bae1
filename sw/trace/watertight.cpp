#include "trace/watertight.h"

#include <cmath>
#include <random>
#include <string>

#include "common/error.h"

namespace kdrt {
namespace {

Scene EmptyMesh(const std::string& source) {
  Scene s;
  s.colors = {{1.0f, 1.0f, 1.0f}};
  s.source = source;
  return s;
}

void AddTriangle(Scene& s, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  s.triangles.push_back({a, b, c});
  s.material.push_back(0);
}

}  // namespace

Scene ClosedSphereMesh(int rings, int segments) {
  if (rings < 2 || rings > 4096 || segments < 3 || segments > 4096) {
    throw InputError("closed sphere mesh: need 2 <= rings <= 4096 and 3 <= segments <= 4096, got " +
                     std::to_string(rings) + " and " + std::to_string(segments));
  }
  Scene s = EmptyMesh("closed sphere mesh " + std::to_string(rings) + "x" + std::to_string(segments));
  // One table of vertices, indexed (ring, segment); the longitude wraps by
  // index, never by recomputing the angle 2*pi, so the seam is closed too.
  std::vector<glm::vec3> ring_vertex(static_cast<size_t>(rings + 1) * segments);
  auto at = [&](int i, int j) -> glm::vec3& {
    return ring_vertex[static_cast<size_t>(i) * segments + (j % segments)];
  };
  for (int i = 0; i <= rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      if (i == 0 || i == rings) {
        at(i, j) = {0.0f, 0.0f, i == 0 ? 1.0f : -1.0f};  // the poles: one vertex each
        continue;
      }
      const double theta = M_PI * i / rings, phi = 2.0 * M_PI * j / segments;
      at(i, j) = {static_cast<float>(std::sin(theta) * std::cos(phi)),
                  static_cast<float>(std::sin(theta) * std::sin(phi)), static_cast<float>(std::cos(theta))};
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      // Seen from outside, increasing j runs counter-clockwise around +z and
      // increasing i runs from the north pole southwards.
      const glm::vec3 &a = at(i, j), &b = at(i + 1, j), &c = at(i + 1, j + 1), &d = at(i, j + 1);
      if (i > 0) AddTriangle(s, a, b, d);
      if (i < rings - 1) AddTriangle(s, d, b, c);
    }
  }
  return s;
}

Scene ClosedCubeMesh(int n) {
  if (n < 1 || n > 1024) throw InputError("closed cube mesh: need 1 <= n <= 1024, got " + std::to_string(n));
  Scene s = EmptyMesh("closed cube mesh " + std::to_string(n));
  auto coord = [n](int i) { return static_cast<float>(-1.0 + 2.0 * i / n); };
  for (int axis = 0; axis < 3; ++axis) {
    const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;  // u x v = +axis
    for (int side = 0; side < 2; ++side) {
      auto lattice = [&](int iu, int iv) {
        glm::vec3 p;
        p[axis] = side == 0 ? -1.0f : 1.0f;
        p[u_axis] = coord(iu);
        p[v_axis] = coord(iv);
        return p;
      };
      for (int iu = 0; iu < n; ++iu) {
        for (int iv = 0; iv < n; ++iv) {
          const glm::vec3 a = lattice(iu, iv), b = lattice(iu + 1, iv), c = lattice(iu + 1, iv + 1),
                          d = lattice(iu, iv + 1);
          if (side == 1) {  // a, b, c, d is counter-clockwise seen from +axis
            AddTriangle(s, a, b, c);
            AddTriangle(s, a, c, d);
          } else {
            AddTriangle(s, a, c, b);
            AddTriangle(s, a, d, c);
          }
        }
      }
    }
  }
  return s;
}

std::vector<Ray> WatertightRays(const Scene& scene, uint32_t seed) {
  // mt19937's raw output is specified by the standard; the distributions are
  // not, so the jitter is derived by hand to be the same everywhere.
  std::mt19937 rng(seed);
  auto jitter = [&rng]() { return static_cast<float>((rng() >> 8) * (1.0 / 16777216.0) * 0.1 - 0.05); };
  std::vector<Ray> rays;
  rays.reserve(scene.triangles.size() * 6);
  for (const Triangle& t : scene.triangles) {
    const glm::vec3 targets[6] = {t.v0, t.v1, t.v2, (t.v0 + t.v1) * 0.5f, (t.v1 + t.v2) * 0.5f,
                                  (t.v2 + t.v0) * 0.5f};
    for (const glm::vec3& target : targets) {
      Ray r;
      for (int k = 0; k < 3; ++k) r.o[k] = 3.0f * target[k] + jitter();
      r.d = target - r.o;
      r.tmin = 0.0f;
      r.tmax = INFINITY;
      rays.push_back(r);
    }
  }
  return rays;
}

}  // namespace kdrt
