#include "trace/memory_image.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "common/error.h"

namespace kdrt {
namespace {

uint64_t AlignUp(uint64_t x) { return (x + img::kSectionAlign - 1) / img::kSectionAlign * img::kSectionAlign; }

}  // namespace

std::vector<uint8_t> BuildMemoryImage(const Scene& scene, const KdTree& tree, const Frame& frame) {
  img::Header h{};
  std::memcpy(h.magic, img::kMagic, sizeof(h.magic));
  h.version = img::kVersion;
  const uint64_t node_offset = AlignUp(img::kHeaderBytes);
  const uint64_t list_offset = AlignUp(node_offset + uint64_t{img::kNodeBytes} * tree.nodes.size());
  const uint64_t tri_offset = AlignUp(list_offset + uint64_t{img::kListEntryBytes} * tree.lists.size());
  const uint64_t total = AlignUp(tri_offset + uint64_t{img::kTriangleBytes} * scene.triangles.size());
  if (total > UINT32_MAX) {
    throw InputError(scene.source, 0,
                     "memory image would be " + std::to_string(total) +
                         " bytes; the image format addresses at most 4 GiB");
  }
  h.total_bytes = static_cast<uint32_t>(total);
  h.node_offset = static_cast<uint32_t>(node_offset);
  h.node_count = static_cast<uint32_t>(tree.nodes.size());
  h.list_offset = static_cast<uint32_t>(list_offset);
  h.list_count = static_cast<uint32_t>(tree.lists.size());
  h.tri_offset = static_cast<uint32_t>(tri_offset);
  h.tri_count = static_cast<uint32_t>(scene.triangles.size());
  h.max_depth = tree.stats.max_depth;
  h.max_leaf_prims = tree.stats.max_leaf_prims;
  for (int i = 0; i < 3; ++i) {
    h.bounds_min[i] = tree.bounds_min[i];
    h.bounds_max[i] = tree.bounds_max[i];
    h.frame_origin[i] = frame.origin[i];
  }
  h.frame_scale_log2 = frame.scale_log2;

  std::vector<uint8_t> bytes(total, 0);
  std::memcpy(bytes.data(), &h, sizeof(h));
  if (!tree.nodes.empty()) {
    std::memcpy(bytes.data() + node_offset, tree.nodes.data(), tree.nodes.size() * img::kNodeBytes);
  }
  if (!tree.lists.empty()) {
    std::memcpy(bytes.data() + list_offset, tree.lists.data(), tree.lists.size() * img::kListEntryBytes);
  }
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    img::TriangleRecord r{};
    for (int k = 0; k < 3; ++k) {
      r.v0[k] = t.v0[k];
      r.v1[k] = t.v1[k];
      r.v2[k] = t.v2[k];
    }
    r.id = static_cast<uint32_t>(i);
    std::memcpy(bytes.data() + tri_offset + i * img::kTriangleBytes, &r, sizeof(r));
  }
  return bytes;
}

FramedImage BuildFramedImage(const Scene& world, const BuildOptions& build) {
  FramedImage out;
  out.frame = ChooseFrame(world);
  const Scene framed = ToFrame(world, out.frame);
  out.tree = BuildKdTree(framed, build);
  out.bytes = BuildMemoryImage(framed, out.tree, out.frame);
  return out;
}

Frame ImageView::frame() const {
  Frame f;
  for (int i = 0; i < 3; ++i) f.origin[i] = header_->frame_origin[i];
  f.scale_log2 = header_->frame_scale_log2;
  return f;
}

ImageView::ImageView(const uint8_t* data, size_t size, const std::string& name)
    : data_(data), size_(size) {
  auto fail = [&](const std::string& what) { throw InputError(name, 0, what); };
  if (size < img::kHeaderBytes) fail("too small for a kdrt memory image header");
  header_ = reinterpret_cast<const img::Header*>(data);
  const img::Header& h = *header_;
  if (std::memcmp(h.magic, img::kMagic, sizeof(h.magic)) != 0) fail("not a kdrt memory image (bad magic)");
  if (h.version != img::kVersion) {
    fail("memory image version " + std::to_string(h.version) + ", this build reads version " +
         std::to_string(img::kVersion));
  }
  if (h.total_bytes != size) fail("header says " + std::to_string(h.total_bytes) + " bytes, have " + std::to_string(size));
  auto check_section = [&](uint64_t off, uint64_t count, uint64_t elem, const char* what) {
    if (off % img::kSectionAlign != 0 || off < img::kHeaderBytes || off + count * elem > size) {
      fail(std::string(what) + " section out of bounds or misaligned");
    }
  };
  check_section(h.node_offset, h.node_count, img::kNodeBytes, "node");
  check_section(h.list_offset, h.list_count, img::kListEntryBytes, "leaf list");
  check_section(h.tri_offset, h.tri_count, img::kTriangleBytes, "triangle");
  if (h.node_count == 0) fail("no root node");
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(h.frame_origin[i])) fail("frame origin is not finite");
  }
  if (h.frame_scale_log2 < -kMaxFrameScaleLog2 || h.frame_scale_log2 > kMaxFrameScaleLog2) {
    fail("frame scale 2^" + std::to_string(h.frame_scale_log2) + " out of range");
  }
  nodes_ = reinterpret_cast<const img::Node*>(data + h.node_offset);
  lists_ = reinterpret_cast<const uint32_t*>(data + h.list_offset);
  tris_ = reinterpret_cast<const img::TriangleRecord*>(data + h.tri_offset);
  for (uint32_t i = 0; i < h.node_count; ++i) {
    const img::Node& n = nodes_[i];
    if (n.IsLeaf()) {
      if (uint64_t{n.FirstEntry()} + n.Count() > h.list_count) fail("node " + std::to_string(i) + ": leaf list out of range");
    } else if (i + 1 >= h.node_count || n.AboveChild() <= i || n.AboveChild() >= h.node_count) {
      // Children after their parent also rules out cycles.
      fail("node " + std::to_string(i) + ": child index out of range");
    } else if (!std::isfinite(n.Split())) {
      fail("node " + std::to_string(i) + ": split position is not finite");
    }
  }
  // Children come after their parents, so one forward pass finds every
  // node's depth; the header's max_depth sizes the hardware's stack and must
  // be the truth.
  std::vector<uint32_t> depth(h.node_count, 0);
  uint32_t max_depth = 0;
  for (uint32_t i = 0; i < h.node_count; ++i) {
    max_depth = std::max(max_depth, depth[i]);
    if (!nodes_[i].IsLeaf()) {
      depth[i + 1] = std::max(depth[i + 1], depth[i] + 1);
      depth[nodes_[i].AboveChild()] = std::max(depth[nodes_[i].AboveChild()], depth[i] + 1);
    }
  }
  if (max_depth != h.max_depth) {
    fail("header says max depth " + std::to_string(h.max_depth) + ", the tree is " + std::to_string(max_depth) +
         " deep");
  }
  if (max_depth >= kMaxImageDepth) {
    fail("tree is " + std::to_string(max_depth) + " levels deep; at most " + std::to_string(kMaxImageDepth - 1) +
         " are supported");
  }
  for (uint32_t i = 0; i < h.list_count; ++i) {
    if (lists_[i] >= h.tri_count) fail("leaf list entry " + std::to_string(i) + ": triangle id out of range");
  }
}

}  // namespace kdrt
