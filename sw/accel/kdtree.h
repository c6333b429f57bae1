// kd-tree construction. The tree comes out already in the memory-image node
// encoding (common/image_format.h): nodes in depth-first order with the below
// child adjacent to its parent, leaves pointing into one shared list array.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "common/image_format.h"
#include "scene/scene.h"

namespace kdrt {

enum class SplitMethod {
  kSah,       // surface area heuristic, Wald & Havran 2006 O(N log N) event sweep
  kMedian,    // median of triangle-box centres on the longest axis
  kMidpoint,  // spatial middle of the node box on the longest axis
};

// What the SAH build asks of a split by default (BuildOptions::min_split_gain):
// 0.1; `--min-split-gain 0` is pbrt-v3's rule, any split cheaper than the
// leaf is good (docs/kdtree.md).
inline constexpr float kDefaultMinSplitGain = 0.1f;

// pbrt-v3 KdTreeAccel defaults, but for the minimum split gain.
struct BuildOptions {
  SplitMethod method = SplitMethod::kSah;
  float traversal_cost = 1.0f;
  float isect_cost = 80.0f;
  float empty_bonus = 0.5f;
  int max_depth = -1;        // -1: round(8 + 1.3 log2 N)
  int max_leaf_prims = 1;    // a node with this many or fewer becomes a leaf
  bool perfect_splits = false;  // clip triangles to the node box (SAH only)
  // SAH only: a node of more than kLargeLeafPrims triangles whose boxes give
  // no good split is decided again on its triangles clipped to its cell,
  // and its subtree built with perfect splits (docs/kdtree.md, "Clipping
  // where the boxes fail").
  bool auto_clip = true;
  // SAH: a split that does not cost less than (1 - G) x the leaf counts
  // towards the bad-refinement limit (0: pbrt-v3's rule, any split cheaper
  // than the leaf is good; docs/kdtree.md, "Minimum split gain").
  float min_split_gain = kDefaultMinSplitGain;
  int threads = 1;           // SAH build threads (0: all cores); the tree does not depend on it
};

// The deepest tree BuildOptions::max_depth may ask for (InputError above it).
inline constexpr int kMaxTreeDepth = 255;

// What max_depth = -1 means: round(8 + 1.3 log2 N) for N non-degenerate
// triangles (capped at kMaxTreeDepth; 0 when N = 0).
int DefaultMaxDepth(size_t triangles);

SplitMethod ParseSplitMethod(const std::string& name);  // "sah", "median", "midpoint"
const char* SplitMethodName(SplitMethod m);

// Why the builder made a node a leaf (the first rule that held):
enum class LeafCause : uint8_t {
  kFew,       // at most max_leaf_prims triangles (empty leaves too)
  kDepth,     // the depth limit
  kNoPlane,   // no candidate plane inside the cell: every triangle spans it on every axis
  kNoGain,    // SAH: no split cheaper than the leaf, kMaxBadRefines times on the path;
              // median/midpoint: the split would put every triangle on both sides
  kHopeless,  // SAH: the best split costs over 4x the leaf in a node of < 16 triangles
  kBudget,    // SAH: the split would exceed the reference budget of a clipped subtree
};
inline constexpr int kLeafCauseCount = 6;
const char* LeafCauseName(LeafCause c);  // "few", "depth", "no_plane", "no_gain", "hopeless", "budget"
const char* LeafCauseText(LeafCause c);  // "few triangles", "depth limit", ... (for people)

// A leaf of more than this many triangles counts as large in LeafCauses.
inline constexpr uint32_t kLargeLeafPrims = 16;

struct LeafCauseCount {
  uint64_t leaves = 0;
  uint64_t references = 0;  // triangles listed in those leaves
  uint64_t large = 0;       // leaves of more than kLargeLeafPrims triangles
  uint32_t largest = 0;     // triangles in the largest of them
};

struct LeafCauses {
  LeafCauseCount by_cause[kLeafCauseCount];
  bool recorded = false;  // false: the tree was not built here (e.g. read back)

  void Add(LeafCause c, size_t prims) {
    LeafCauseCount& n = by_cause[static_cast<int>(c)];
    ++n.leaves;
    n.references += prims;
    n.large += prims > kLargeLeafPrims;
    if (prims > n.largest) n.largest = static_cast<uint32_t>(prims);
  }
  void Merge(const LeafCauses& o) {
    for (int i = 0; i < kLeafCauseCount; ++i) {
      by_cause[i].leaves += o.by_cause[i].leaves;
      by_cause[i].references += o.by_cause[i].references;
      by_cause[i].large += o.by_cause[i].large;
      by_cause[i].largest = std::max(by_cause[i].largest, o.by_cause[i].largest);
    }
  }
};

// Leaf sizes in powers of two: bucket 0 counts empty leaves, bucket b > 0
// leaves of 2^(b-1) .. 2^b - 1 triangles, the last bucket every larger leaf.
inline constexpr int kLeafSizeBuckets = 12;

struct TreeStats {
  uint32_t nodes = 0;
  uint32_t inner_nodes = 0;
  uint32_t leaves = 0;
  uint32_t empty_leaves = 0;
  uint32_t max_depth = 0;         // root has depth 0
  uint32_t depth_limit = 0;       // the depth limit the build used (BuildOptions::max_depth resolved)
  double avg_leaf_depth = 0;      // over all leaves
  uint32_t max_leaf_prims = 0;
  double avg_leaf_prims = 0;      // over non-empty leaves
  uint64_t references = 0;        // total leaf list entries
  double refs_per_triangle = 0;   // references / non-degenerate triangles
  double sah_cost = 0;            // expected cost of the finished tree (pbrt's cost model)
  uint32_t degenerate_triangles = 0;  // left out of the tree
  double build_seconds = 0;
  LeafCauses leaf_causes;  // recorded by the builder, not recounted from the nodes
  uint64_t leaf_sizes[kLeafSizeBuckets] = {};  // leaves per size bucket (kLeafSizeBuckets)
};

struct KdTree {
  std::vector<img::Node> nodes;  // root = 0
  std::vector<uint32_t> lists;   // triangle ids (scene order)
  glm::vec3 bounds_min{0.0f};    // box of the non-degenerate triangles
  glm::vec3 bounds_max{0.0f};
  TreeStats stats;
};

// Throws InputError on NaN/Inf vertices, invalid options, or a tree that
// does not fit the memory image's indices (28-bit nodes, 30-bit counts).
KdTree BuildKdTree(const Scene& scene, const BuildOptions& options = {});

// The statistics of a finished tree (everything but degenerate_triangles,
// depth_limit and build_seconds), recounted from its nodes; `triangles` is the number of
// non-degenerate triangles. sah_cost uses options' traversal and
// intersection costs and the cells implied by tree.bounds_min/max.
TreeStats ComputeTreeStats(const KdTree& tree, size_t triangles, const BuildOptions& options);

}  // namespace kdrt
