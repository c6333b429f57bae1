// Building, validating and reading the memory image (common/image_format.h,
// docs/memory-image.md). The reference tracer and the RTL simulator both read
// the very same bytes produced here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "accel/kdtree.h"
#include "common/image_format.h"
#include "fp/format.h"
#include "scene/scene.h"
#include "trace/frame.h"

namespace kdrt {

// Deepest tree an image may hold: the reference traversal's stack size.
inline constexpr uint32_t kMaxImageDepth = 128;

// Lays out the header, nodes, leaf lists and triangle records of a scene
// already in its frame (trace/frame.h) and the tree built on it, with splits
// and vertices in `layout`'s number format (binary32 by default). Throws
// InputError if the image would not fit 32-bit byte offsets or the tree
// would not fit the layout's node fields.
std::vector<uint8_t> BuildMemoryImage(const Scene& framed, const KdTree& tree, const Frame& frame,
                                      const img::ImageLayout& layout = img::ImageLayout{});

// The image layout of a datapath format: its own (packed) one; binary32 for
// fp64, which reads the fp32 image. Throws InputError for a format with no
// encoding.
img::ImageLayout LayoutFor(const fp::Format& format);

// The whole way from a scene in world coordinates: its frame, the scene in
// the frame, the kd-tree built on that, the image.
struct FramedImage {
  Frame frame;
  KdTree tree;  // over the framed scene
  std::vector<uint8_t> bytes;
};
FramedImage BuildFramedImage(const Scene& world, const BuildOptions& build);

// A validated, typed view of an image held elsewhere. Construction checks the
// magic, version, section bounds and every node's child/list references, so a
// traversal over a view can never read outside the image.
class ImageView;
// The same tree and triangles as a validated fp32 image, stored in
// `layout`'s format: every split and coordinate rounded once, as a datapath
// of that format rounds what it loads from the fp32 image, so a trace in
// that format sees the same values (and hits) from either image.
std::vector<uint8_t> RepackImage(const ImageView& fp32, const img::ImageLayout& layout);

class ImageView {
 public:
  ImageView(const uint8_t* data, size_t size, const std::string& name = "memory image");
  explicit ImageView(const std::vector<uint8_t>& bytes, const std::string& name = "memory image")
      : ImageView(bytes.data(), bytes.size(), name) {}

  const img::Header& header() const { return *header_; }
  const img::ImageLayout& layout() const { return layout_; }
  // Node i (a slot index, docs/memory-image.md) in the fp32 form: a packed
  // split widened to binary32 (exact), indices as stored.
  img::Node node(uint32_t i) const { return packed_ ? DecodeNode(i) : nodes_[i]; }
  // The below child of inner node i.
  uint32_t next(uint32_t i) const { return layout_.NextNode(i); }
  // Triangle `id` with its vertices widened to binary32 (exact).
  img::TriangleRecord triangle(uint32_t id) const { return packed_ ? DecodeTriangle(id) : tris_[id]; }
  const uint32_t* lists() const { return lists_; }
  // fp32 images only: the nodes and triangle records as stored.
  const img::Node* raw_nodes() const { return packed_ ? nullptr : nodes_; }
  const img::TriangleRecord* raw_triangles() const { return packed_ ? nullptr : tris_; }
  Frame frame() const;
  const uint8_t* data() const { return data_; }
  size_t size() const { return size_; }

 private:
  img::Node DecodeNode(uint32_t i) const;
  img::TriangleRecord DecodeTriangle(uint32_t id) const;

  img::ImageLayout layout_;
  bool packed_ = false;
  const uint8_t* data_;
  size_t size_;
  const img::Header* header_;
  const img::Node* nodes_;
  const uint32_t* lists_;
  const img::TriangleRecord* tris_;
};

}  // namespace kdrt
