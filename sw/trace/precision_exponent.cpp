// The exponent criteria (docs/precision.md): the magnitudes the datapath
// meets, computed in double, against the normal range of E exponent bits,
// independently of the mantissa width. Each criterion looks at one side:
//  - overflow: a value must stay below 2^bias, one binade under the largest
//    finite value, so that rounding it up or adding two or three of them (the
//    determinant, T) cannot reach infinity whatever M is;
//  - flush: a value must be at least 2^(1-bias), the smallest normal.
// A flush is only counted for values that carry a scene's scale (a
// triangle's area, a hit distance): a tiny coordinate or edge value next to
// large ones flushes harmlessly, it is below the rounding error already there.
#include <algorithm>
#include <cmath>

#include "fp/ftz.h"
#include "trace/intersect.h"
#include "trace/precision_criteria.h"

namespace kdrt::precision {
namespace {

constexpr int kBeyondFp64 = 12;

int Bias(int e) { return (1 << (e - 1)) - 1; }

// Exponent bits for which |x| (finite, non-zero) stays below 2^bias.
int BitsNotOverflowing(double x) {
  if (x == 0 || !std::isfinite(x)) return 0;
  const int ilog = std::ilogb(x);
  for (int e = 2; e <= fp::kFp64.e; ++e) {
    if (ilog <= Bias(e) - 1) return e;
  }
  return kBeyondFp64;
}

// Exponent bits for which |x| (finite, non-zero) is a normal number.
int BitsNotFlushing(double x) {
  if (x == 0 || !std::isfinite(x)) return 0;
  const int ilog = std::ilogb(x);
  for (int e = 2; e <= fp::kFp64.e; ++e) {
    if (ilog >= 1 - Bias(e)) return e;
  }
  return kBeyondFp64;
}

// The exponent bits one item needs on one side: the most any of its values needs.
struct Need {
  int bits = 0;
  void Overflow(double x) { bits = std::max(bits, BitsNotOverflowing(x)); }
  void Flush(double x) { bits = std::max(bits, BitsNotFlushing(x)); }
};

double Abs3Max(const float v[3]) {
  return std::max({std::fabs(double{v[0]}), std::fabs(double{v[1]}), std::fabs(double{v[2]})});
}

// Twice the triangle's area: the watertight determinant of a ray along the
// normal (det = area2 * |n . d| / |d_kz|, within a factor sqrt(3) of
// area2 * |cos| for any direction).
double Area2(const img::TriangleRecord& t) {
  const double u[3] = {double{t.v1[0]} - t.v0[0], double{t.v1[1]} - t.v0[1], double{t.v1[2]} - t.v0[2]};
  const double v[3] = {double{t.v2[0]} - t.v0[0], double{t.v2[1]} - t.v0[1], double{t.v2[2]} - t.v0[2]};
  const double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

// The ray's [t0, t1] against the scene box (the clip unit's rule, exact in
// double): false when the ray misses the box or leaves it before t = 0.
bool BoxExit(const Ray& ray, const img::Header& h, double* t1_out) {
  double t0 = ray.tmin, t1 = ray.tmax;
  for (int i = 0; i < 3; ++i) {
    const double o = ray.o[i], d = ray.d[i];
    if (d == 0) {
      if (o < h.bounds_min[i] || o > h.bounds_max[i]) return false;
      continue;
    }
    const double ta = (h.bounds_min[i] - o) / d, tb = (h.bounds_max[i] - o) / d;
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  *t1_out = t1;
  return t0 <= t1 && t1 > 0;
}

// Exponent bits for which the triangle keeps its area when the coordinates
// below the smallest normal are stored as zero: a flushed coordinate is
// harmless beside large ones, unless every coordinate that gives the
// triangle its extent on some axis flushes (a needle of radius 1e-6 about an
// axis). Fewer bits flush more coordinates; counted from the most bits down,
// so the count never grows with more bits.
int BitsKeepingAreaAfterFlush(const img::TriangleRecord& t) {
  const float* v[3] = {t.v0, t.v1, t.v2};
  int first_safe = 0;  // from this many bits on, nothing flushes
  for (const float* p : v) {
    for (int i = 0; i < 3; ++i) first_safe = std::max(first_safe, BitsNotFlushing(p[i]));
  }
  for (int e = first_safe - 1; e >= 2; --e) {
    const double min_normal = std::ldexp(1.0, 1 - Bias(e));
    double q[3][3];
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < 3; ++i) q[k][i] = std::fabs(double{v[k][i]}) < min_normal ? 0.0 : double{v[k][i]};
    }
    if (Collinear(q[0], q[1], q[2])) return e + 1;
  }
  return 0;
}

}  // namespace

void AddImageExponentCriteria(const ImageView& image, std::vector<PrecisionCriterion>* out) {
  PrecisionCriterion coords{"coordinate_overflow", true, "triangles", "have a vertex coordinate that overflows",
                                true};
  PrecisionCriterion under{"triangle_underflow", true, "triangles",
                           "have a determinant (twice the area) that flushes to zero: no ray can hit them"};
  PrecisionCriterion over{"triangle_overflow", true, "triangles", "have a determinant (twice the area) that overflows"};
  PrecisionCriterion flush{"coordinate_flush", true, "triangles",
                           "become degenerate (no area) when their coordinates below the smallest normal flush to "
                           "zero",
                           true};
  for (uint32_t t = 0; t < image.header().tri_count; ++t) {
    const img::TriangleRecord tri = image.triangle(t);
    Need c;
    for (const float* v : {tri.v0, tri.v1, tri.v2}) c.Overflow(Abs3Max(v));
    coords.Add(c.bits);
    const double area2 = Area2(tri);
    if (area2 == 0) continue;  // degenerate in the image: never hit in any format
    Need u, o;
    u.Flush(area2);
    o.Overflow(area2);
    under.Add(u.bits);
    over.Add(o.bits);
    flush.Add(BitsKeepingAreaAfterFlush(tri));
  }
  out->push_back(coords);
  out->push_back(flush);
  out->push_back(under);
  out->push_back(over);
}

void AddRayExponentCriteria(const ImageView& image, const std::vector<Ray>& rays, const std::vector<Hit>& hits,
                            std::vector<PrecisionCriterion>* out) {
  PrecisionCriterion ray_over{"ray_overflow", true, "rays",
                              "overflow in ray setup or box clipping (origin, 1/d, box distances)"};
  PrecisionCriterion ray_under{"ray_underflow", true, "rays",
                               "flush to zero in ray setup or box clipping (d, 1/d, box exit distance)"};
  PrecisionCriterion hit_over{"hit_overflow", true, "hit tests",
                              "overflow (vertex - origin, edge products, determinant, T or t)"};
  PrecisionCriterion hit_under{"hit_underflow", true, "hit tests",
                               "flush to zero (vertex - origin, z, T at normal incidence, tmin * det)"};
  fp::ScopedIeeeDefault ieee;  // plain double arithmetic whatever the caller set
  const fp::NativeF64Arith a;
  const img::Header& h = image.header();
  for (size_t i = 0; i < rays.size(); ++i) {
    // The datapath sees the ray in the image's frame (trace/frame.h): the
    // magnitudes that matter are the framed ones.
    const Ray ray = ToFrame(rays[i], image.frame()).ray;
    Need over, under;
    for (int k = 0; k < 3; ++k) over.Overflow(std::fabs(double{ray.o[k]}));
    over.Overflow(ray.tmin);
    over.Overflow(ray.tmax);  // +inf (no limit) is skipped
    const double dz = std::max({std::fabs(double{ray.d[0]}), std::fabs(double{ray.d[1]}), std::fabs(double{ray.d[2]})});
    over.Overflow(dz);
    over.Overflow(1 / dz);
    under.Flush(dz);
    under.Flush(1 / dz);
    double t1 = 0;
    if (BoxExit(ray, h, &t1)) {
      over.Overflow(t1);
      under.Flush(t1);
      for (int k = 0; k < 3; ++k) {
        over.Overflow(std::fabs(h.bounds_min[k] - double{ray.o[k]}));
        over.Overflow(std::fabs(h.bounds_max[k] - double{ray.o[k]}));
      }
    }
    ray_over.Add(over.bits);
    ray_under.Add(under.bits);
    if (!hits[i].IsHit()) continue;

    // The hit's watertight test (docs/dataflow.md, section 3) in double.
    const RaySetup<fp::NativeF64Arith> r = SetupRay(a, ray);
    const img::TriangleRecord tri = image.triangle(hits[i].prim);
    const float* v[3] = {tri.v0, tri.v1, tri.v2};
    Need ho, hu;
    double p[3][3], x[3], y[3], z[3], p_max = 0, z_max = 0;
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) {
        p[k][j] = v[k][j] - r.o[j];
        p_max = std::max(p_max, std::fabs(p[k][j]));
      }
      x[k] = p[k][r.kx] - r.sx * p[k][r.kz];
      y[k] = p[k][r.ky] - r.sy * p[k][r.kz];
      z[k] = r.sz * p[k][r.kz];
      z_max = std::max(z_max, std::fabs(z[k]));
      ho.Overflow(std::fabs(x[k]));
      ho.Overflow(std::fabs(y[k]));
      ho.Overflow(std::fabs(z[k]));
    }
    ho.Overflow(p_max);
    const double prod[6] = {x[2] * y[1], y[2] * x[1], x[0] * y[2], y[0] * x[2], x[1] * y[0], y[1] * x[0]};
    for (double q : prod) ho.Overflow(std::fabs(q));
    const double e[3] = {prod[0] - prod[1], prod[2] - prod[3], prod[4] - prod[5]};
    const double det = (e[0] + e[1]) + e[2];
    const double ez[3] = {e[0] * z[0], e[1] * z[1], e[2] * z[2]};
    const double t_scaled = (ez[0] + ez[1]) + ez[2];
    for (int k = 0; k < 3; ++k) {
      ho.Overflow(std::fabs(e[k]));
      ho.Overflow(std::fabs(ez[k]));
    }
    ho.Overflow(std::fabs(det));
    ho.Overflow(std::fabs(ez[0] + ez[1]));
    ho.Overflow(std::fabs(t_scaled));
    if (det != 0) ho.Overflow(std::fabs(t_scaled / det));
    const double area2 = Area2(tri);
    hu.Flush(p_max);
    hu.Flush(z_max);
    hu.Flush(area2 * z_max);
    if (ray.tmin > 0) hu.Flush(ray.tmin * area2);
    hit_over.Add(ho.bits);
    hit_under.Add(hu.bits);
  }
  out->push_back(ray_over);
  out->push_back(ray_under);
  out->push_back(hit_over);
  out->push_back(hit_under);
}

}  // namespace kdrt::precision
