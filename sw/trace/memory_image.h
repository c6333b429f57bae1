// Building, validating and reading the memory image (common/image_format.h,
// docs/memory-image.md). The reference tracer and the RTL simulator both read
// the very same bytes produced here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "accel/kdtree.h"
#include "common/image_format.h"
#include "scene/scene.h"
#include "trace/frame.h"

namespace kdrt {

// Deepest tree an image may hold: the reference traversal's stack size.
inline constexpr uint32_t kMaxImageDepth = 128;

// Lays out the header, nodes, leaf lists and triangle records of a scene
// already in its frame (trace/frame.h) and the tree built on it. Throws
// InputError if the image would not fit 32-bit byte offsets.
std::vector<uint8_t> BuildMemoryImage(const Scene& framed, const KdTree& tree, const Frame& frame);

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
class ImageView {
 public:
  ImageView(const uint8_t* data, size_t size, const std::string& name = "memory image");
  explicit ImageView(const std::vector<uint8_t>& bytes, const std::string& name = "memory image")
      : ImageView(bytes.data(), bytes.size(), name) {}

  const img::Header& header() const { return *header_; }
  const img::Node* nodes() const { return nodes_; }
  const uint32_t* lists() const { return lists_; }
  const img::TriangleRecord* triangles() const { return tris_; }
  Frame frame() const;
  const uint8_t* data() const { return data_; }
  size_t size() const { return size_; }

 private:
  const uint8_t* data_;
  size_t size_;
  const img::Header* header_;
  const img::Node* nodes_;
  const uint32_t* lists_;
  const img::TriangleRecord* tris_;
};

}  // namespace kdrt
