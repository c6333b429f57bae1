#include "trace/packet.h"

#include <cstring>

#include "common/error.h"
#include "trace/tracer.h"
#include "trace/traversal.h"

namespace kdrt {

int ParsePacketWidth(const std::string& text) {
  if (text == "off" || text == "0") return 0;
  if (text == "4") return 4;
  if (text == "8") return 8;
  if (text == "16") return 16;
  throw InputError("--packets '" + text + "': expected off, 4, 8 or 16");
}

const char* PacketFormats() { return "fp32"; }

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define KDRT_HAVE_PACKETS 1
// The vector helpers below are always inlined: no vector crosses a call,
// so the ABI note on wide vector returns does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace {

using A = fp::NativeF32Arith;

template <int W>
struct Vec {
  typedef float F __attribute__((vector_size(4 * W)));
  typedef int32_t I __attribute__((vector_size(4 * W)));
  typedef uint32_t U __attribute__((vector_size(4 * W)));
};

// a + b and a - b on the bits, wrapping: every lane is computed, also those
// a Select() then leaves out (-0.0 or NaN bits, where a signed sum would
// overflow).
template <int W>
KDRT_HOT_INLINE typename Vec<W>::I WrapAdd(typename Vec<W>::I a, typename Vec<W>::I b) {
  using U = typename Vec<W>::U;
  return reinterpret_cast<typename Vec<W>::I>(reinterpret_cast<U>(a) + reinterpret_cast<U>(b));
}

template <int W>
KDRT_HOT_INLINE typename Vec<W>::I WrapSub(typename Vec<W>::I a, typename Vec<W>::I b) {
  using U = typename Vec<W>::U;
  return reinterpret_cast<typename Vec<W>::I>(reinterpret_cast<U>(a) - reinterpret_cast<U>(b));
}

template <int W>
KDRT_HOT_INLINE typename Vec<W>::F SplatF(float x) {
  typename Vec<W>::F v;
  for (int i = 0; i < W; ++i) v[i] = x;
  return v;
}

template <int W>
KDRT_HOT_INLINE typename Vec<W>::I SplatI(int32_t x) {
  typename Vec<W>::I v;
  for (int i = 0; i < W; ++i) v[i] = x;
  return v;
}

typedef float F4 __attribute__((vector_size(16)));

// Bit i: lane i of the mask (-1 or 0) is set. Four lanes at a time (SSE's
// movmskps, in every x86-64 ISA).
template <int W>
KDRT_HOT_INLINE unsigned MoveMask(typename Vec<W>::I m) {
  unsigned bits = 0;
  for (int k = 0; k < W / 4; ++k) {
    F4 part;
    std::memcpy(&part, reinterpret_cast<const char*>(&m) + 16 * k, sizeof part);
    bits |= static_cast<unsigned>(__builtin_ia32_movmskps(part)) << (4 * k);
  }
  return bits;
}

// The lanes of `bits` as a mask vector.
template <int W>
KDRT_HOT_INLINE typename Vec<W>::I MaskOf(unsigned bits) {
  typename Vec<W>::I lane;
  for (int i = 0; i < W; ++i) lane[i] = 1 << i;
  return (SplatI<W>(static_cast<int32_t>(bits)) & lane) != SplatI<W>(0);
}

// Per lane: a where m is set, else b. As and/or on the bits: GCC lowers ?: on
// vectors wider than the ISA's registers lane by lane.
template <class V, class M>
KDRT_HOT_INLINE V Select(M m, V a, V b) {
  return reinterpret_cast<V>((reinterpret_cast<M>(a) & m) | (reinterpret_cast<M>(b) & ~m));
}

// A::NudgeUp and A::NudgeDown by kTraversalSlackUlps, lane by lane.
template <int W>
KDRT_HOT_INLINE typename Vec<W>::F NudgeUpV(typename Vec<W>::F x) {
  using I = typename Vec<W>::I;
  using F = typename Vec<W>::F;
  const F inf = SplatF<W>(A::Inf());
  const I bits = reinterpret_cast<I>(x);
  const I move = (x > SplatF<W>(0.0f)) & (x != inf);
  const I u = WrapAdd<W>(bits, SplatI<W>(static_cast<int32_t>(kTraversalSlackUlps)));
  const I up = Select(u >= SplatI<W>(0x7F800000), reinterpret_cast<I>(inf), u);
  return reinterpret_cast<F>(Select(move, up, bits));
}

template <int W>
KDRT_HOT_INLINE typename Vec<W>::F NudgeDownV(typename Vec<W>::F x) {
  using I = typename Vec<W>::I;
  using F = typename Vec<W>::F;
  const I bits = reinterpret_cast<I>(x);
  const I move = (x > SplatF<W>(0.0f)) & (x != SplatF<W>(A::Inf()));
  const I down = Select(bits < SplatI<W>(static_cast<int32_t>(0x00800000u + kTraversalSlackUlps)), SplatI<W>(0),
                        WrapSub<W>(bits, SplatI<W>(static_cast<int32_t>(kTraversalSlackUlps))));
  return reinterpret_cast<F>(Select(move, down, bits));
}

// The rays' side of a packet's watertight tests, lane by lane (RaySetup's
// fields as vectors).
template <int W>
struct LaneRays {
  typename Vec<W>::F o[3], sx, sy, sz, tmin;
};

// IntersectWatertight (trace/intersect.h) of one leaf's triangles against the
// lanes `lanes`, which share the axis permutation KX, KY, KZ: each lane does
// the scalar test's IEEE operations in the same order on the same operands
// (as trace/leaf_x4.h does across triangles), with the leaf's tmax its own
// best t on entry, and keeps the closest candidate by the scalar rule.
template <int W, int KX, int KY, int KZ>
KDRT_HOT_INLINE void LeafTestW(const LaneRays<W>& r, const img::TriangleRecord* tris, const uint32_t* ids,
                               uint32_t count, typename Vec<W>::I lanes, typename Vec<W>::F* best_t,
                               typename Vec<W>::F* best_u, typename Vec<W>::F* best_v, typename Vec<W>::I* best_prim) {
  using F = typename Vec<W>::F;
  using I = typename Vec<W>::I;
  const F zero = SplatF<W>(0.0f);
  const F tmax = *best_t;
  const I sign = SplatI<W>(static_cast<int32_t>(0x80000000u));
  for (uint32_t k = 0; k < count; ++k) {
    const uint32_t id = ids[k];
    const img::TriangleRecord& tri = tris[id];
    const float* v[3] = {tri.v0, tri.v1, tri.v2};
    F p[3][3];
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) p[j][i] = SplatF<W>(A::Load(v[j][i])) - r.o[i];
    }
    F x[3], y[3], z[3];
    for (int j = 0; j < 3; ++j) {
      x[j] = p[j][KX] - r.sx * p[j][KZ];
      y[j] = p[j][KY] - r.sy * p[j][KZ];
    }
    const F e0 = x[2] * y[1] - y[2] * x[1];
    const F e1 = x[0] * y[2] - y[0] * x[2];
    const F e2 = x[1] * y[0] - y[1] * x[0];
    const I any_neg = (e0 < zero) | (e1 < zero) | (e2 < zero);
    const I any_pos = (zero < e0) | (zero < e1) | (zero < e2);
    const F det = (e0 + e1) + e2;
    const I det_neg = det < zero;
    I hit = lanes & ~(any_neg & any_pos) & (det_neg | (zero < det));
    if (MoveMask<W>(hit) == 0) continue;
    for (int j = 0; j < 3; ++j) z[j] = r.sz * p[j][KZ];
    const I flip = det_neg & sign;
    const F t_scaled = reinterpret_cast<F>(reinterpret_cast<I>(((e0 * z[0]) + (e1 * z[1])) + (e2 * z[2])) ^ flip);
    const F det_abs = reinterpret_cast<F>(reinterpret_cast<I>(det) ^ flip);
    hit &= (r.tmin * det_abs <= t_scaled) & (t_scaled <= tmax * det_abs);
    if (MoveMask<W>(hit) == 0) continue;
    const F rcp = SplatF<W>(1.0f) / det_abs;
    const F t = t_scaled * rcp;
    const F u = reinterpret_cast<F>(reinterpret_cast<I>(e1) ^ flip) * rcp;
    const F vv = reinterpret_cast<F>(reinterpret_cast<I>(e2) ^ flip) * rcp;
    // id < prim as unsigned numbers (kNoPrim is the largest).
    const I idv = SplatI<W>(static_cast<int32_t>(id ^ 0x80000000u));
    const I better = hit & ((t < *best_t) | ((t == *best_t) & (idv < (*best_prim ^ sign))));
    *best_t = Select(better, t, *best_t);
    *best_u = Select(better, u, *best_u);
    *best_v = Select(better, vv, *best_v);
    *best_prim = Select(better, SplatI<W>(static_cast<int32_t>(id)), *best_prim);
  }
}

// TraceRayIn<false> (trace/traversal.h) for up to W rays at once on native
// fp32. Lane l follows its own scalar walk: the packet is at a node, and the
// lanes active there are those whose walk is at that node; a lane whose walk
// goes on elsewhere waits in a packet stack entry (its real pushes, and the
// child it alone goes to when the others go first to the other child) or has
// ended. Sets fallback bit l when lane l left the packet (its results here
// are then not written).
template <int W>
KDRT_HOT_INLINE unsigned PacketWalk(const ImageView& image, const Ray* rays, int n, IsectMethod isect, Query query,
                                    int stack_limit, Hit* hits, RayCounters* counters, uint64_t* fetches) {
  using F = typename Vec<W>::F;
  using I = typename Vec<W>::I;
  const A a;
  const img::Header& h = image.header();
  RaySetup<A> r[W];
  TraceResult<A> best[W];
  RayCounters walked[W];
  int sp[W], in_plane[W];
  float o[3][W], d[3][W], inv_d[3][W], t0s[W], t1s[W];
  unsigned alive = 0;
  for (int l = 0; l < W; ++l) {
    const int k = l < n ? l : 0;  // lanes past n repeat ray 0, never active
    const FramedRay framed = ToFrameFtz(rays[k], image.frame());
    r[l] = SetupRay(a, framed.ray);
    best[l] = TraceResult<A>{};
    best[l].t_scale_log2 = framed.t_scale_log2;
    best[l].t = r[l].tmax;
    best[l].u = best[l].v = a.Zero();
    const BoxClip<A> clip = ClipToBox(a, r[l], h.bounds_min, h.bounds_max);
    for (int i = 0; i < 3; ++i) {
      o[i][l] = r[l].o[i];
      d[i][l] = r[l].d[i];
      inv_d[i][l] = r[l].inv_d[i];
    }
    t0s[l] = clip.t0;
    t1s[l] = clip.t1;
    sp[l] = in_plane[l] = 0;
    if (l >= n) continue;
    if (clip.miss) {
      hits[l] = ToHit(a, best[l]);  // counted nothing, as the scalar walk
    } else {
      alive |= 1u << l;
    }
  }
  LaneRays<W> lr;
  int perm[W];
  {
    float sx[W], sy[W], sz[W], tmin[W];
    for (int l = 0; l < W; ++l) {
      sx[l] = r[l].sx;
      sy[l] = r[l].sy;
      sz[l] = r[l].sz;
      tmin[l] = r[l].tmin;
      perm[l] = r[l].kz * 3 + r[l].kx;
    }
    std::memcpy(&lr.sx, sx, sizeof(F));
    std::memcpy(&lr.sy, sy, sizeof(F));
    std::memcpy(&lr.sz, sz, sizeof(F));
    std::memcpy(&lr.tmin, tmin, sizeof(F));
    for (int i = 0; i < 3; ++i) std::memcpy(&lr.o[i], o[i], sizeof(F));
  }
  F vo[3], vd[3], vinv[3], t0, t1;
  for (int i = 0; i < 3; ++i) {
    std::memcpy(&vo[i], o[i], sizeof(F));
    std::memcpy(&vd[i], d[i], sizeof(F));
    std::memcpy(&vinv[i], inv_d[i], sizeof(F));
  }
  std::memcpy(&t0, t0s, sizeof(F));
  std::memcpy(&t1, t1s, sizeof(F));
  const F zero = SplatF<W>(0.0f);
  I nodes = SplatI<W>(0);
  uint64_t fetched = 0;  // a local: GCC keeps a counter behind a pointer in memory
  unsigned fallback = 0;

  const auto finish = [&](int l) __attribute__((always_inline)) {
    walked[l].nodes = static_cast<uint32_t>(nodes[l]);
    counters[l] += walked[l];
    hits[l] = ToHit(a, best[l]);
    alive &= ~(1u << l);
  };

  struct Entry {
    uint32_t node;
    unsigned lanes;   // lanes that go on at `node`
    unsigned pushed;  // of those, the ones whose own walk pushed it
    F t0, t1;
  };
  Entry stack[kMaxTraversalStack];
  int top = 0;
  const uint32_t* lists = image.lists();
  const img::Node* raw_nodes = image.raw_nodes();
  const img::TriangleRecord* raw_tris = image.raw_triangles();
  const bool four_wide = KDRT_HAVE_LEAF_X4 && isect == IsectMethod::kWatertight && raw_tris != nullptr;

  unsigned active = alive;
  I act = MaskOf<W>(active);
  uint32_t node = 0;
  for (;;) {
    if (active == 0) {
      // Every lane here is done or waits in the stack: the top entry's
      // lanes go on. Its pushed lanes pop it as their own walk does.
      if (top == 0) break;
      const Entry& e = stack[--top];
      unsigned pushed = e.pushed & alive;
      active = e.lanes & ~e.pushed & alive;
      if (pushed != 0) {
        float e_t0[W];
        std::memcpy(e_t0, &e.t0, sizeof(F));
        for (unsigned m = pushed; m != 0; m &= m - 1) {
          const int l = __builtin_ctz(m);
          --sp[l];
          const bool may_stop = best[l].prim != kNoPrim && in_plane[l] == 0;
          if (may_stop && a.Lt(best[l].t, e_t0[l])) {
            finish(l);
            continue;
          }
          if (InPlane(a, e_t0[l])) --in_plane[l];
          active |= 1u << l;
        }
      }
      node = e.node;
      t0 = e.t0;
      t1 = e.t1;
      act = MaskOf<W>(active);
      continue;
    }
    const img::Node nd = raw_nodes[node];
    // An empty leaf other than the root is not fetched (TraceRayIn).
    const bool counted = !(nd.IsLeaf() && nd.Count() == 0 && node != 0);
    if (counted) nodes -= act;
    ++fetched;
    if (!nd.IsLeaf()) {
      const int axis = nd.Axis();
      const F split = SplatF<W>(A::Load(nd.Split()));
      const F oa = vo[axis];
      const F ts = (split - oa) * vinv[axis];
      const F t_lo = NudgeDownV<W>(ts);
      const F t_hi = NudgeUpV<W>(ts);
      const I below_first = (oa < split) | ((oa == split) & (vd[axis] <= zero));
      const I first_only = (t1 < t_lo) | (ts <= zero);
      const I second_only = ~first_only & (t_hi < t0);
      I push = ~(first_only | second_only) & act;
      I go_below = act & ((below_first & first_only) | (~below_first & second_only) | push);
      I go_above = act & ((~below_first & first_only) | (below_first & second_only) | push);
      const unsigned push_below = MoveMask<W>(push & below_first);
      const unsigned push_above = MoveMask<W>(push & ~below_first);
      // The packet goes first where its pushing lanes go first; a lane that
      // would push the other way round leaves it.
      const bool below_order = push_above == 0 || (push_below != 0 && __builtin_popcount(push_below) >=
                                                                           __builtin_popcount(push_above));
      unsigned pushed = push_below | push_above;
      unsigned leave = below_order ? push_above : push_below;
      if (pushed != 0) {
        // Their own pushes: the stack limit (a push onto a full stack ends
        // the ray) and the in-plane count.
        float lo[W];
        std::memcpy(lo, &t_lo, sizeof(F));
        for (unsigned m = pushed & ~leave; m != 0; m &= m - 1) {
          const int l = __builtin_ctz(m);
          if (sp[l] >= stack_limit) {
            ++walked[l].overflows;
            finish(l);
            leave |= 1u << l;
            continue;
          }
          ++sp[l];
          if (InPlane(a, lo[l])) ++in_plane[l];
        }
        if (leave != 0) {
          fallback |= leave & alive;
          alive &= ~leave;
          pushed &= ~leave;
          const I gone = MaskOf<W>(leave);
          push &= ~gone;
          go_below &= ~gone;
          go_above &= ~gone;
        }
      }
      const uint32_t below = node + 1;
      const uint32_t above = nd.AboveChild();
      const uint32_t near = below_order ? below : above;
      const uint32_t far = below_order ? above : below;
      const I near_lanes = below_order ? go_below : go_above;
      const I far_lanes = below_order ? go_above : go_below;
      const unsigned near_bits = MoveMask<W>(near_lanes);
      const unsigned far_bits = MoveMask<W>(far_lanes);
      if (near_bits == 0) {
        node = far;
        active = far_bits;
        act = far_lanes;
      } else {
        if (far_bits != 0) {
          stack[top++] = Entry{far, far_bits, pushed, Select(push, t_lo, t0), t1};
          t1 = Select(push, t_hi, t1);
        }
        node = near;
        active = near_bits;
        act = near_lanes;
      }
      continue;
    }
    // A leaf: each active lane tests its triangles as the scalar walk does,
    // then ends or waits for the stack entry its walk pops next.
    const uint32_t count = nd.Count();
    const uint32_t* ids = lists + nd.FirstEntry();
    float t1_lane[W];
    std::memcpy(t1_lane, &t1, sizeof(F));
    // The lanes that share the first active lane's axis permutation test
    // the leaf's triangles together, one triangle for all of them at a time.
    unsigned together = 0;
    if (raw_tris != nullptr && isect == IsectMethod::kWatertight && (active & (active - 1)) != 0) {
      const int code = perm[__builtin_ctz(active)];
      for (unsigned m = active; m != 0; m &= m - 1) {
        if (perm[__builtin_ctz(m)] == code) together |= m & -m;
      }
      if ((together & (together - 1)) == 0) {
        together = 0;
      } else {
        float bt[W], bu[W], bv[W];
        int32_t bp[W];
        for (int l = 0; l < W; ++l) {
          bt[l] = best[l].t;
          bu[l] = best[l].u;
          bv[l] = best[l].v;
          bp[l] = static_cast<int32_t>(best[l].prim);
        }
        F vt, vu, vv;
        I vp;
        std::memcpy(&vt, bt, sizeof(F));
        std::memcpy(&vu, bu, sizeof(F));
        std::memcpy(&vv, bv, sizeof(F));
        std::memcpy(&vp, bp, sizeof(F));
        const I lanes = MaskOf<W>(together);
        switch (code) {
          case 0 * 3 + 1: LeafTestW<W, 1, 2, 0>(lr, raw_tris, ids, count, lanes, &vt, &vu, &vv, &vp); break;
          case 0 * 3 + 2: LeafTestW<W, 2, 1, 0>(lr, raw_tris, ids, count, lanes, &vt, &vu, &vv, &vp); break;
          case 1 * 3 + 2: LeafTestW<W, 2, 0, 1>(lr, raw_tris, ids, count, lanes, &vt, &vu, &vv, &vp); break;
          case 1 * 3 + 0: LeafTestW<W, 0, 2, 1>(lr, raw_tris, ids, count, lanes, &vt, &vu, &vv, &vp); break;
          case 2 * 3 + 0: LeafTestW<W, 0, 1, 2>(lr, raw_tris, ids, count, lanes, &vt, &vu, &vv, &vp); break;
          default: LeafTestW<W, 1, 0, 2>(lr, raw_tris, ids, count, lanes, &vt, &vu, &vv, &vp); break;
        }
        std::memcpy(bt, &vt, sizeof(F));
        std::memcpy(bu, &vu, sizeof(F));
        std::memcpy(bv, &vv, sizeof(F));
        std::memcpy(bp, &vp, sizeof(F));
        for (unsigned m = together; m != 0; m &= m - 1) {
          const int l = __builtin_ctz(m);
          best[l].t = bt[l];
          best[l].u = bu[l];
          best[l].v = bv[l];
          best[l].prim = static_cast<uint32_t>(bp[l]);
        }
      }
    }
    for (unsigned m = active; m != 0; m &= m - 1) {
      const int l = __builtin_ctz(m);
      TraceResult<A>& b = best[l];
      const auto offer = [&b](float t, float u, float v, uint32_t id) {
        if (t < b.t || (t == b.t && id < b.prim)) {
          b.t = t;
          b.u = u;
          b.v = v;
          b.prim = id;
        }
      };
      walked[l].leaves += counted;
      walked[l].empty_skipped += !counted;
      walked[l].tri_tests += count;
      const float leaf_tmax = b.t;
      if ((together >> l) & 1) {
        // tested above
      } else if (four_wide && count > 1) {
#if KDRT_HAVE_LEAF_X4
        for (uint32_t k = 0; k < count; k += 4) {
          float ct[4], cu[4], cv[4];
          const uint32_t group = count - k < 4 ? count - k : 4;
          for (unsigned hm = IntersectWatertightX4(r[l], raw_tris, ids + k, group, leaf_tmax, ct, cu, cv); hm != 0;
               hm &= hm - 1) {
            const int lane = __builtin_ctz(hm);
            offer(ct[lane], cu[lane], cv[lane], ids[k + lane]);
          }
        }
#endif
      } else {
        for (uint32_t k = 0; k < count; ++k) {
          const uint32_t id = ids[k];
          const Candidate<A> c = isect == IsectMethod::kWatertight
                                     ? IntersectWatertight(a, r[l], image.triangle(id), leaf_tmax)
                                     : IntersectMoller(a, r[l], image.triangle(id), leaf_tmax);
          if (c.hit) offer(c.t, c.u, c.v, id);
        }
      }
      const bool may_stop = b.prim != kNoPrim && in_plane[l] == 0;
      if ((b.prim != kNoPrim && query == Query::kAny) || (may_stop && a.Le(b.t, t1_lane[l])) || sp[l] == 0) {
        finish(l);
      }
    }
    active = 0;
    act = SplatI<W>(0);
  }
  // Every lane ends at a leaf or when its last stack entry pops.
  for (unsigned m = alive; m != 0; m &= m - 1) finish(__builtin_ctz(m));
  *fetches += fetched;
  return fallback;
}

unsigned Walk4(const ImageView& image, const Ray* rays, int n, IsectMethod isect, Query query, int stack_limit,
               Hit* hits, RayCounters* counters, uint64_t* fetches) {
  return PacketWalk<4>(image, rays, n, isect, query, stack_limit, hits, counters, fetches);
}

__attribute__((target("avx2"))) unsigned Walk8(const ImageView& image, const Ray* rays, int n, IsectMethod isect,
                                                Query query, int stack_limit, Hit* hits, RayCounters* counters, uint64_t* fetches) {
  return PacketWalk<8>(image, rays, n, isect, query, stack_limit, hits, counters, fetches);
}

__attribute__((target("avx2"))) unsigned Walk16(const ImageView& image, const Ray* rays, int n, IsectMethod isect,
                                                 Query query, int stack_limit, Hit* hits, RayCounters* counters, uint64_t* fetches) {
  return PacketWalk<16>(image, rays, n, isect, query, stack_limit, hits, counters, fetches);
}

// Without AVX2: 8 and 16 lanes on SSE2 registers, two or four at a time.
unsigned Walk8Sse(const ImageView& image, const Ray* rays, int n, IsectMethod isect, Query query, int stack_limit,
                  Hit* hits, RayCounters* counters, uint64_t* fetches) {
  return PacketWalk<8>(image, rays, n, isect, query, stack_limit, hits, counters, fetches);
}

unsigned Walk16Sse(const ImageView& image, const Ray* rays, int n, IsectMethod isect, Query query, int stack_limit,
                   Hit* hits, RayCounters* counters, uint64_t* fetches) {
  return PacketWalk<16>(image, rays, n, isect, query, stack_limit, hits, counters, fetches);
}

bool HaveAvx2() {
  static const bool have = __builtin_cpu_supports("avx2");
  return have;
}

}  // namespace

#else
#define KDRT_HAVE_PACKETS 0
#endif

PacketPlan PlanPackets(const ImageView& image, const TraceOptions& options) {
  PacketPlan p;
  if (options.packets == 0) return p;
  const fp::Format trav = TravFormat(options);
  if (!options.format.IsFp32() || !trav.IsFp32()) {
    p.why_scalar = "format " + options.format.Name() + (trav == options.format ? "" : " (traversal " + trav.Name() + ")") +
                   " runs one ray at a time (packed: " + PacketFormats() + ")";
    return p;
  }
  if (image.raw_nodes() == nullptr) {
    p.why_scalar = "an image in a narrower format runs one ray at a time (packed: an fp32 image)";
    return p;
  }
#if KDRT_HAVE_PACKETS
  p.width = options.packets;
  p.isa = p.width == 4 || !HaveAvx2() ? "sse2" : "avx2";
#else
  p.why_scalar = "this build has no packet path (GCC on x86-64 only)";
#endif
  return p;
}

void TracePacket(const PacketPlan& plan, const ImageView& image, const Ray* rays, int n, const TraceOptions& options,
                 Hit* hits, RayCounters* counters, PacketCounts* counts) {
  [[maybe_unused]] uint64_t* const fetches = &counts->node_fetches;
  const int stack_limit = options.stack_depth > 0 ? options.stack_depth : kMaxTraversalStack;
  unsigned fallback = 0;
#if KDRT_HAVE_PACKETS
  const bool avx2 = plan.isa[0] == 'a';
  switch (plan.width) {
    case 4:
      fallback = Walk4(image, rays, n, options.isect, options.query, stack_limit, hits, counters, fetches);
      break;
    case 8:
      fallback = avx2 ? Walk8(image, rays, n, options.isect, options.query, stack_limit, hits, counters, fetches)
                      : Walk8Sse(image, rays, n, options.isect, options.query, stack_limit, hits, counters, fetches);
      break;
    default:
      fallback = avx2 ? Walk16(image, rays, n, options.isect, options.query, stack_limit, hits, counters, fetches)
                      : Walk16Sse(image, rays, n, options.isect, options.query, stack_limit, hits, counters, fetches);
      break;
  }
#else
  fallback = n >= 32 ? ~0u : (1u << n) - 1;
#endif
  const fp::NativeF32Arith a;
  for (unsigned m = fallback; m != 0; m &= m - 1) {
    const int l = __builtin_ctz(m);
    hits[l] = ToHit(a, TraceRayIn<false>(a, a, image, rays[l], options.isect, options.query, &counters[l], nullptr,
                                         stack_limit));
    ++counts->scalar_rays;
  }
}

}  // namespace kdrt
