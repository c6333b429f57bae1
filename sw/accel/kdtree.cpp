// BuildKdTree: option checks, the degenerate-triangle filter, the choice of
// builder, and the statistics of the finished tree.
#include "accel/kdtree.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "accel/build_util.h"
#include "common/error.h"

namespace kdrt {
namespace {

// Local on purpose (scene/IsDegenerate has the same contract): the cross
// product, in float, is exactly the zero vector.
bool ZeroArea(const Triangle& t) {
  const glm::vec3 e1 = t.v1 - t.v0;
  const glm::vec3 e2 = t.v2 - t.v0;
  const float cx = e1.y * e2.z - e1.z * e2.y;
  const float cy = e1.z * e2.x - e1.x * e2.z;
  const float cz = e1.x * e2.y - e1.y * e2.x;
  return cx == 0.0f && cy == 0.0f && cz == 0.0f;
}

bool Finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string SourceName(const Scene& scene) {
  return scene.source.empty() ? std::string("scene") : scene.source;
}

void CheckOptions(const BuildOptions& o, const std::string& source) {
  auto fail = [&](const std::string& what) { throw InputError(source, 0, what); };
  if (!std::isfinite(o.traversal_cost) || o.traversal_cost < 0) {
    fail("kd-tree traversal cost must be a finite number >= 0");
  }
  if (!std::isfinite(o.isect_cost) || o.isect_cost < 0) {
    fail("kd-tree intersection cost must be a finite number >= 0");
  }
  if (!std::isfinite(o.empty_bonus) || o.empty_bonus < 0 || o.empty_bonus > 1) {
    fail("kd-tree empty bonus must be between 0 and 1");
  }
  if (!std::isfinite(o.min_split_gain) || o.min_split_gain < 0 || o.min_split_gain >= 1) {
    fail("kd-tree minimum split gain must be at least 0 and below 1");
  }
  if (o.max_depth < -1 || o.max_depth > kMaxTreeDepth) {
    fail("kd-tree max depth must be -1 (automatic) or 0.." + std::to_string(kMaxTreeDepth));
  }
  if (o.max_leaf_prims < 0) fail("kd-tree max leaf primitives must be >= 0");
  if (o.threads < 0 || o.threads > 1024) fail("kd-tree build threads must be 0 (all cores) .. 1024");
}

accel::BuildInput Prepare(const Scene& scene, const BuildOptions& options, uint32_t* degenerate) {
  accel::BuildInput in;
  in.triangles = &scene.triangles;
  in.source = SourceName(scene);
  const size_t n = scene.triangles.size();
  if (n > img::kMaxIndex) {
    throw InputError(in.source, 0, "more than 2^30 triangles, too many for the memory image");
  }
  in.boxes.resize(n);
  in.flat.assign(n, 0);
  *degenerate = 0;
  for (int a = 0; a < 3; ++a) {
    in.bounds.lo[a] = std::numeric_limits<float>::infinity();
    in.bounds.hi[a] = -std::numeric_limits<float>::infinity();
  }
  for (size_t i = 0; i < n; ++i) {
    const Triangle& t = scene.triangles[i];
    if (!Finite(t.v0) || !Finite(t.v1) || !Finite(t.v2)) {
      throw InputError(in.source, 0,
                       "triangle " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
    if (ZeroArea(t)) {
      ++*degenerate;
      continue;
    }
    in.ids.push_back(static_cast<uint32_t>(i));
    accel::Box& b = in.boxes[i];
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min({t.v0[a], t.v1[a], t.v2[a]});
      b.hi[a] = std::max({t.v0[a], t.v1[a], t.v2[a]});
      if (t.v0[a] == t.v1[a] && t.v0[a] == t.v2[a]) in.flat[i] |= 1u << a;
      in.bounds.lo[a] = std::min(in.bounds.lo[a], b.lo[a]);
      in.bounds.hi[a] = std::max(in.bounds.hi[a], b.hi[a]);
    }
  }
  if (in.ids.empty()) {
    for (int a = 0; a < 3; ++a) in.bounds.lo[a] = in.bounds.hi[a] = 0.0f;
  }
  in.max_depth = options.max_depth >= 0 ? options.max_depth : DefaultMaxDepth(in.ids.size());
  return in;
}

}  // namespace

namespace accel {
void TreeWriter::Fail(const std::string& what) const { throw InputError(source_, 0, what); }
}  // namespace accel

int DefaultMaxDepth(size_t triangles) {
  if (triangles == 0) return 0;
  const double d = std::round(8.0 + 1.3 * std::log2(static_cast<double>(triangles)));
  return static_cast<int>(std::min<double>(d, kMaxTreeDepth));
}

SplitMethod ParseSplitMethod(const std::string& name) {
  if (name == "sah") return SplitMethod::kSah;
  if (name == "median") return SplitMethod::kMedian;
  if (name == "midpoint") return SplitMethod::kMidpoint;
  throw InputError("unknown kd-tree split method '" + name +
                   "' (expected sah, median or midpoint)");
}

const char* SplitMethodName(SplitMethod m) {
  switch (m) {
    case SplitMethod::kSah: return "sah";
    case SplitMethod::kMedian: return "median";
    case SplitMethod::kMidpoint: return "midpoint";
  }
  return "unknown";
}

KdTree BuildKdTree(const Scene& scene, const BuildOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::string source = SourceName(scene);
  CheckOptions(options, source);
  uint32_t degenerate = 0;
  const accel::BuildInput input = Prepare(scene, options, &degenerate);

  KdTree tree;
  tree.bounds_min = glm::vec3(input.bounds.lo[0], input.bounds.lo[1], input.bounds.lo[2]);
  tree.bounds_max = glm::vec3(input.bounds.hi[0], input.bounds.hi[1], input.bounds.hi[2]);
  accel::TreeWriter writer(&tree.nodes, &tree.lists, source);
  if (input.ids.empty()) {
    std::vector<uint32_t> none;
    writer.AddLeaf(none, LeafCause::kFew);
  } else if (options.method == SplitMethod::kSah) {
    accel::BuildSahTree(input, options, &writer);
  } else {
    accel::BuildSimpleTree(input, options.method == SplitMethod::kMedian, options.max_leaf_prims,
                           &writer);
  }
  tree.stats = ComputeTreeStats(tree, input.ids.size(), options);
  tree.stats.leaf_causes = writer.causes();
  tree.stats.leaf_causes.recorded = true;
  tree.stats.degenerate_triangles = degenerate;
  tree.stats.depth_limit = static_cast<uint32_t>(input.max_depth);
  tree.stats.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return tree;
}

}  // namespace kdrt
