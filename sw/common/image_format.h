// The kdrt memory image, version 2: the bytes a hardware core reads.
// docs/memory-image.md is the prose specification of this header; the RTL
// package (rtl/kdrt_pkg.sv) mirrors the constants. Everything is little-endian,
// every float is IEEE binary32, every section starts on a 64-byte boundary.
//
//   offset 0    Header (128 bytes)
//   node_offset nodes, node_count x 8 bytes, root = node 0
//   list_offset leaf lists, list_count x uint32 (triangle ids)
//   tri_offset  triangles, tri_count x 48 bytes, indexed by triangle id
#pragma once

#include <cstdint>
#include <cstring>

namespace kdrt::img {

inline constexpr char kMagic[8] = {'K', 'D', 'R', 'T', 'I', 'M', 'G', '\0'};
inline constexpr uint32_t kVersion = 2;
inline constexpr uint32_t kHeaderBytes = 128;
inline constexpr uint32_t kSectionAlign = 64;
inline constexpr uint32_t kNodeBytes = 8;
inline constexpr uint32_t kListEntryBytes = 4;
inline constexpr uint32_t kTriangleBytes = 48;

struct Header {
  char magic[8];          // "KDRTIMG\0"
  uint32_t version;       // kVersion
  uint32_t total_bytes;   // whole image, including padding
  uint32_t node_offset;   // byte offset of node 0
  uint32_t node_count;
  uint32_t list_offset;   // byte offset of list entry 0
  uint32_t list_count;    // number of uint32 entries
  uint32_t tri_offset;    // byte offset of triangle 0
  uint32_t tri_count;     // == number of scene triangles (file order)
  uint32_t max_depth;     // deepest node, root at depth 0
  uint32_t max_leaf_prims;// largest leaf list
  float bounds_min[3];    // scene box the root cell spans (in the frame)
  float bounds_max[3];
  float frame_origin[3];  // world = framed * 2^-frame_scale_log2 + frame_origin
  int32_t frame_scale_log2;
  uint32_t reserved[10];  // zero
};
static_assert(sizeof(Header) == kHeaderBytes, "header layout");

// Node word 1, bits [1:0]: the split axis (0 = x, 1 = y, 2 = z) or kLeaf.
inline constexpr uint32_t kLeaf = 3;

// One 8-byte kd-tree node (pbrt-style).
//   inner: word0 = split position (float bits); word1 = axis | above << 2,
//          where `above` is the node index of the child on the +axis side;
//          the child on the -axis side ("below") is always this index + 1.
//   leaf:  word0 = index of the first entry in the leaf lists;
//          word1 = kLeaf | count << 2 (count 0 = empty leaf).
struct Node {
  uint32_t word0;
  uint32_t word1;

  static Node Inner(int axis, float split, uint32_t above_child) {
    Node n;
    std::memcpy(&n.word0, &split, 4);
    n.word1 = static_cast<uint32_t>(axis) | (above_child << 2);
    return n;
  }
  static Node Leaf(uint32_t first, uint32_t count) { return Node{first, kLeaf | (count << 2)}; }

  bool IsLeaf() const { return (word1 & 3u) == kLeaf; }
  int Axis() const { return static_cast<int>(word1 & 3u); }
  float Split() const {
    float f;
    std::memcpy(&f, &word0, 4);
    return f;
  }
  uint32_t AboveChild() const { return word1 >> 2; }
  uint32_t FirstEntry() const { return word0; }
  uint32_t Count() const { return word1 >> 2; }
};
static_assert(sizeof(Node) == kNodeBytes, "node layout");

// 30 bits are left for a child index or a leaf's count.
inline constexpr uint32_t kMaxIndex = (1u << 30) - 1;

// Triangle record: the three vertices in file order, as the watertight and
// the Moller-Trumbore tests both read them, then the triangle id (a check for
// the hardware, equal to the record's index) and padding.
struct TriangleRecord {
  float v0[3];
  float v1[3];
  float v2[3];
  uint32_t id;
  uint32_t pad[2];
};
static_assert(sizeof(TriangleRecord) == kTriangleBytes, "triangle layout");

}  // namespace kdrt::img
