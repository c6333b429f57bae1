// One uniform grid level, shared by the uniform grid (grid.cpp: one level)
// and the hierarchical grid (hgrid.cpp: a top level and nested sub-grids):
// the resolution rule, the cell planes, the binning of triangles into cell
// lists and the 3D-DDA walk (Amanatides & Woo 1987).
//
// Exactness (structure.h) rests on two choices:
//  - every cell boundary is an fp32 plane, and the walk computes the ray's
//    crossing of plane k as (plane_k - o) * inv_d, the kd-tree's formula,
//    from the plane itself (never by accumulating steps). Each axis' crossing
//    times are then monotone in k, and the cell the walk is in at parameter t
//    is exactly the one those computed times bracket: the walk cannot skip a
//    cell, and it departs from the exact path only where a computed crossing
//    time differs from the exact one (a few ulps of t);
//  - a triangle is binned into every cell it overlaps widened by a margin
//    (kMarginScale of the scene's coordinate range), far larger than those
//    few ulps of t and than the watertight test's own tolerance. So a point
//    the exact ray reaches near a hit lies within the margin of the cell the
//    walk holds at that t, and the triangle is in that cell's list.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "common/error.h"
#include "structures/structure.h"
#include "structures/tri_box.h"

namespace kdrt::grid {

// Keeps the cell offsets of one level below 256 MB.
inline constexpr uint64_t kMaxCellsPerLevel = uint64_t{1} << 26;

// Margin of the binning, relative to the largest coordinate magnitude of the
// scene box: 2^-12 in the frame (coordinates up to 16), i.e. 128 fp32 ulps
// at the frame's edge. The rounding it must cover grows with the distance
// from the ray's origin (a few ulps of it): measured against brute force on
// rays aimed at vertices, fp32 hits are exact from up to 30 scene sizes away
// (from 100 to 10^4 sizes, a few rays in 10^4 keep another triangle at the
// same t). fp64 needs far less.
inline constexpr double kMarginScale = 1.0 / 65536.0;

inline double BinningMargin(const accel::Box& bounds) {
  double scale = 0;
  for (int a = 0; a < 3; ++a) {
    scale = std::max(scale, std::max(std::fabs(double(bounds.lo[a])), std::fabs(double(bounds.hi[a]))));
  }
  if (!(scale > 0) || !std::isfinite(scale)) scale = 1;  // empty or one-point scene: any margin will do
  return scale * kMarginScale;
}

// A box is usable for a grid when it is finite and not inverted (an empty
// scene's box may be neither).
inline bool ValidBox(const accel::Box& b) {
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a]) || !(b.lo[a] <= b.hi[a])) return false;
  }
  return true;
}

struct Resolution {
  int n[3] = {1, 1, 1};
  bool clamped = false;  // the cell budget bound the density rule
  uint64_t cells() const { return uint64_t(n[0]) * uint64_t(n[1]) * uint64_t(n[2]); }
};

// The lecture's n^3 = d |O| with cells as close to cubes as possible: the
// cells per unit length s solves prod_i max(1, extent_i s) = d |O|, so an
// axis thinner than a cell (a flat or nearly flat scene) gets one cell and
// the others share the budget. Then n_i = max(1, round(extent_i s)); if that
// exceeds max_cells, s shrinks until it fits.
inline Resolution ChooseResolution(const double extent[3], size_t count, double density, uint64_t max_cells) {
  Resolution res;
  const double target = density * double(count);
  if (!(target > 1)) return res;
  bool thin[3];
  for (int a = 0; a < 3; ++a) thin[a] = !(extent[a] > 0);
  double s = 0;
  for (;;) {
    int free_axes = 0;
    double volume = 1;
    for (int a = 0; a < 3; ++a) {
      if (thin[a]) continue;
      ++free_axes;
      volume *= extent[a];
    }
    if (free_axes == 0) return res;
    s = std::pow(target / volume, 1.0 / free_axes);
    int thinnest = -1;
    for (int a = 0; a < 3; ++a) {
      if (!thin[a] && extent[a] * s < 1 && (thinnest < 0 || extent[a] < extent[thinnest])) thinnest = a;
    }
    if (thinnest < 0) break;
    thin[thinnest] = true;
  }
  auto fill = [&](double scale) {
    for (int a = 0; a < 3; ++a) {
      const double n = thin[a] ? 1.0 : std::round(extent[a] * scale);
      res.n[a] = int(std::clamp(n, 1.0, double(max_cells)));
    }
  };
  fill(s);
  if (res.cells() > max_cells) {
    res.clamped = true;
    s *= std::cbrt(double(max_cells) / double(res.cells()));
    for (fill(s); res.cells() > max_cells; fill(s)) s *= 0.99;
  }
  return res;
}

// One uniform grid: n[a] cells along axis a between n[a] + 1 strictly
// increasing fp32 planes (held by the caller's plane array), its cells
// numbered x fastest from first_cell on.
struct Level {
  int n[3] = {1, 1, 1};
  uint32_t plane_offset[3] = {0, 0, 0};
  uint32_t first_cell = 0;
  uint32_t stride[3] = {1, 1, 1};
  double lo[3] = {0, 0, 0};         // for the walk's first guess of a cell index
  double inv_width[3] = {0, 0, 0};  // n / extent (0 when flat)
  uint32_t cells() const { return uint32_t(n[0]) * uint32_t(n[1]) * uint32_t(n[2]); }
};

// n + 1 planes from lo to hi, the ends exact. Planes that rounding to fp32
// would merge (a cell narrower than a few ulps) halve the resolution until
// they are strictly increasing; returns the n used.
inline int AppendAxisPlanes(float lo, float hi, int n, std::vector<float>* planes) {
  std::vector<float> p;
  for (;; n = std::max(1, n / 2)) {
    p.assign(size_t(n) + 1, lo);
    p[size_t(n)] = hi;
    bool increasing = n == 1 || lo < hi;
    for (int k = 1; k < n && increasing; ++k) {
      p[size_t(k)] = float(double(lo) + (double(hi) - double(lo)) * k / n);
      increasing = p[size_t(k - 1)] < p[size_t(k)];
    }
    if (increasing && (n == 1 || p[size_t(n - 1)] < hi)) break;
  }
  planes->insert(planes->end(), p.begin(), p.end());
  return n;
}

// A level over [lo, hi] with the given resolution (reduced where fp32 cannot
// hold the planes apart), its planes appended to `planes`.
inline Level MakeLevel(const float lo[3], const float hi[3], const Resolution& res, uint32_t first_cell,
                       std::vector<float>* planes) {
  Level g;
  g.first_cell = first_cell;
  for (int a = 0; a < 3; ++a) {
    g.plane_offset[a] = uint32_t(planes->size());
    g.n[a] = AppendAxisPlanes(lo[a], hi[a], res.n[a], planes);
    g.lo[a] = lo[a];
    const double extent = double(hi[a]) - double(lo[a]);
    g.inv_width[a] = extent > 0 ? g.n[a] / extent : 0.0;
  }
  g.stride[0] = 1;
  g.stride[1] = uint32_t(g.n[0]);
  g.stride[2] = uint32_t(g.n[0]) * uint32_t(g.n[1]);
  return g;
}

// The density rule over a box of fp32 bounds.
inline Resolution ResolutionForBox(const float lo[3], const float hi[3], size_t count, double density) {
  const double extent[3] = {double(hi[0]) - lo[0], double(hi[1]) - lo[1], double(hi[2]) - lo[2]};
  return ChooseResolution(extent, count, density, kMaxCellsPerLevel);
}

// ---------------------------------------------------------------------------
// Binning.

// Calls fn(local cell index) for every cell of `g` that the triangle meets,
// each cell widened by `margin` on every side.
template <class Fn>
void ForEachOverlappedCell(const Level& g, const float* planes, const img::TriangleRecord& tri,
                           const accel::Box& box, double margin, Fn&& fn) {
  int first[3], last[3];
  for (int a = 0; a < 3; ++a) {
    // Cell k spans [p[k], p[k+1]]; it is a candidate when that, widened,
    // meets the triangle's box. Only the interior planes p[1..n-1] decide.
    const float* p = planes + g.plane_offset[a];
    const int n = g.n[a];
    first[a] = int(std::lower_bound(p + 1, p + n, double(box.lo[a]) - margin,
                                    [](float q, double x) { return double(q) < x; }) -
                   (p + 1));
    last[a] = int(std::upper_bound(p + 1, p + n, double(box.hi[a]) + margin,
                                   [](double x, float q) { return x < double(q); }) -
                  (p + 1));
    if (first[a] > last[a]) return;
  }
  // A triangle whose candidates are one cell meets that cell: it meets the
  // widened union of the candidates (it lies in the grid, or for a sub-grid
  // it met the widened parent cell, which is that union).
  if (first[0] == last[0] && first[1] == last[1] && first[2] == last[2]) {
    fn(uint32_t(first[0]) * g.stride[0] + uint32_t(first[1]) * g.stride[1] + uint32_t(first[2]) * g.stride[2]);
    return;
  }
  // Many candidates (a triangle large against the cells): a slab or row
  // the triangle misses is skipped whole, so the cost follows the cells the
  // triangle meets rather than its box.
  const TriangleBoxTest test(tri);
  const float* px = planes + g.plane_offset[0];
  const float* py = planes + g.plane_offset[1];
  const float* pz = planes + g.plane_offset[2];
  const bool prune_slabs = first[0] != last[0] || first[1] != last[1];
  const bool prune_rows = first[0] != last[0];
  double lo[3], hi[3];
  for (int z = first[2]; z <= last[2]; ++z) {
    lo[2] = double(pz[z]) - margin;
    hi[2] = double(pz[z + 1]) + margin;
    if (prune_slabs) {
      lo[0] = double(px[first[0]]) - margin;
      hi[0] = double(px[last[0] + 1]) + margin;
      lo[1] = double(py[first[1]]) - margin;
      hi[1] = double(py[last[1] + 1]) + margin;
      if (!test.Overlaps(lo, hi)) continue;
    }
    for (int y = first[1]; y <= last[1]; ++y) {
      lo[1] = double(py[y]) - margin;
      hi[1] = double(py[y + 1]) + margin;
      if (prune_rows) {
        lo[0] = double(px[first[0]]) - margin;
        hi[0] = double(px[last[0] + 1]) + margin;
        if (!test.Overlaps(lo, hi)) continue;
      }
      for (int x = first[0]; x <= last[0]; ++x) {
        lo[0] = double(px[x]) - margin;
        hi[0] = double(px[x + 1]) + margin;
        if (test.Overlaps(lo, hi)) fn(uint32_t(x) + uint32_t(y) * g.stride[1] + uint32_t(z) * g.stride[2]);
      }
    }
  }
}

// Triangle lists of one level, flat: cell c (local index) holds
// refs[begin[c] .. begin[c+1]), ids ascending.
struct CellLists {
  std::vector<uint32_t> begin;
  std::vector<uint32_t> refs;
  uint32_t size(uint32_t cell) const { return begin[cell + 1] - begin[cell]; }
};

// Bins ids[0..count) (ascending) into the cells of `g`. The count pass
// runs the overlap tests and keeps each triangle's cells (4 bytes a
// reference, freed on return); the fill pass writes each list from its end,
// triangles in descending order, which leaves every offset at its list's
// start and the lists ascending without a second offset array. Gives up
// (returns false) as soon as the references would exceed max_refs.
inline bool BinTriangles(const Level& g, const float* planes, const StructureInput& in, const uint32_t* ids,
                         size_t count, double margin, uint64_t max_refs, CellLists* out) {
  CellLists& lists = *out;
  const uint32_t cells = g.cells();
  lists.begin.assign(size_t(cells) + 1, 0);
  lists.refs.clear();
  max_refs = std::min<uint64_t>(max_refs, std::numeric_limits<uint32_t>::max());
  std::vector<uint32_t> overlapped;  // the cells of triangle i: [first[i], first[i+1])
  std::vector<size_t> first(count + 1, 0);
  overlapped.reserve(std::min<uint64_t>(max_refs, count + count / 2));
  for (size_t i = 0; i < count; ++i) {
    first[i] = overlapped.size();
    const uint32_t id = ids[i];
    ForEachOverlappedCell(g, planes, in.triangles[id], in.boxes[id], margin, [&](uint32_t cell) {
      ++lists.begin[cell];
      overlapped.push_back(cell);
    });
    if (overlapped.size() > max_refs) return false;
  }
  first[count] = overlapped.size();
  uint32_t total = 0;
  for (uint32_t c = 0; c < cells; ++c) {
    total += lists.begin[c];
    lists.begin[c] = total;  // the end of cell c's list, for now
  }
  lists.begin[cells] = total;
  lists.refs.resize(total);
  for (size_t i = count; i-- > 0;) {
    for (size_t k = first[i]; k < first[i + 1]; ++k) lists.refs[--lists.begin[overlapped[k]]] = ids[i];
  }
  return true;
}

// The same without a budget: InputError past 2^32 references.
inline CellLists BinAll(const Level& g, const float* planes, const StructureInput& in, const uint32_t* ids,
                        size_t count, double margin) {
  CellLists lists;
  if (!BinTriangles(g, planes, in, ids, count, margin, std::numeric_limits<uint64_t>::max(), &lists)) {
    throw InputError("grid: more than 2^32 triangle references; lower --grid-density");
  }
  return lists;
}

// ---------------------------------------------------------------------------
// Traversal.

// The cell index along one axis whose computed crossing times bracket t
// (clamped into the grid). For a ray parallel to the axis' planes, the cell
// holding the origin's coordinate instead.
template <class A>
struct AxisStart {
  int index;
  int step;                // +1, -1, or 0 for a ray parallel to the planes
  typename A::T t_next;    // where the ray leaves the cell along this axis
};

template <class A>
inline typename A::T PlaneT(const A& a, const RaySetup<A>& r, int axis, float plane) {
  return a.Mul(a.Sub(a.Load(plane), r.o[axis]), r.inv_d[axis]);
}

template <class A>
AxisStart<A> StartOnAxis(const A& a, const RaySetup<A>& r, const Level& g, const float* p, int axis,
                         typename A::T t) {
  const int n = g.n[axis];
  const bool parallel = a.Eq(r.d[axis], a.Zero());
  // A first guess from the point at t (in double, only a guess); the
  // comparisons below decide.
  const double o = double(a.Store(r.o[axis]));
  const double pos = parallel ? o : o + double(a.Store(t)) * double(a.Store(r.d[axis]));
  const double x = (pos - g.lo[axis]) * g.inv_width[axis];
  int k = x >= 1 ? (x < n ? int(x) : n - 1) : 0;
  if (parallel) {
    while (k > 0 && a.Lt(r.o[axis], a.Load(p[k]))) --k;
    while (k < n - 1 && a.Le(a.Load(p[k + 1]), r.o[axis])) ++k;
    return AxisStart<A>{k, 0, a.Inf()};
  }
  if (!a.IsNeg(r.inv_d[axis])) {  // cell k spans [t(p[k]), t(p[k+1]))
    while (k > 0 && a.Lt(t, PlaneT(a, r, axis, p[k]))) --k;
    while (k < n - 1 && a.Le(PlaneT(a, r, axis, p[k + 1]), t)) ++k;
    return AxisStart<A>{k, 1, PlaneT(a, r, axis, p[k + 1])};
  }
  // cell k spans [t(p[k+1]), t(p[k]))
  while (k < n - 1 && a.Lt(t, PlaneT(a, r, axis, p[k + 1]))) ++k;
  while (k > 0 && a.Le(PlaneT(a, r, axis, p[k]), t)) --k;
  return AxisStart<A>{k, -1, PlaneT(a, r, axis, p[k])};
}

// Walks the cells of `g` the ray crosses from t0 on, front to back, calling
// visit(global cell index, t_enter, t_exit) for each; stops when visit
// returns true (then returns true), when the ray leaves the grid, or after
// the cell in which it reaches t1.
template <class A, class Visit>
bool WalkLevel(const A& a, const RaySetup<A>& r, const Level& g, const float* planes, typename A::T t0,
               typename A::T t1, Visit&& visit) {
  using T = typename A::T;
  const float* p[3];
  int index[3], step[3];
  T t_next[3];
  uint32_t cell = g.first_cell;
  for (int axis = 0; axis < 3; ++axis) {
    p[axis] = planes + g.plane_offset[axis];
    const AxisStart<A> s = StartOnAxis(a, r, g, p[axis], axis, t0);
    index[axis] = s.index;
    step[axis] = s.step;
    t_next[axis] = s.t_next;
    cell += uint32_t(s.index) * g.stride[axis];
  }
  T t_enter = t0;
  for (;;) {
    // The axis crossed first; on a tie the lower axis, so that the cells of
    // a ray through an edge are all visited one by one.
    int axis = a.Le(t_next[0], t_next[1]) ? 0 : 1;
    if (a.Lt(t_next[2], t_next[axis])) axis = 2;
    const T t_exit = t_next[axis];
    if (visit(cell, t_enter, t_exit)) return true;
    if (a.Lt(t1, t_exit) || step[axis] == 0) return false;
    index[axis] += step[axis];
    if (index[axis] < 0 || index[axis] >= g.n[axis]) return false;
    if (step[axis] > 0) {
      cell += g.stride[axis];
      t_next[axis] = PlaneT(a, r, axis, p[axis][index[axis] + 1]);
    } else {
      cell -= g.stride[axis];
      t_next[axis] = PlaneT(a, r, axis, p[axis][index[axis]]);
    }
    t_enter = t_exit;
  }
}

// ---------------------------------------------------------------------------
// The built cells of a grid or hierarchical grid.

struct Cells {
  std::vector<Level> levels;      // levels[0] is the top level
  std::vector<float> planes;      // every level's planes
  std::vector<uint32_t> begin;    // cell c's list is refs[begin[c] .. begin[c+1])
  std::vector<uint32_t> refs;
  std::vector<uint32_t> child;    // hgrid only: the level of a cell's sub-grid, 0 for none
  bool empty = true;              // no usable box: every ray misses

  uint32_t cell_count() const { return begin.empty() ? 0 : uint32_t(begin.size() - 1); }
  uint64_t bytes() const {
    return begin.size() * sizeof(uint32_t) + refs.size() * sizeof(uint32_t) + child.size() * sizeof(uint32_t) +
           planes.size() * sizeof(float) + levels.size() * sizeof(Level);
  }
};

// Lets tests look at the cells of a grid or hgrid structure (dynamic_cast).
class CellsView {
 public:
  virtual ~CellsView() = default;
  const Cells& cells() const { return cells_; }

 protected:
  Cells cells_;
};

// Tests one cell's list; the counters' meaning is structure.h's.
template <class A>
inline void TestCellList(const A& a, const RaySetup<A>& r, const Cells& c, const StructureInput& in, uint32_t cell,
                         TraceResult<A>& best, TraceScratch& scratch) {
  ++scratch.counters.nodes;
  const uint32_t end = c.begin[cell + 1];
  uint32_t k = c.begin[cell];
  if (k == end) return;
  ++scratch.counters.leaves;
  for (; k < end; ++k) {
    const uint32_t id = c.refs[k];
    TestMailboxed(a, r, in.triangles[id], id, best, scratch);
  }
}

// Fills the statistics both grids share from the cells.
inline void FillCellStats(const Cells& c, StructureStats* s) {
  s->memory_bytes = c.bytes();
  s->nodes = c.cell_count();
  s->references = c.refs.size();
  s->leaves = 0;
  s->max_leaf_prims = 0;
  for (uint32_t cell = 0; cell < c.cell_count(); ++cell) {
    const uint32_t size = c.begin[cell + 1] - c.begin[cell];
    if (size > 0) ++s->leaves;
    s->max_leaf_prims = std::max(s->max_leaf_prims, size);
  }
}

}  // namespace kdrt::grid
