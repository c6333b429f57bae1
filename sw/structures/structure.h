// The lecture's other acceleration structures (uniform grid, hierarchical
// grid, octree, BVH) as software backends of the reference tracer, so a user
// can compare them with the kd-tree the hardware reads (`kdrt render --accel`,
// `kdrt compare-accel`, docs/structures.md).
//
// Every backend is built over the triangles of the fp32 memory image (the
// scene in its frame, trace/frame.h) and traces the framed ray with the
// kd-tree tracer's ray setup and watertight test (trace/intersect.h) in fp32
// or fp64. The closest hit is the kd-tree's: the smallest t, among equal t
// the smallest triangle id. So on scenes without ties at equal t every
// backend returns the kd-tree's hit buffer bit for bit; only the visiting
// order and the work differ.
//
// What a backend must keep to stay exact:
//  - a triangle is listed in every cell (leaf) it touches, cells widened a
//    little for the binning, so rounding in the traversal cannot lose a hit;
//  - the ray's cell intervals are widened by kTraversalSlackUlps
//    (trace/traversal.h), and the ray stops only when its best hit lies
//    within the (widened) exit of the cell just finished;
//  - a mailboxed triangle tested once for a ray is never tested again for
//    that ray (the hit, if any, is already in `best`).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "accel/build_util.h"
#include "accel/kdtree.h"
#include "common/image_format.h"
#include "common/ray.h"
#include "fp/format.h"
#include "trace/intersect.h"
#include "trace/memory_image.h"
#include "trace/tracer.h"
#include "trace/traversal.h"

namespace kdrt {

// Every structure `--accel` names: the kd-tree's three split rules (the
// memory image, traced by trace/tracer.h) and the software-only ones.
enum class AccelKind { kSah, kMedian, kMidpoint, kGrid, kHgrid, kOctree, kBvh };

AccelKind ParseAccelKind(const std::string& name);  // InputError naming the choices
const char* AccelKindName(AccelKind kind);
inline bool IsKdTree(AccelKind kind) { return kind == AccelKind::kSah || kind == AccelKind::kMedian || kind == AccelKind::kMidpoint; }
std::vector<AccelKind> AllAccelKinds();  // in the order above
AccelKind AccelKindOf(SplitMethod method);
SplitMethod SplitMethodOf(AccelKind kd_kind);  // InputError for a software structure

// Build parameters of the software structures. The defaults are the ones
// docs/structures.md measures.
struct StructureOptions {
  // Uniform grid resolution (the lecture's n^3 = d |O|): cells ~ density x
  // triangles, cubical cells fitted to the scene box. Measured (100k, 1M):
  // 4 and 8 are equally fast, 8 with twice the memory.
  double grid_density = 4.0;
  // The same rule for the hierarchical grid's top level and each sub-grid:
  // 1 was the fastest there, with a third of the memory of 4.
  double hgrid_density = 1.0;
  // Hierarchical grid: a cell with more triangles than this gets its own
  // grid, down to hgrid_max_levels levels (top level = 1).
  int hgrid_max_prims = 16;
  int hgrid_max_levels = 3;
  // Octree: a cell with more triangles than this splits into eight, down to
  // octree_max_depth (-1: round((8 + 1.3 log2 N) / 3) + 1, capped at 32;
  // deeper limits changed nothing measurable), if the split pays and fits
  // the reference budget (octree_tree.h).
  int octree_max_prims = 8;
  int octree_max_depth = -1;
  // BVH: binned SAH on centroids (this many bins per axis); a node becomes
  // a leaf when no split is cheaper than testing all its triangles (the
  // lecture's cost rule, bvh.cpp).
  int bvh_bins = 32;
};

// Throws InputError for options out of range (with the option's name).
void CheckStructureOptions(const StructureOptions& options);

// What a structure costs, measured when it is built.
struct StructureStats {
  double build_seconds = 0;
  uint64_t memory_bytes = 0;   // cells/nodes and reference lists; triangles not included
  uint64_t nodes = 0;          // grid cells (all levels) or tree nodes
  uint64_t leaves = 0;         // cells or leaves that hold triangles
  uint64_t references = 0;     // triangle references in all lists
  uint32_t max_depth = 0;      // tree depth or grid levels (root/top level = 0)
  uint32_t max_leaf_prims = 0; // longest list
  nlohmann::json extra = nlohmann::json::object();  // structure-specific (grid resolution, ...)
};

// Per-ray work, the same meaning in every structure.
struct AccelCounters {
  uint32_t nodes = 0;         // grid cells stepped into or tree nodes visited (kd: nodes fetched)
  uint32_t leaves = 0;        // of those, the ones holding triangles (kd: leaves incl. empty)
  uint32_t tri_tests = 0;     // ray/triangle tests run
  uint32_t mailbox_hits = 0;  // tests avoided because the mailbox had the triangle
  AccelCounters& operator+=(const AccelCounters& o) {
    nodes += o.nodes;
    leaves += o.leaves;
    tri_tests += o.tri_tests;
    mailbox_hits += o.mailbox_hits;
    return *this;
  }
};

// The lecture's mailbox: a ray number per triangle. One per tracing thread;
// NextRay() before each ray.
class Mailbox {
 public:
  explicit Mailbox(size_t triangles) : last_(triangles, 0) {}
  void NextRay() {
    if (++ray_ == 0) {  // wrapped: forget every entry
      std::fill(last_.begin(), last_.end(), 0u);
      ray_ = 1;
    }
  }
  // True if the triangle was already tested for this ray; marks it tested.
  bool Seen(uint32_t id) {
    if (last_[id] == ray_) return true;
    last_[id] = ray_;
    return false;
  }
  size_t bytes() const { return last_.size() * sizeof(uint32_t); }

 private:
  std::vector<uint32_t> last_;
  uint32_t ray_ = 0;
};

// What the builders get: the fp32 image's triangles (all of them, by scene
// id, in the frame) and the non-degenerate ones the kd-tree holds.
struct StructureInput {
  std::vector<img::TriangleRecord> triangles;  // by scene id
  std::vector<uint32_t> ids;                   // non-degenerate ids, ascending
  std::vector<accel::Box> boxes;               // per scene id (meaningful for `ids` only)
  accel::Box bounds{};                         // the image's scene box (the kd-tree's root cell)
};
// Throws InputError if the image is not an fp32 image.
StructureInput MakeStructureInput(const ImageView& fp32_image);

// Per-thread state of one trace.
struct TraceScratch {
  explicit TraceScratch(size_t triangles) : mailbox(triangles) {}
  Mailbox mailbox;
  AccelCounters counters;  // of the current ray
};

// The test every backend runs on a triangle: the watertight test over the
// ray's whole [tmin, tmax], the candidate kept if closer than the best so
// far (equal t: smaller id). Testing against the ray's tmax rather than the
// best t makes the result the exact (t, id) minimum over the triangles
// tested, whatever their order, so the backends agree with each other even
// at ties (two triangles hit at one t); the kd-tree tests a leaf against the
// best t at its entry and may keep the other triangle of such a tie.
template <class A>
inline void TestTriangle(const A& a, const RaySetup<A>& r, const img::TriangleRecord& tri, uint32_t id,
                         TraceResult<A>& best, AccelCounters& counters) {
  ++counters.tri_tests;
  const Candidate<A> c = IntersectWatertight(a, r, tri, r.tmax);
  if (c.hit && (a.Lt(c.t, best.t) || (a.Eq(c.t, best.t) && id < best.prim))) {
    best.t = c.t;
    best.u = c.u;
    best.v = c.v;
    best.prim = id;
  }
}

// The same behind the mailbox.
template <class A>
inline void TestMailboxed(const A& a, const RaySetup<A>& r, const img::TriangleRecord& tri, uint32_t id,
                          TraceResult<A>& best, TraceScratch& scratch) {
  if (scratch.mailbox.Seen(id)) {
    ++scratch.counters.mailbox_hits;
    return;
  }
  TestTriangle(a, r, tri, id, best, scratch.counters);
}

// True when a ray whose cell (or node interval) ends at `t_exit` (not yet
// widened) is finished: it has a hit and, for a closest-hit query, that hit
// lies no farther than the widened exit.
template <class A>
inline bool DoneAfterCell(const A& a, const TraceResult<A>& best, Query query, typename A::T t_exit) {
  if (best.prim == kNoPrim) return false;
  return query == Query::kAny || a.Le(best.t, a.NudgeUp(t_exit, kTraversalSlackUlps));
}

class Structure {
 public:
  explicit Structure(const StructureInput& input) : input_(&input) {}
  virtual ~Structure() = default;
  virtual AccelKind kind() const = 0;
  virtual bool uses_mailbox() const = 0;
  const StructureStats& stats() const { return stats_; }
  const StructureInput& input() const { return *input_; }

  // What every Build* factory returns: make() (the whole build) run, and
  // its wall time recorded in stats().build_seconds.
  template <class Make>
  static std::unique_ptr<Structure> Timed(Make&& make) {
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<Structure> s = make();
    s->stats_.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return s;
  }
  size_t triangle_count() const { return input_->triangles.size(); }

  // Traces one ray already set up in the frame. `best` comes in as a miss
  // with t = r.tmax; the backend leaves the closest hit in it.
  virtual void Trace(const fp::NativeF32Arith& a, const RaySetup<fp::NativeF32Arith>& r, Query query,
                     TraceResult<fp::NativeF32Arith>& best, TraceScratch& scratch) const = 0;
  virtual void Trace(const fp::NativeF64Arith& a, const RaySetup<fp::NativeF64Arith>& r, Query query,
                     TraceResult<fp::NativeF64Arith>& best, TraceScratch& scratch) const = 0;

 protected:
  const StructureInput* input_;
  StructureStats stats_;
};

// Backends implement one template, `template <class A> void TraceT(const A&,
// const RaySetup<A>&, Query, TraceResult<A>&, TraceScratch&) const`; this
// turns it into the two virtual entry points.
template <class Derived>
class StructureBase : public Structure {
 public:
  using Structure::Structure;
  void Trace(const fp::NativeF32Arith& a, const RaySetup<fp::NativeF32Arith>& r, Query query,
             TraceResult<fp::NativeF32Arith>& best, TraceScratch& scratch) const override {
    static_cast<const Derived*>(this)->TraceT(a, r, query, best, scratch);
  }
  void Trace(const fp::NativeF64Arith& a, const RaySetup<fp::NativeF64Arith>& r, Query query,
             TraceResult<fp::NativeF64Arith>& best, TraceScratch& scratch) const override {
    static_cast<const Derived*>(this)->TraceT(a, r, query, best, scratch);
  }
};

// The backends (grid.cpp, hgrid.cpp, octree.cpp, bvh.cpp). They keep a
// pointer to `input`, which must outlive them; each checks `options`
// (CheckStructureOptions). Build time goes into stats() (Structure::Timed).
std::unique_ptr<Structure> BuildGrid(const StructureInput& input, const StructureOptions& options);
std::unique_ptr<Structure> BuildHgrid(const StructureInput& input, const StructureOptions& options);
std::unique_ptr<Structure> BuildOctree(const StructureInput& input, const StructureOptions& options);
std::unique_ptr<Structure> BuildBvh(const StructureInput& input, const StructureOptions& options);

// Any software structure (InputError for a kd-tree kind: that is the image).
std::unique_ptr<Structure> BuildStructure(AccelKind kind, const StructureInput& input,
                                          const StructureOptions& options);

nlohmann::json StructureStatsJson(const StructureStats& s);

}  // namespace kdrt
