// Ray/triangle tests, templated on an arithmetic policy (fp/format.h:
// NativeF32Arith or SoftArith) so that the same source defines the fp32 fast
// path and every reduced-precision format. The operation order here IS the
// hardware's: docs/dataflow.md lists it step by step and the RTL intersection
// unit computes exactly these operations in exactly this order.
#pragma once

#include <cstdint>

#include "common/image_format.h"
#include "common/ray.h"

namespace kdrt {

enum class IsectMethod { kWatertight, kMoller };

// A ray converted into the datapath format, with the per-ray constants of
// both the traversal (reciprocal direction) and the watertight test
// (axis permutation and shear), computed once in the ray setup stage.
template <class A>
struct RaySetup {
  using T = typename A::T;
  T o[3], d[3], inv_d[3];
  T tmin, tmax;
  int kx, ky, kz;
  T sx, sy, sz;
};

template <class A>
RaySetup<A> SetupRay(const A& a, const Ray& ray) {
  RaySetup<A> r;
  for (int i = 0; i < 3; ++i) {
    r.o[i] = a.Load(ray.o[i]);
    r.d[i] = a.Load(ray.d[i]);
    r.inv_d[i] = a.Div(a.One(), r.d[i]);
  }
  r.tmin = a.Load(ray.tmin);
  r.tmax = a.Load(ray.tmax);
  // kz = axis of the largest |d|; the first such axis on ties.
  r.kz = 0;
  if (a.Lt(a.Abs(r.d[r.kz]), a.Abs(r.d[1]))) r.kz = 1;
  if (a.Lt(a.Abs(r.d[r.kz]), a.Abs(r.d[2]))) r.kz = 2;
  r.kx = r.kz == 2 ? 0 : r.kz + 1;
  r.ky = r.kx == 2 ? 0 : r.kx + 1;
  // Swapping kx and ky for a negative dz keeps the winding, so the sign of
  // the determinant keeps meaning "front side".
  if (a.IsNeg(r.d[r.kz])) {
    int t = r.kx;
    r.kx = r.ky;
    r.ky = t;
  }
  r.sx = a.Div(r.d[r.kx], r.d[r.kz]);
  r.sy = a.Div(r.d[r.ky], r.d[r.kz]);
  r.sz = a.Div(a.One(), r.d[r.kz]);
  // A shear that flushes to zero makes the test trace a ray without that
  // direction component, parallel to that axis' planes. The traversal must
  // trace the same ray: with the component kept, its plane crossings move by
  // up to t itself from where the test sees the ray, and the cells it visits
  // no longer hold the triangle the test hits (fp16, a sphere of 102k
  // triangles: a ray with |d_y / d_z| = 4e-5 fell through). So the component
  // becomes a zero of its sign, and its reciprocal an infinity, for both.
  if (a.IsZero(r.sx) && !a.IsZero(r.d[r.kx])) {
    r.d[r.kx] = a.IsNeg(r.d[r.kx]) ? a.Neg(a.Zero()) : a.Zero();
    r.inv_d[r.kx] = a.Div(a.One(), r.d[r.kx]);
  }
  if (a.IsZero(r.sy) && !a.IsZero(r.d[r.ky])) {
    r.d[r.ky] = a.IsNeg(r.d[r.ky]) ? a.Neg(a.Zero()) : a.Zero();
    r.inv_d[r.ky] = a.Div(a.One(), r.d[r.ky]);
  }
  return r;
}

// A hit candidate from one test, in the datapath format.
template <class A>
struct Candidate {
  typename A::T t, u, v;
  bool hit = false;
};

// Woop, Benthin & Wald 2013. Hit iff all edge functions have one sign (zeros
// allowed: edges and vertices are inside, and a shared edge computes exactly
// negated values in its two triangles, so no ray slips between them), the
// determinant is non-zero and tmin*det <= T <= tmax*det after the sign of det
// is folded into T. Only then is the reciprocal of det used.
template <class A>
Candidate<A> IntersectWatertight(const A& a, const RaySetup<A>& r, const img::TriangleRecord& tri,
                                 typename A::T tmax) {
  using T = typename A::T;
  Candidate<A> c;
  T p[3][3];  // vertex - origin, per vertex and axis
  const float* v[3] = {tri.v0, tri.v1, tri.v2};
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 3; ++i) p[k][i] = a.Sub(a.Load(v[k][i]), r.o[i]);
  }
  T x[3], y[3], z[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = a.Sub(p[k][r.kx], a.Mul(r.sx, p[k][r.kz]));
    y[k] = a.Sub(p[k][r.ky], a.Mul(r.sy, p[k][r.kz]));
  }
  // Edge functions: e0 is opposite v0, and so on.
  const T e0 = a.Sub(a.Mul(x[2], y[1]), a.Mul(y[2], x[1]));
  const T e1 = a.Sub(a.Mul(x[0], y[2]), a.Mul(y[0], x[2]));
  const T e2 = a.Sub(a.Mul(x[1], y[0]), a.Mul(y[1], x[0]));
  const T zero = a.Zero();
  const bool any_neg = a.Lt(e0, zero) || a.Lt(e1, zero) || a.Lt(e2, zero);
  const bool any_pos = a.Lt(zero, e0) || a.Lt(zero, e1) || a.Lt(zero, e2);
  if (any_neg && any_pos) return c;
  const T det = a.Add(a.Add(e0, e1), e2);
  const bool det_neg = a.Lt(det, zero);
  if (!det_neg && !a.Lt(zero, det)) return c;  // zero or NaN
  for (int k = 0; k < 3; ++k) z[k] = a.Mul(r.sz, p[k][r.kz]);
  T t_scaled = a.Add(a.Add(a.Mul(e0, z[0]), a.Mul(e1, z[1])), a.Mul(e2, z[2]));
  T det_abs = det, e1s = e1, e2s = e2;
  if (det_neg) {
    t_scaled = a.Neg(t_scaled);
    det_abs = a.Neg(det);
    e1s = a.Neg(e1);
    e2s = a.Neg(e2);
  }
  if (!a.Le(a.Mul(r.tmin, det_abs), t_scaled)) return c;
  if (!a.Le(t_scaled, a.Mul(tmax, det_abs))) return c;
  const T rcp = a.Div(a.One(), det_abs);
  c.t = a.Mul(t_scaled, rcp);
  c.u = a.Mul(e1s, rcp);
  c.v = a.Mul(e2s, rcp);
  c.hit = true;
  return c;
}

// Moller & Trumbore 1997, double-sided, for comparison; not watertight.
template <class A>
Candidate<A> IntersectMoller(const A& a, const RaySetup<A>& r, const img::TriangleRecord& tri,
                             typename A::T tmax) {
  using T = typename A::T;
  Candidate<A> c;
  T v0[3], e1[3], e2[3], s[3];
  for (int i = 0; i < 3; ++i) {
    v0[i] = a.Load(tri.v0[i]);
    e1[i] = a.Sub(a.Load(tri.v1[i]), v0[i]);
    e2[i] = a.Sub(a.Load(tri.v2[i]), v0[i]);
    s[i] = a.Sub(r.o[i], v0[i]);
  }
  auto cross = [&](const T* p, const T* q, T* out) {
    out[0] = a.Sub(a.Mul(p[1], q[2]), a.Mul(p[2], q[1]));
    out[1] = a.Sub(a.Mul(p[2], q[0]), a.Mul(p[0], q[2]));
    out[2] = a.Sub(a.Mul(p[0], q[1]), a.Mul(p[1], q[0]));
  };
  auto dot = [&](const T* p, const T* q) { return a.Add(a.Add(a.Mul(p[0], q[0]), a.Mul(p[1], q[1])), a.Mul(p[2], q[2])); };
  T pv[3], qv[3];
  cross(r.d, e2, pv);
  const T det = dot(e1, pv);
  const T zero = a.Zero();
  if (!a.Lt(zero, det) && !a.Lt(det, zero)) return c;
  const T inv = a.Div(a.One(), det);
  const T u = a.Mul(dot(s, pv), inv);
  if (!a.Le(zero, u) || !a.Le(u, a.One())) return c;  // also rejects NaN
  cross(s, e1, qv);
  const T v = a.Mul(dot(r.d, qv), inv);
  if (!a.Le(zero, v) || !a.Le(a.Add(u, v), a.One())) return c;
  const T t = a.Mul(dot(e2, qv), inv);
  if (!a.Le(r.tmin, t) || !a.Le(t, tmax)) return c;
  c.t = t;
  c.u = u;
  c.v = v;
  c.hit = true;
  return c;
}

}  // namespace kdrt
