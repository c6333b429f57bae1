// Perfect splits (Havran; Wald & Havran 2006): the box a triangle occupies in
// a node is the box of the triangle clipped to the node cell, not the
// triangle's whole box, so a long triangle stops counting in cells it only
// passes by in its bounding box.
#include <algorithm>
#include <cmath>
#include <limits>

#include "accel/build_util.h"

namespace kdrt::accel {
namespace {

// Double rounding errors of the clip are far below this fraction of the
// coordinates' magnitude; points this close outside a plane count as inside
// and the box grows by it, which keeps the result conservative.
constexpr double kRelTolerance = 1e-12;

constexpr int kMaxPolygon = 16;  // 3 vertices + at most one per clip plane

struct Polygon {
  double p[kMaxPolygon][3];
  int n = 0;
};

// Keeps the part of `in` with sign * (x[axis] - plane) <= tol.
void ClipAgainstPlane(const Polygon& in, int axis, double plane, double sign, double tol,
                      Polygon* out) {
  out->n = 0;
  for (int i = 0; i < in.n; ++i) {
    const double* cur = in.p[i];
    const double* nxt = in.p[(i + 1) % in.n];
    const bool cur_in = sign * (cur[axis] - plane) <= tol;
    const bool nxt_in = sign * (nxt[axis] - plane) <= tol;
    if (cur_in) {
      for (int a = 0; a < 3; ++a) out->p[out->n][a] = cur[a];
      ++out->n;
    }
    if (cur_in != nxt_in) {
      double t = (plane - cur[axis]) / (nxt[axis] - cur[axis]);
      t = std::min(1.0, std::max(0.0, t));
      double* q = out->p[out->n];
      for (int a = 0; a < 3; ++a) q[a] = cur[a] + t * (nxt[a] - cur[a]);
      q[axis] = plane;
      ++out->n;
    }
  }
}

float RoundDown(double d) {
  float f = static_cast<float>(d);
  if (static_cast<double>(f) > d) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

float RoundUp(double d) {
  float f = static_cast<float>(d);
  if (static_cast<double>(f) < d) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

bool ClippedTriangleBox(const Triangle& t, const Box& cell, Box* out) {
  Polygon a, b;
  const glm::vec3* v[3] = {&t.v0, &t.v1, &t.v2};
  double tol[3];
  for (int axis = 0; axis < 3; ++axis) {
    double mag = std::max(std::fabs(static_cast<double>(cell.lo[axis])),
                          std::fabs(static_cast<double>(cell.hi[axis])));
    for (int i = 0; i < 3; ++i) mag = std::max(mag, std::fabs(static_cast<double>((*v[i])[axis])));
    tol[axis] = kRelTolerance * mag;
  }
  a.n = 3;
  for (int i = 0; i < 3; ++i) {
    for (int axis = 0; axis < 3; ++axis) a.p[i][axis] = (*v[i])[axis];
  }
  Polygon* cur = &a;
  Polygon* next = &b;
  // A plane all three vertices lie inside of leaves the polygon as it is
  // (its points are their convex combinations, inside up to rounding far
  // below tol), so it is skipped: most triangles of a node lie inside most
  // of its faces.
  for (int axis = 0; axis < 3; ++axis) {
    const float tri_lo = std::min({t.v0[axis], t.v1[axis], t.v2[axis]});
    const float tri_hi = std::max({t.v0[axis], t.v1[axis], t.v2[axis]});
    if (tri_lo < cell.lo[axis]) {
      ClipAgainstPlane(*cur, axis, cell.lo[axis], -1.0, tol[axis], next);
      std::swap(cur, next);
      if (cur->n == 0) return false;
    }
    if (tri_hi > cell.hi[axis]) {
      ClipAgainstPlane(*cur, axis, cell.hi[axis], 1.0, tol[axis], next);
      std::swap(cur, next);
      if (cur->n == 0) return false;
    }
  }
  for (int axis = 0; axis < 3; ++axis) {
    double lo = cur->p[0][axis];
    double hi = lo;
    for (int i = 1; i < cur->n; ++i) {
      lo = std::min(lo, cur->p[i][axis]);
      hi = std::max(hi, cur->p[i][axis]);
    }
    // Widening must not carry the box past the triangle's own box: a triangle
    // touching a split plane from one side would then count on both sides.
    const float tri_lo = std::min({t.v0[axis], t.v1[axis], t.v2[axis]});
    const float tri_hi = std::max({t.v0[axis], t.v1[axis], t.v2[axis]});
    const float flo = std::max(RoundDown(lo - tol[axis]), tri_lo);
    const float fhi = std::min(RoundUp(hi + tol[axis]), tri_hi);
    out->lo[axis] = std::min(std::max(flo, cell.lo[axis]), cell.hi[axis]);
    out->hi[axis] = std::max(std::min(fhi, cell.hi[axis]), cell.lo[axis]);
  }
  return true;
}

}  // namespace kdrt::accel
