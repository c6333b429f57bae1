// The fp32 leaf test four triangles at a time: IntersectWatertight
// (trace/intersect.h) on native fp32, lane by lane. Every lane performs the
// same IEEE operations in the same order on the same operands as the scalar
// test, under the same MXCSR (FTZ/DAZ, round to nearest, no contraction:
// -ffp-contract=off), so its t, u, v and hit decision are the scalar test's
// bit for bit; only the branches are gone. tests/trace/leaf_x4_test.cpp checks
// it against the scalar test. GCC vector extensions (__builtin_shuffle is
// GCC's): SSE on x86-64, NEON on AArch64, no intrinsics; other compilers
// keep the scalar loop.
#pragma once

#include <cstdint>
#include <cstring>

#include "common/image_format.h"
#include "fp/format.h"
#include "trace/intersect.h"

namespace kdrt {

#if defined(__GNUC__) && !defined(__clang__)
#define KDRT_HAVE_LEAF_X4 1

namespace leaf_x4 {

typedef float V4f __attribute__((vector_size(16)));
typedef int32_t V4i __attribute__((vector_size(16)));

inline V4f Splat(float x) { return V4f{x, x, x, x}; }
inline V4i Bits(V4f x) { return reinterpret_cast<V4i>(x); }
inline V4f Floats(V4i x) { return reinterpret_cast<V4f>(x); }

// fp::NativeF32Arith::Load per lane: a subnormal becomes a zero of its sign.
inline V4f Load(V4f x) {
  const V4i u = Bits(x);
  const V4i sub = (u & 0x7F800000) == 0;  // -1 where the exponent field is 0
  const V4i keep = ~sub | static_cast<int32_t>(0x80000000u);
  return Floats(u & keep);
}

inline V4f Row(const img::TriangleRecord& t, int k) {
  V4f r;
  std::memcpy(&r, reinterpret_cast<const float*>(&t) + 4 * k, sizeof r);
  return r;
}

// The columns of the 4x4 matrix with rows a, b, c, d.
inline void Transpose(V4f a, V4f b, V4f c, V4f d, V4f out[4]) {
  const V4f ab_lo = __builtin_shuffle(a, b, V4i{0, 4, 1, 5});
  const V4f cd_lo = __builtin_shuffle(c, d, V4i{0, 4, 1, 5});
  const V4f ab_hi = __builtin_shuffle(a, b, V4i{2, 6, 3, 7});
  const V4f cd_hi = __builtin_shuffle(c, d, V4i{2, 6, 3, 7});
  out[0] = __builtin_shuffle(ab_lo, cd_lo, V4i{0, 1, 4, 5});
  out[1] = __builtin_shuffle(ab_lo, cd_lo, V4i{2, 3, 6, 7});
  out[2] = __builtin_shuffle(ab_hi, cd_hi, V4i{0, 1, 4, 5});
  out[3] = __builtin_shuffle(ab_hi, cd_hi, V4i{2, 3, 6, 7});
}

// The test of four triangles (vert[vertex][axis], lane k: triangle k) with
// the ray's axes kx, ky, kz fixed.
template <int KX, int KY, int KZ>
inline unsigned TestX4(const RaySetup<fp::NativeF32Arith>& r, const V4f vert[3][3], uint32_t n, float tmax,
                       float out_t[4], float out_u[4], float out_v[4]) {
  V4f p[3][3];  // vertex - origin, per vertex and axis
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 3; ++i) p[k][i] = leaf_x4::Load(vert[k][i]) - Splat(r.o[i]);
  }
  const V4f sx = Splat(r.sx), sy = Splat(r.sy), sz = Splat(r.sz);
  V4f x[3], y[3], z[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = p[k][KX] - sx * p[k][KZ];
    y[k] = p[k][KY] - sy * p[k][KZ];
  }
  const V4f e0 = x[2] * y[1] - y[2] * x[1];
  const V4f e1 = x[0] * y[2] - y[0] * x[2];
  const V4f e2 = x[1] * y[0] - y[1] * x[0];
  const V4f zero = Splat(0.0f);
  const V4i any_neg = (e0 < zero) | (e1 < zero) | (e2 < zero);
  const V4i any_pos = (zero < e0) | (zero < e1) | (zero < e2);
  const V4f det = (e0 + e1) + e2;
  const V4i det_neg = det < zero;
  V4i hit = ~(any_neg & any_pos) & (det_neg | (zero < det));
  for (int k = 0; k < 3; ++k) z[k] = sz * p[k][KZ];
  // a.Neg is a sign flip: the xor below, NaN and zero included.
  const V4i flip = det_neg & static_cast<int32_t>(0x80000000u);
  const V4f t_scaled =
      leaf_x4::Floats(leaf_x4::Bits(((e0 * z[0]) + (e1 * z[1])) + (e2 * z[2])) ^ flip);
  const V4f det_abs = leaf_x4::Floats(leaf_x4::Bits(det) ^ flip);
  hit &= (Splat(r.tmin) * det_abs <= t_scaled) & (t_scaled <= Splat(tmax) * det_abs);
  unsigned mask = 0;
  for (uint32_t k = 0; k < n; ++k) mask |= (hit[k] != 0 ? 1u : 0u) << k;
  if (mask == 0) return 0;
  const V4f rcp = Splat(1.0f) / det_abs;
  const V4f tt = t_scaled * rcp;
  const V4f uu = leaf_x4::Floats(leaf_x4::Bits(e1) ^ flip) * rcp;
  const V4f vv = leaf_x4::Floats(leaf_x4::Bits(e2) ^ flip) * rcp;
  for (int k = 0; k < 4; ++k) {
    out_t[k] = tt[k];
    out_u[k] = uu[k];
    out_v[k] = vv[k];
  }
  return mask;
}

}  // namespace leaf_x4

// The watertight test of triangles tris[ids[0..n)] (n <= 4) against the ray
// `r`, every one with the leaf's `tmax`. Returns the lanes that hit as bits
// (bit k: ids[k]) and their t, u, v in out_t/out_u/out_v[k]. Must run under
// fp::ScopedFtzDaz, as NativeF32Arith does.
inline unsigned IntersectWatertightX4(const RaySetup<fp::NativeF32Arith>& r, const img::TriangleRecord* tris,
                                      const uint32_t* ids, uint32_t n, float tmax, float out_t[4], float out_u[4],
                                      float out_v[4]) {
  using leaf_x4::V4f;
  using leaf_x4::V4i;
  using leaf_x4::Splat;
  // Lanes past n repeat the last triangle; their results are masked off.
  const img::TriangleRecord* t[4];
  for (uint32_t k = 0; k < 4; ++k) t[k] = &tris[ids[k < n ? k : n - 1]];
  V4f c0[4], c1[4];
  leaf_x4::Transpose(leaf_x4::Row(*t[0], 0), leaf_x4::Row(*t[1], 0), leaf_x4::Row(*t[2], 0),
                     leaf_x4::Row(*t[3], 0), c0);  // v0.x v0.y v0.z v1.x
  leaf_x4::Transpose(leaf_x4::Row(*t[0], 1), leaf_x4::Row(*t[1], 1), leaf_x4::Row(*t[2], 1),
                     leaf_x4::Row(*t[3], 1), c1);  // v1.y v1.z v2.x v2.y
  const V4f v2z{t[0]->v2[2], t[1]->v2[2], t[2]->v2[2], t[3]->v2[2]};
  const V4f vert[3][3] = {{c0[0], c0[1], c0[2]}, {c0[3], c1[0], c1[1]}, {c1[2], c1[3], v2z}};
  // The ray's axis permutation as template arguments: indexed at run time,
  // the per-axis values went through memory.
  switch (r.kz * 3 + r.kx) {
    case 0 * 3 + 1: return leaf_x4::TestX4<1, 2, 0>(r, vert, n, tmax, out_t, out_u, out_v);
    case 0 * 3 + 2: return leaf_x4::TestX4<2, 1, 0>(r, vert, n, tmax, out_t, out_u, out_v);
    case 1 * 3 + 2: return leaf_x4::TestX4<2, 0, 1>(r, vert, n, tmax, out_t, out_u, out_v);
    case 1 * 3 + 0: return leaf_x4::TestX4<0, 2, 1>(r, vert, n, tmax, out_t, out_u, out_v);
    case 2 * 3 + 0: return leaf_x4::TestX4<0, 1, 2>(r, vert, n, tmax, out_t, out_u, out_v);
    default: return leaf_x4::TestX4<1, 0, 2>(r, vert, n, tmax, out_t, out_u, out_v);
  }
}

#else
#define KDRT_HAVE_LEAF_X4 0
#endif

}  // namespace kdrt
