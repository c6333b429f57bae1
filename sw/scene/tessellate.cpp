#include "scene/tessellate.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

namespace kdrt {

namespace {

constexpr double kPi = 3.14159265358979323846;

glm::vec3 ToFloat(const glm::dvec3& p) {
  return glm::vec3(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z));
}

// cos/sin of 2*pi*i/n, with the quarter turns exact so axis-aligned seams
// do not pick up 1e-17 noise.
void UnitCircle(int i, int n, double* c, double* s) {
  if ((4 * i) % n == 0) {
    static const double kC[4] = {1, 0, -1, 0};
    static const double kS[4] = {0, 1, 0, -1};
    int q = (4 * i / n) % 4;
    *c = kC[q];
    *s = kS[q];
    return;
  }
  double a = 2.0 * kPi * i / n;
  *c = std::cos(a);
  *s = std::sin(a);
}

}  // namespace

void MakeFrame(const glm::dvec3& axis, glm::dvec3* u, glm::dvec3* v) {
  glm::dvec3 a = glm::abs(axis);
  glm::dvec3 helper(0.0);
  if (a.x <= a.y && a.x <= a.z) {
    helper.x = 1.0;
  } else if (a.y <= a.z) {
    helper.y = 1.0;
  } else {
    helper.z = 1.0;
  }
  *u = glm::normalize(glm::cross(axis, helper));
  *v = glm::cross(axis, *u);
}

int SphereTriangleCount(int segments) {
  int stacks = std::max(2, segments / 2);
  return 2 * segments * (stacks - 1);
}

void AddSphere(SceneBuilder& b, const glm::dvec3& centre, double radius, int segments) {
  const int stacks = std::max(2, segments / 2);
  // rings[j][i] for the stacks-1 latitude rings between the poles.
  std::vector<glm::vec3> ring((stacks - 1) * segments);
  for (int j = 1; j < stacks; ++j) {
    double theta = kPi * j / stacks;
    double z = (2 * j == stacks) ? 0.0 : std::cos(theta);
    double rr = std::sin(theta);
    for (int i = 0; i < segments; ++i) {
      double c, s;
      UnitCircle(i, segments, &c, &s);
      ring[(j - 1) * segments + i] = ToFloat(centre + radius * glm::dvec3(rr * c, rr * s, z));
    }
  }
  auto at = [&](int j, int i) -> const glm::vec3& {
    return ring[(j - 1) * segments + (i % segments)];
  };
  const glm::vec3 north = ToFloat(centre + glm::dvec3(0, 0, radius));
  const glm::vec3 south = ToFloat(centre - glm::dvec3(0, 0, radius));
  for (int i = 0; i < segments; ++i) b.AddTriangle(north, at(1, i), at(1, i + 1));
  for (int j = 1; j + 1 < stacks; ++j) {
    for (int i = 0; i < segments; ++i) {
      glm::vec3 quad[4] = {at(j, i), at(j + 1, i), at(j + 1, i + 1), at(j, i + 1)};
      b.AddFan(quad, 4);
    }
  }
  for (int i = 0; i < segments; ++i) b.AddTriangle(south, at(stacks - 1, i + 1), at(stacks - 1, i));
}

void AddCone(SceneBuilder& b, const glm::dvec3& base, double rb, const glm::dvec3& apex, double ra,
             int segments, int bands) {
  glm::dvec3 axis = glm::normalize(apex - base);
  glm::dvec3 u, v;
  MakeFrame(axis, &u, &v);
  // Ring j (0 = base, bands = apex) is computed once and shared by the bands
  // on either side of it.
  std::vector<glm::vec3> ring((bands + 1) * segments);
  for (int j = 0; j <= bands; ++j) {
    const double t = static_cast<double>(j) / bands;
    // The end rings from base and apex themselves, exactly as one band's.
    const glm::dvec3 centre = j == 0 ? base : j == bands ? apex : base + t * (apex - base);
    const double r = j == 0 ? rb : j == bands ? ra : rb + t * (ra - rb);
    for (int i = 0; i < segments; ++i) {
      double c, s;
      UnitCircle(i, segments, &c, &s);
      ring[j * segments + i] = ToFloat(centre + r * (c * u + s * v));
    }
  }
  for (int j = 0; j < bands; ++j) {
    const glm::vec3* bottom = &ring[j * segments];
    const glm::vec3* top = &ring[(j + 1) * segments];
    const bool point_below = j == 0 && rb == 0.0;
    const bool point_above = j == bands - 1 && ra == 0.0;
    for (int i = 0; i < segments; ++i) {
      int k = (i + 1) % segments;
      if (point_below) {
        b.AddTriangle(bottom[i], top[k], top[i]);
      } else if (point_above) {
        b.AddTriangle(bottom[i], bottom[k], top[i]);
      } else {
        glm::vec3 quad[4] = {bottom[i], bottom[k], top[k], top[i]};
        b.AddFan(quad, 4);
      }
    }
  }
}

int ConeBands(const glm::dvec3& base, double rb, const glm::dvec3& apex, double ra, int segments,
              double max_aspect) {
  if (max_aspect <= 0.0) return 1;
  const double side = 2.0 * std::max(rb, ra) * std::sin(kPi / segments);
  const double length = glm::length(apex - base);
  if (!(side > 0.0)) return 1;
  const double bands = std::ceil(length / (max_aspect * side));
  return static_cast<int>(std::clamp(bands, 1.0, static_cast<double>(kMaxConeBands)));
}

void AddTorus(SceneBuilder& b, const glm::dvec3& centre, const glm::dvec3& axis, double major_r,
              double minor_r, int major_segments, int minor_segments) {
  glm::dvec3 u, v;
  MakeFrame(axis, &u, &v);
  std::vector<glm::vec3> p(major_segments * minor_segments);
  for (int i = 0; i < major_segments; ++i) {
    double c, s;
    UnitCircle(i, major_segments, &c, &s);
    glm::dvec3 radial = c * u + s * v;
    for (int k = 0; k < minor_segments; ++k) {
      double ck, sk;
      UnitCircle(k, minor_segments, &ck, &sk);
      p[i * minor_segments + k] =
          ToFloat(centre + (major_r + minor_r * ck) * radial + (minor_r * sk) * axis);
    }
  }
  for (int i = 0; i < major_segments; ++i) {
    int i1 = (i + 1) % major_segments;
    for (int k = 0; k < minor_segments; ++k) {
      int k1 = (k + 1) % minor_segments;
      glm::vec3 quad[4] = {p[i * minor_segments + k], p[i1 * minor_segments + k],
                           p[i1 * minor_segments + k1], p[i * minor_segments + k1]};
      b.AddFan(quad, 4);
    }
  }
}

void AddGrid(SceneBuilder& b, const glm::dvec3& corner, const glm::dvec3& edge_u,
             const glm::dvec3& edge_v, int nu, int nv) {
  std::vector<glm::vec3> p((nu + 1) * (nv + 1));
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      p[j * (nu + 1) + i] = ToFloat(corner + (static_cast<double>(i) / nu) * edge_u +
                                    (static_cast<double>(j) / nv) * edge_v);
    }
  }
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      glm::vec3 quad[4] = {p[j * (nu + 1) + i], p[j * (nu + 1) + i + 1],
                           p[(j + 1) * (nu + 1) + i + 1], p[(j + 1) * (nu + 1) + i]};
      b.AddFan(quad, 4);
    }
  }
}

}  // namespace kdrt
