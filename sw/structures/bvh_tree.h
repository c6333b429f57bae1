// The flat node array of the SAH BVH (bvh.cpp), exposed so that tests and
// tools can check its invariants (child boxes inside parents, every triangle
// in one leaf) without going through rays.
#pragma once

#include <cstdint>
#include <vector>

#include "structures/structure.h"

namespace kdrt {

// A leaf never holds more triangles than this (it fits BvhNode::count); a
// node with more is split even when the SAH says a leaf would be cheaper.
inline constexpr uint32_t kBvhMaxLeafPrims = 255;
// Below this depth splits follow the SAH; deeper nodes (only reached when the
// SAH keeps peeling off a few triangles) split at the object median, which
// halves the count each level, so no tree is deeper than this + 23.
inline constexpr uint32_t kBvhMaxSahDepth = 64;

// pbrt-v3's LinearBVHNode: 32 bytes, depth-first order, the first child of
// an inner node right after it in memory.
struct alignas(32) BvhNode {  // one node never straddles two cache lines
  float box[6];     // lo x, y, z, then hi x, y, z (rounded outwards to normal floats or zero)
  uint32_t offset;  // leaf: first entry in BvhTree::ids; inner: index of the second child
  uint16_t count;   // leaf: triangles (1 .. kBvhMaxLeafPrims); inner: 0
  uint8_t axis;     // inner: split axis (the first child holds the lower centroids)
  uint8_t pad;
  bool IsLeaf() const { return count != 0; }
  const float* lo() const { return box; }
  const float* hi() const { return box + 3; }
};
static_assert(sizeof(BvhNode) == 32, "BvhNode layout");

struct BvhTree {
  std::vector<BvhNode> nodes;  // empty for a scene without non-degenerate triangles
  std::vector<uint32_t> ids;   // triangle ids in leaf order (one entry per triangle)
};

// The tree behind a structure BuildBvh made; nullptr for any other structure.
const BvhTree* BvhTreeOf(const Structure& s);

}  // namespace kdrt
