// The mantissa criteria (docs/precision.md): what rounding every fp32 value
// of the image to m fraction bits does to the geometry, with an unbounded
// exponent range so that they depend on m alone. An item needs
// 1 + (the largest m < 23 at which it breaks) bits, or 0 if it never breaks:
// rounding is not monotone in m (a pair that two grids separate can meet on a
// finer one), so "breaks at m or at some finer width" is what makes the
// counts shrink as m grows.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "fp/format.h"
#include "trace/frame.h"
#include "trace/precision_criteria.h"

namespace kdrt {

float RoundMantissa(float x, int m) {
  if (m >= 23) return x;
  const uint32_t u = fp::BitsOf(x);
  if ((u & 0x7F800000u) == 0x7F800000u) return x;  // inf, NaN
  return fp::FloatOf(fp::RoundEncoding(u, 23 - m));
}

namespace {

// Dekker's exact product: a * b == hi + lo exactly (binary64, round to
// nearest, no overflow or underflow; -ffp-contract=off keeps it exact).
void TwoProduct(double a, double b, double* hi, double* lo) {
  constexpr double kSplit = 134217729.0;  // 2^27 + 1
  *hi = a * b;
  double t = kSplit * a;
  const double ah = t - (t - a), al = a - ah;
  t = kSplit * b;
  const double bh = t - (t - b), bl = b - bh;
  *lo = ((ah * bh - *hi) + ah * bl + al * bh) + al * bl;
}

// a * b == c * d exactly: hi is the rounded product and lo the exact rest,
// so equal products give equal pairs and different ones different pairs.
bool ProductsEqual(double a, double b, double c, double d) {
  double h1, l1, h2, l2;
  TwoProduct(a, b, &h1, &l1);
  TwoProduct(c, d, &h2, &l2);
  return h1 == h2 && l1 == l2;
}

}  // namespace

bool Collinear(const double a[3], const double b[3], const double c[3]) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return ProductsEqual(u[1], v[2], u[2], v[1]) && ProductsEqual(u[2], v[0], u[0], v[2]) &&
         ProductsEqual(u[0], v[1], u[1], v[0]);
}

namespace precision {
namespace {

using Key = std::array<uint32_t, 3>;

uint32_t KeyBits(float x) {
  const uint32_t u = fp::BitsOf(x);
  return u == 0x80000000u ? 0u : u;  // -0 and +0 are one position
}

// vertex_collapse: distinct vertex positions that some width below 23 bits
// rounds onto the same point as another distinct position.
PrecisionCriterion VertexCollapse(const ImageView& image) {
  PrecisionCriterion c{"vertex_collapse", false, "vertices", "collapse onto another vertex", true};
  std::vector<Key> verts;
  for (uint32_t t = 0; t < image.header().tri_count; ++t) {
    const img::TriangleRecord tri = image.triangle(t);
    for (const float* v : {tri.v0, tri.v1, tri.v2}) verts.push_back({KeyBits(v[0]), KeyBits(v[1]), KeyBits(v[2])});
  }
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());

  std::vector<int> needs(verts.size(), 0);
  size_t unset = verts.size();
  struct Rounded {
    Key key;
    uint32_t index;
    bool operator<(const Rounded& o) const { return key < o.key; }
  };
  std::vector<Rounded> rounded(verts.size());
  for (int m = kMaxMantissaBits - 1; m >= 1 && unset > 0; --m) {
    for (size_t i = 0; i < verts.size(); ++i) {
      Key k;
      for (int a = 0; a < 3; ++a) k[a] = KeyBits(RoundMantissa(fp::FloatOf(verts[i][a]), m));
      rounded[i] = {k, static_cast<uint32_t>(i)};
    }
    std::sort(rounded.begin(), rounded.end());
    for (size_t begin = 0, end; begin < rounded.size(); begin = end) {
      for (end = begin + 1; end < rounded.size() && rounded[end].key == rounded[begin].key;) ++end;
      if (end - begin < 2) continue;
      for (size_t j = begin; j < end; ++j) {
        int& n = needs[rounded[j].index];
        if (n == 0) {
          n = m + 1;
          --unset;
        }
      }
    }
  }
  for (int n : needs) c.Add(n);
  return c;
}

// The bits a triangle needs to keep its area when load(m, p) gives its three
// vertices at m mantissa bits: 1 + the largest m < 23 at which they are
// collinear, 0 if never, -1 if they are collinear already at 23 bits.
template <class Load>
int BitsKeepingArea(Load load) {
  double p[3][3];
  load(kMaxMantissaBits, p);
  if (Collinear(p[0], p[1], p[2])) return -1;
  for (int m = kMaxMantissaBits - 1; m >= 1; --m) {
    load(m, p);
    if (Collinear(p[0], p[1], p[2])) return m + 1;
  }
  return 0;
}

// degenerate_triangles: triangles with area in the image whose rounded
// vertices are collinear at some width below 23 bits.
PrecisionCriterion DegenerateTriangles(const ImageView& image, int threads) {
  PrecisionCriterion c{"degenerate_triangles", false, "triangles", "become degenerate (no area)", true};
  const uint32_t n = image.header().tri_count;
  std::vector<int> needs(n, -1);  // -1: degenerate in the image, not checked
  ParallelFor(n, threads, [&](size_t t) {
    const img::TriangleRecord tri = image.triangle(static_cast<uint32_t>(t));
    const float* v[3] = {tri.v0, tri.v1, tri.v2};
    needs[t] = BitsKeepingArea([&](int m, double p[3][3]) {
      for (int k = 0; k < 3; ++k) {
        for (int a = 0; a < 3; ++a) p[k][a] = RoundMantissa(v[k][a], m);
      }
    });
  });
  for (int b : needs) {
    if (b >= 0) c.Add(b);
  }
  return c;
}

// split_order: inner nodes whose split lies inside its cell on its axis
// (between the planes of the ancestors and the scene box) in the image, and
// outside the rounded cell at some width below 23 bits. Rounding is monotone,
// so this cannot happen: every triangle stays inside its rounded leaf cells
// and the traversal's slack covers flat cells (a split that rounds onto a
// bounding plane), which is why distinct planes may merge. The check stays as
// the guard of that argument (a mapping of the image that is not monotone
// would break it).
PrecisionCriterion SplitOrder(const ImageView& image) {
  PrecisionCriterion c{"split_order", false, "split planes", "leave their cell", true};
  const img::Header& h = image.header();
  struct Cell {
    uint32_t node;
    float lo[3], hi[3];
  };
  std::vector<Cell> stack;
  Cell root{0, {}, {}};
  for (int a = 0; a < 3; ++a) {
    root.lo[a] = h.bounds_min[a];
    root.hi[a] = h.bounds_max[a];
  }
  stack.push_back(root);
  while (!stack.empty()) {
    const Cell cell = stack.back();
    stack.pop_back();
    const img::Node node = image.node(cell.node);
    if (node.IsLeaf()) continue;
    const int a = node.Axis();
    const float s = node.Split(), lo = cell.lo[a], hi = cell.hi[a];
    if (lo <= s && s <= hi) {
      int needs = 0;
      for (int m = kMaxMantissaBits - 1; m >= 1; --m) {
        const float rs = RoundMantissa(s, m);
        if (rs < RoundMantissa(lo, m) || RoundMantissa(hi, m) < rs) {
          needs = m + 1;
          break;
        }
      }
      c.Add(needs);
    }
    Cell below = cell, above = cell;
    below.node = image.next(cell.node);
    below.hi[a] = s;
    above.node = node.AboveChild();
    above.lo[a] = s;
    stack.push_back(below);
    stack.push_back(above);
  }
  return c;
}

// x rounded to m bits (nearest even, unbounded exponent range): RoundMantissa
// for a double, such as the difference of two rounded values, on the
// encoding (exact: these doubles are normal, as differences of fp32 values
// are multiples of 2^-149; frexp and ldexp took a third of the analysis).
double RoundMantissaD(double x, int m) {
  if (x == 0 || !std::isfinite(x) || m >= 52) return x;
  uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  u = fp::RoundEncoding(u, 52 - m);
  std::memcpy(&x, &u, sizeof x);
  return x;
}

}  // namespace

// hit_degenerate: the triangle a ray hits (in fp64) as the watertight test
// sees it: vertex - origin of the values the format loads, rounded once more.
// When the ray starts far from a small triangle, that difference keeps none
// of the triangle's extent and the test sees no area: the ray passes through
// a mesh that has collapsed (holes on a closed mesh, seen with e6m5 on a
// sphere seen from 100 radii).
void AddRayMantissaCriteria(const ImageView& image, const std::vector<Ray>& rays, const std::vector<Hit>& hits,
                            int threads, std::vector<PrecisionCriterion>* out) {
  PrecisionCriterion c{"hit_degenerate", false, "hit tests",
                       "lose their area relative to the ray origin (vertex - origin)"};
  std::vector<int> needs(rays.size(), -1);  // -1: a miss, or no area even in fp32 (nothing to lose)
  ParallelFor(rays.size(), threads, [&](size_t i) {
    if (!hits[i].IsHit()) return;
    const Ray ray = ToFrame(rays[i], image.frame()).ray;
    const img::TriangleRecord tri = image.triangle(hits[i].prim);
    const float* v[3] = {tri.v0, tri.v1, tri.v2};
    needs[i] = BitsKeepingArea([&](int m, double p[3][3]) {
      for (int k = 0; k < 3; ++k) {
        for (int a = 0; a < 3; ++a) {
          p[k][a] = RoundMantissaD(double{RoundMantissa(v[k][a], m)} - double{RoundMantissa(ray.o[a], m)}, m);
        }
      }
    });
  });
  for (int b : needs) {
    if (b >= 0) c.Add(b);
  }
  out->push_back(std::move(c));
}

void AddMantissaCriteria(const ImageView& image, int threads, std::vector<PrecisionCriterion>* out) {
  out->push_back(VertexCollapse(image));
  out->push_back(DegenerateTriangles(image, threads));
  out->push_back(SplitOrder(image));
}

}  // namespace precision
}  // namespace kdrt
