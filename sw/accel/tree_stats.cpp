// Tree statistics, recounted from the finished node array (so they describe
// exactly what the hardware will read, whatever builder made it).
#include <algorithm>
#include <string>
#include <vector>

#include "accel/build_util.h"
#include "accel/kdtree.h"
#include "common/error.h"

namespace kdrt {

TreeStats ComputeTreeStats(const KdTree& tree, size_t triangles, const BuildOptions& options) {
  TreeStats st;
  if (tree.nodes.empty()) return st;
  accel::Box root;
  for (int a = 0; a < 3; ++a) {
    root.lo[a] = tree.bounds_min[a];
    root.hi[a] = tree.bounds_max[a];
  }
  const double root_sa = accel::SurfaceArea(root);
  // A flat or empty root box has no meaningful area ratios; count every node
  // as if it spanned the root then.
  auto ratio = [&](const accel::Box& b) {
    return root_sa > 0 ? accel::SurfaceArea(b) / root_sa : 1.0;
  };

  struct Item {
    uint32_t index;
    uint32_t depth;
    accel::Box cell;
  };
  std::vector<Item> stack{{0, 0, root}};
  uint64_t leaf_depth_sum = 0;
  uint32_t non_empty = 0;
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const img::Node& node = tree.nodes[item.index];
    ++st.nodes;
    st.max_depth = std::max(st.max_depth, item.depth);
    if (node.IsLeaf()) {
      ++st.leaves;
      leaf_depth_sum += item.depth;
      const uint32_t count = node.Count();
      if (count == 0) {
        ++st.empty_leaves;
      } else {
        ++non_empty;
      }
      int bucket = 0;
      while (bucket + 1 < kLeafSizeBuckets && (count >> bucket) != 0) ++bucket;
      ++st.leaf_sizes[bucket];
      st.max_leaf_prims = std::max(st.max_leaf_prims, count);
      st.references += count;
      st.sah_cost += static_cast<double>(options.isect_cost) * count * ratio(item.cell);
      continue;
    }
    ++st.inner_nodes;
    st.sah_cost += static_cast<double>(options.traversal_cost) * ratio(item.cell);
    const uint32_t below = item.index + 1;
    const uint32_t above = node.AboveChild();
    if (above <= below || above >= tree.nodes.size()) {
      throw InputError("kd-tree node " + std::to_string(item.index) +
                       " has an above child index out of range");
    }
    const int axis = node.Axis();
    Item b{below, item.depth + 1, item.cell};
    b.cell.hi[axis] = node.Split();
    Item a{above, item.depth + 1, item.cell};
    a.cell.lo[axis] = node.Split();
    stack.push_back(a);
    stack.push_back(b);
  }
  st.avg_leaf_depth = st.leaves ? static_cast<double>(leaf_depth_sum) / st.leaves : 0.0;
  st.avg_leaf_prims = non_empty ? static_cast<double>(st.references) / non_empty : 0.0;
  st.refs_per_triangle = triangles ? static_cast<double>(st.references) / triangles : 0.0;
  return st;
}

const char* LeafCauseName(LeafCause c) {
  switch (c) {
    case LeafCause::kFew: return "few";
    case LeafCause::kDepth: return "depth";
    case LeafCause::kNoPlane: return "no_plane";
    case LeafCause::kNoGain: return "no_gain";
    case LeafCause::kHopeless: return "hopeless";
    case LeafCause::kBudget: return "budget";
  }
  return "unknown";
}

const char* LeafCauseText(LeafCause c) {
  switch (c) {
    case LeafCause::kFew: return "few triangles";
    case LeafCause::kDepth: return "depth limit";
    case LeafCause::kNoPlane: return "no plane";
    case LeafCause::kNoGain: return "no cheaper split";
    case LeafCause::kHopeless: return "hopeless split";
    case LeafCause::kBudget: return "reference budget";
  }
  return "unknown";
}

}  // namespace kdrt
