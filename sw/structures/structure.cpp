#include "structures/structure.h"

#include <cmath>

#include "common/error.h"

namespace kdrt {
namespace {

struct KindName {
  AccelKind kind;
  const char* name;
};
constexpr KindName kKinds[] = {
    {AccelKind::kSah, "sah"},       {AccelKind::kMedian, "median"}, {AccelKind::kMidpoint, "midpoint"},
    {AccelKind::kGrid, "grid"},     {AccelKind::kHgrid, "hgrid"},   {AccelKind::kOctree, "octree"},
    {AccelKind::kBvh, "bvh"},
};

}  // namespace

AccelKind ParseAccelKind(const std::string& name) {
  for (const KindName& k : kKinds) {
    if (name == k.name) return k.kind;
  }
  throw InputError("unknown structure '" + name +
                   "' (expected sah, median, midpoint (kd-trees), grid, hgrid, octree or bvh)");
}

const char* AccelKindName(AccelKind kind) {
  for (const KindName& k : kKinds) {
    if (kind == k.kind) return k.name;
  }
  return "?";
}

std::vector<AccelKind> AllAccelKinds() {
  std::vector<AccelKind> all;
  for (const KindName& k : kKinds) all.push_back(k.kind);
  return all;
}

AccelKind AccelKindOf(SplitMethod method) {
  switch (method) {
    case SplitMethod::kMedian:
      return AccelKind::kMedian;
    case SplitMethod::kMidpoint:
      return AccelKind::kMidpoint;
    default:
      return AccelKind::kSah;
  }
}

SplitMethod SplitMethodOf(AccelKind kind) {
  if (kind == AccelKind::kSah) return SplitMethod::kSah;
  if (kind == AccelKind::kMedian) return SplitMethod::kMedian;
  if (kind == AccelKind::kMidpoint) return SplitMethod::kMidpoint;
  throw InputError(std::string("'") + AccelKindName(kind) + "' is not a kd-tree split rule");
}

void CheckStructureOptions(const StructureOptions& o) {
  if (!(o.grid_density > 0) || !std::isfinite(o.grid_density) || o.grid_density > 1000) {
    throw InputError("--grid-density must be a number in (0, 1000] (cells per triangle)");
  }
  if (!(o.hgrid_density > 0) || !std::isfinite(o.hgrid_density) || o.hgrid_density > 1000) {
    throw InputError("--hgrid-density must be a number in (0, 1000] (cells per triangle)");
  }
  if (o.hgrid_max_prims < 1) throw InputError("hgrid_max_prims must be at least 1");
  if (o.hgrid_max_levels < 1 || o.hgrid_max_levels > 8) throw InputError("hgrid_max_levels must be in [1, 8]");
  if (o.octree_max_prims < 1) throw InputError("octree_max_prims must be at least 1");
  if (o.octree_max_depth < -1 || o.octree_max_depth > 32) throw InputError("octree_max_depth must be in [-1, 32]");
  if (o.bvh_bins < 2 || o.bvh_bins > 256) throw InputError("bvh_bins must be in [2, 256]");
}

StructureInput MakeStructureInput(const ImageView& image) {
  if (!image.layout().IsFp32()) {
    throw InputError("the software structures are built from the fp32 memory image");
  }
  const img::Header& h = image.header();
  StructureInput in;
  in.triangles.resize(h.tri_count);
  in.boxes.resize(h.tri_count);
  for (uint32_t id = 0; id < h.tri_count; ++id) {
    const img::TriangleRecord t = image.triangle(id);
    in.triangles[id] = t;
    // The kd-tree builder's rule: the cross product, in float, is exactly zero.
    if (IsDegenerate(Triangle{glm::vec3(t.v0[0], t.v0[1], t.v0[2]), glm::vec3(t.v1[0], t.v1[1], t.v1[2]),
                              glm::vec3(t.v2[0], t.v2[1], t.v2[2])})) {
      continue;
    }
    in.ids.push_back(id);
    accel::Box& b = in.boxes[id];
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(t.v0[a], std::min(t.v1[a], t.v2[a]));
      b.hi[a] = std::max(t.v0[a], std::max(t.v1[a], t.v2[a]));
    }
  }
  for (int a = 0; a < 3; ++a) {
    in.bounds.lo[a] = h.bounds_min[a];
    in.bounds.hi[a] = h.bounds_max[a];
  }
  return in;
}

std::unique_ptr<Structure> BuildStructure(AccelKind kind, const StructureInput& input,
                                          const StructureOptions& options) {
  switch (kind) {
    case AccelKind::kGrid:
      return BuildGrid(input, options);
    case AccelKind::kHgrid:
      return BuildHgrid(input, options);
    case AccelKind::kOctree:
      return BuildOctree(input, options);
    case AccelKind::kBvh:
      return BuildBvh(input, options);
    default:
      throw InputError(std::string("'") + AccelKindName(kind) + "' is a kd-tree: it is the memory image");
  }
}

nlohmann::json StructureStatsJson(const StructureStats& s) {
  nlohmann::json j = {
      {"build_seconds", s.build_seconds}, {"memory_bytes", s.memory_bytes}, {"nodes", s.nodes},
      {"leaves", s.leaves},               {"references", s.references},     {"max_depth", s.max_depth},
      {"max_leaf_prims", s.max_leaf_prims},
  };
  for (auto it = s.extra.begin(); it != s.extra.end(); ++it) j[it.key()] = it.value();
  return j;
}

}  // namespace kdrt
