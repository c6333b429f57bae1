// The triangle/box overlap test the grid, hgrid and octree builders bin
// with: a triangle goes to every cell it meets.
#pragma once

#include <algorithm>
#include <cmath>

#include "common/image_format.h"

namespace kdrt {

inline double Dot(const double* p, const double* q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; }

// Akenine-Moller's separating-axis triangle/box test ("Fast 3D triangle-box
// overlap testing", 2001) in double, split in two: the box-independent half
// (the candidate axes and the triangle's extent along each) is computed once
// per triangle and serves every candidate child of a cell. Touching counts
// as overlapping; a zero axis (an edge parallel to a box axis) never
// separates.
class TriangleBoxTest {
 public:
  explicit TriangleBoxTest(const img::TriangleRecord& t) {
    const float* src[3] = {t.v0, t.v1, t.v2};
    double v[3][3], e[3][3];
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) v[i][k] = src[i][k];
    }
    for (int k = 0; k < 3; ++k) {
      box_lo_[k] = std::min({v[0][k], v[1][k], v[2][k]});
      box_hi_[k] = std::max({v[0][k], v[1][k], v[2][k]});
      for (int i = 0; i < 3; ++i) e[i][k] = v[(i + 1) % 3][k] - v[i][k];
    }
    SetAxis(0, e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
            e[0][0] * e[1][1] - e[0][1] * e[1][0], v);
    for (int i = 0; i < 3; ++i) {  // box axis x edge
      SetAxis(1 + 3 * i, 0.0, -e[i][2], e[i][1], v);
      SetAxis(2 + 3 * i, e[i][2], 0.0, -e[i][0], v);
      SetAxis(3 + 3 * i, -e[i][1], e[i][0], 0.0, v);
    }
  }

  bool Overlaps(const double lo[3], const double hi[3]) const {
    double centre[3], half[3];
    for (int k = 0; k < 3; ++k) {
      if (box_lo_[k] > hi[k] || box_hi_[k] < lo[k]) return false;
      centre[k] = 0.5 * (lo[k] + hi[k]);
      half[k] = 0.5 * (hi[k] - lo[k]);
    }
    for (int a = 0; a < kAxes; ++a) {
      const double c = Dot(centre, axis_[a]);
      const double r = Dot(half, abs_[a]);
      if (min_[a] > c + r || max_[a] < c - r) return false;
    }
    return true;
  }

 private:
  static constexpr int kAxes = 10;  // the normal and the nine edge cross products

  void SetAxis(int a, double x, double y, double z, const double v[3][3]) {
    const double axis[3] = {x, y, z};
    for (int k = 0; k < 3; ++k) {
      axis_[a][k] = axis[k];
      abs_[a][k] = std::fabs(axis[k]);
    }
    const double d0 = Dot(v[0], axis), d1 = Dot(v[1], axis), d2 = Dot(v[2], axis);
    min_[a] = std::min({d0, d1, d2});
    max_[a] = std::max({d0, d1, d2});
  }

  double axis_[kAxes][3], abs_[kAxes][3], min_[kAxes], max_[kAxes];
  double box_lo_[3], box_hi_[3];  // the box face axes
};

}  // namespace kdrt
