// The kdrt memory image, version 5: the bytes a hardware core reads.
// docs/memory-image.md is the prose specification of this header; the RTL
// package (rtl/kdrt_pkg.sv) mirrors the constants. Everything is little-endian,
// every section starts on a 64-byte boundary.
//
//   offset 0    Header (128 bytes)
//   node_offset nodes, packed into 16-byte beats, root = node 0
//   list_offset leaf lists, list_count x uint32 (triangle ids)
//   tri_offset  triangles, tri_count records in lines of whole beats, by triangle id
//
// Split positions and vertices are stored in the image's number format
// (header format_e, format_m; ImageLayout below): an fp32 image holds
// binary32 values in 8-byte nodes and 48-byte triangles, a narrower format
// packs them (e.g. fp16: 3 nodes per beat, 2 triangles per 48 bytes). The header's
// bounds and frame are binary32 in every image.
#pragma once

#include <cstdint>
#include <cstring>

namespace kdrt::img {

inline constexpr char kMagic[8] = {'K', 'D', 'R', 'T', 'I', 'M', 'G', '\0'};
inline constexpr uint32_t kVersion = 5;
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
  uint32_t format_e;      // the number format of splits and vertices:
  uint32_t format_m;      //   exponent and mantissa bits (8, 23 = binary32)
  uint32_t reserved[8];   // zero
};
static_assert(sizeof(Header) == kHeaderBytes, "header layout");

// Node word 1, bits [1:0]: the split axis (0 = x, 1 = y, 2 = z) or kLeaf.
inline constexpr uint32_t kLeaf = 3;
// The largest child index an inner node holds (28 bits: two bits above it
// mark empty children), and so the most nodes a tree may have, less one.
inline constexpr uint32_t kMaxChildIndex = (1u << 28) - 1;

// One 8-byte kd-tree node (pbrt-style).
//   inner: word0 = split position (float bits); word1 = axis | above << 2
//          | below_empty << 30 | above_empty << 31, where `above` (28 bits)
//          is the node index of the child on the +axis side; the child on
//          the -axis side ("below") is always this index + 1. A child that
//          is an empty leaf is marked in its parent, so that the hardware
//          never fetches it (docs/memory-image.md); a kd-tree's own nodes
//          (KdTree::nodes) leave the marks zero, the memory image sets them.
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
  uint32_t AboveChild() const { return (word1 >> 2) & kMaxChildIndex; }
  // Inner nodes: the child on the -axis / +axis side is an empty leaf.
  bool BelowEmpty() const { return (word1 >> 30 & 1u) != 0; }
  bool AboveEmpty() const { return (word1 >> 31) != 0; }
  Node WithEmptyChildren(bool below_empty, bool above_empty) const {
    return Node{word0, (word1 & ~(3u << 30)) | uint32_t{below_empty} << 30 | uint32_t{above_empty} << 31};
  }
  uint32_t FirstEntry() const { return word0; }
  uint32_t Count() const { return word1 >> 2; }
};
static_assert(sizeof(Node) == kNodeBytes, "node layout");

// 30 bits are left for a child index or a leaf's count.
inline constexpr uint32_t kMaxIndex = (1u << 30) - 1;

// Where a format's values go. W = 1 + e + m bits per value.
//
// Nodes: NodesPerBeat() nodes of NodeBits() bits in each 16-byte beat (node
// k of a beat at bits [k * NodeBits, (k + 1) * NodeBits), little-endian), a
// node never straddling two beats. W > 16: 2 nodes of 64 bits; W <= 16: 3
// nodes of 42 bits. Within a node, with H = NodeBits - W - 2:
//   bits [W-1:0]               inner: the split (format bits)
//   bits [W+1:W]               the axis 0/1/2, or kLeaf
//   bits [NodeBits-3:W+2]      inner: the above child's index (H - 2 bits)
//   bits [NodeBits-1:NodeBits-2] inner: below child empty, above child empty
// A leaf reads the other NodeBits - 2 bits as one number {bits above the
// axis, bits below it}: its low FirstBits() are the first list entry, the
// rest the count. For W = 32 this is exactly img::Node (word 0 the split or
// first entry, word 1 axis | above << 2 | marks << 30 or kLeaf | count << 2).
//
// Node indices address slots: node i is slot i % 4 of beat i / 4 when 3
// nodes share a beat (slot 3 is never used), slot i % 2 of beat i / 2 when
// 2 do. The below child is the next slot, NextNode(i).
//
// Triangles: lines of TriangleLineBeats() beats, each holding
// TrianglesPerLine() records (1, or 2 where two fit in 3 beats and one does
// not fit in 1: 15 <= W <= 21, fp16 and bf16), so a record takes no more
// beats than it needs. Triangle i is record i % P of line i / P, in the
// record's slot of TriangleSlotBits() bits at bit (i % P) * slot: the 9
// coordinates v0.x, v0.y, v0.z, v1.x, ..., v2.z at bits [k * W, (k + 1) * W),
// then the triangle id (32 bits, a check; the hardware takes the id from the
// leaf list) at bit 9 * W where it fits in the slot, zeros after. For W = 32
// this is img::TriangleRecord.
struct ImageLayout {
  int e = 8, m = 23;

  int Width() const { return 1 + e + m; }
  int NodesPerBeat() const { return Width() <= 16 ? 3 : 2; }
  int NodeBits() const { return NodesPerBeat() == 3 ? 42 : 64; }
  // Bits above the axis: a leaf's high payload, an inner node's above
  // child (ChildBits) and its two empty-child marks.
  int AboveBits() const { return NodeBits() - Width() - 2; }
  int ChildBits() const { return AboveBits() - 2; }
  int FirstBits() const { return NodesPerBeat() == 3 ? 24 : 32; }
  int CountBits() const { return NodeBits() - 2 - FirstBits(); }
  // Index bits that select the slot within a beat.
  int SlotBits() const { return NodesPerBeat() == 3 ? 2 : 1; }
  int TrianglesPerLine() const { return 9 * Width() > 128 && 9 * Width() <= 192 ? 2 : 1; }
  int TriangleLineBeats() const { return TrianglesPerLine() == 2 ? 3 : (9 * Width() + 127) / 128; }
  uint32_t TriangleLineBytes() const { return 16u * static_cast<uint32_t>(TriangleLineBeats()); }
  int TriangleSlotBits() const { return TrianglesPerLine() == 2 ? 192 : 128 * TriangleLineBeats(); }
  bool TriangleHasId() const { return 9 * Width() + 32 <= TriangleSlotBits(); }
  // Triangle i's line (byte offset within the triangle section) and its bit offset there.
  uint64_t TriangleLineOffset(uint32_t i) const {
    return uint64_t{i / static_cast<uint32_t>(TrianglesPerLine())} * TriangleLineBytes();
  }
  int TriangleBitOffset(uint32_t i) const {
    return static_cast<int>(i % static_cast<uint32_t>(TrianglesPerLine())) * TriangleSlotBits();
  }
  // Bytes of the triangle section for n triangles.
  uint64_t TriangleSectionBytes(uint64_t n) const {
    return (n + TrianglesPerLine() - 1) / TrianglesPerLine() * TriangleLineBytes();
  }
  // The largest above-child index and leaf count the fields hold.
  uint64_t MaxAbove() const { return ChildBits() >= 28 ? kMaxChildIndex : (uint64_t{1} << ChildBits()) - 1; }
  uint64_t MaxFirst() const { return (uint64_t{1} << FirstBits()) - 1; }
  uint64_t MaxCount() const { return CountBits() >= 30 ? kMaxIndex : (uint64_t{1} << CountBits()) - 1; }

  // The index of the p-th node in layout order, and back.
  uint32_t IndexOfPosition(uint32_t p) const {
    return NodesPerBeat() == 3 ? (p / 3) << 2 | (p % 3) : p;
  }
  uint32_t PositionOfIndex(uint32_t i) const { return NodesPerBeat() == 3 ? (i >> 2) * 3 + (i & 3) : i; }
  bool ValidIndex(uint32_t i) const { return NodesPerBeat() != 3 || (i & 3) != 3; }
  uint32_t NextNode(uint32_t i) const { return NodesPerBeat() == 3 && (i & 3) == 2 ? i + 2 : i + 1; }
  // Byte offset of node i's beat within the node section, and its bit offset there.
  uint64_t NodeBeatOffset(uint32_t i) const { return uint64_t{i >> SlotBits()} * 16; }
  int NodeBitOffset(uint32_t i) const { return static_cast<int>(i & ((1u << SlotBits()) - 1)) * NodeBits(); }
  // Bytes of the node section for n nodes.
  uint64_t NodeSectionBytes(uint64_t n) const {
    return NodesPerBeat() == 3 ? (n + 2) / 3 * 16 : n * 8;
  }

  bool IsFp32() const { return e == 8 && m == 23; }
};

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
