#include "trace/memory_image.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "common/error.h"
#include "fp/format.h"

namespace kdrt {
namespace {

uint64_t AlignUp(uint64_t x) { return (x + img::kSectionAlign - 1) / img::kSectionAlign * img::kSectionAlign; }

// Little-endian bit fields of up to 64 bits at any bit offset, a byte (or
// the part of one in the field) at a time; only the field's bytes are read
// or written.
uint64_t GetBits(const uint8_t* p, uint64_t bit, int n) {
  uint64_t v = 0;
  for (int got = 0; got < n;) {
    const uint64_t b = bit + static_cast<uint64_t>(got);
    const int off = static_cast<int>(b & 7);
    const int take = std::min(8 - off, n - got);
    v |= uint64_t{(p[b >> 3] >> off) & ((1u << take) - 1u)} << got;
    got += take;
  }
  return v;
}

// A copy of up to N bytes of a beat or a line with 8 zero bytes after it, so
// that any field of at most 57 bits starting in it is one unaligned 64-bit
// load and a shift (GetBits a byte at a time was most of decoding, and the
// decoding a tenth of a packed format's trace).
template <size_t N>
class PaddedCopy {
 public:
  explicit PaddedCopy(const uint8_t* p, size_t n = N) { std::memcpy(bytes_, p, std::min(n, N)); }
  uint64_t Bits(uint64_t bit, int n) const {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    if (n <= 57) {
      uint64_t v;
      std::memcpy(&v, bytes_ + (bit >> 3), sizeof v);
      return (v >> (bit & 7)) & ((uint64_t{1} << n) - 1);
    }
#endif
    return GetBits(bytes_, bit, n);
  }

 private:
  uint8_t bytes_[N + 8] = {};
};

// Writes the low n bits of v at bit `bit`. The 8 bytes from bit / 8 must be
// inside the buffer (BuildMemoryImage pads its buffer while it writes): a
// field of at most 57 bits is then one unaligned 64-bit read-modify-write.
void SetBits(uint8_t* p, uint64_t bit, int n, uint64_t v) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  if (n <= 57) {
    const uint64_t mask = ((uint64_t{1} << n) - 1) << (bit & 7);
    uint64_t word;
    std::memcpy(&word, p + (bit >> 3), sizeof word);
    word = (word & ~mask) | ((v << (bit & 7)) & mask);
    std::memcpy(p + (bit >> 3), &word, sizeof word);
    return;
  }
#endif
  for (int put = 0; put < n;) {
    const uint64_t b = bit + static_cast<uint64_t>(put);
    const int off = static_cast<int>(b & 7);
    const int take = std::min(8 - off, n - put);
    const unsigned mask = ((1u << take) - 1u) << off;
    const unsigned field = static_cast<unsigned>((v >> put) << off) & mask;
    p[b >> 3] = static_cast<uint8_t>((p[b >> 3] & ~mask) | field);
    put += take;
  }
}

// A coordinate as the image stores it: binary32 bits as they are in an fp32
// image (the datapath's load does the rounding, as before version 3), else
// rounded once to the format, exactly as the datapath's load would.
uint32_t StoredBits(const img::ImageLayout& layout, float x) {
  return layout.IsFp32() ? fp::BitsOf(x) : fp::FromFloat(fp::Format{layout.e, layout.m}, x);
}

float LoadedFloat(const img::ImageLayout& layout, uint32_t bits) {
  return layout.IsFp32() ? fp::FloatOf(bits) : fp::ToFloat(fp::Format{layout.e, layout.m}, bits);
}

}  // namespace

img::ImageLayout LayoutFor(const fp::Format& format) {
  if (format.IsFp64()) return img::ImageLayout{};
  fp::MakeFormat(format.e, format.m);  // throws for a format with no encoding
  return img::ImageLayout{format.e, format.m};
}

std::vector<uint8_t> BuildMemoryImage(const Scene& scene, const KdTree& tree, const Frame& frame,
                                      const img::ImageLayout& layout) {
  img::Header h{};
  std::memcpy(h.magic, img::kMagic, sizeof(h.magic));
  h.version = img::kVersion;
  h.format_e = static_cast<uint32_t>(layout.e);
  h.format_m = static_cast<uint32_t>(layout.m);
  const uint64_t node_offset = AlignUp(img::kHeaderBytes);
  const uint64_t list_offset = AlignUp(node_offset + layout.NodeSectionBytes(tree.nodes.size()));
  const uint64_t tri_offset = AlignUp(list_offset + uint64_t{img::kListEntryBytes} * tree.lists.size());
  const uint64_t total = AlignUp(tri_offset + layout.TriangleSectionBytes(scene.triangles.size()));
  if (total > UINT32_MAX) {
    throw InputError(scene.source, 0,
                     "memory image would be " + std::to_string(total) +
                         " bytes; the image format addresses at most 4 GiB");
  }
  const std::string fmt_name = fp::Format{layout.e, layout.m}.Name();
  if (!tree.nodes.empty() && layout.IndexOfPosition(static_cast<uint32_t>(tree.nodes.size() - 1)) > layout.MaxAbove()) {
    throw InputError(scene.source, 0,
                     std::to_string(tree.nodes.size()) + " kd-tree nodes do not fit the " +
                         std::to_string(std::min(layout.ChildBits(), 28)) + "-bit child index of a " + fmt_name +
                         " image node (docs/memory-image.md)");
  }
  if (tree.lists.size() > layout.MaxFirst() + 1) {
    throw InputError(scene.source, 0,
                     std::to_string(tree.lists.size()) + " leaf list entries do not fit the " +
                         std::to_string(layout.FirstBits()) + "-bit first-entry field of a " + fmt_name +
                         " image node (docs/memory-image.md)");
  }
  if (tree.stats.max_leaf_prims > layout.MaxCount()) {
    throw InputError(scene.source, 0,
                     "a leaf of " + std::to_string(tree.stats.max_leaf_prims) + " triangles does not fit the " +
                         std::to_string(layout.CountBits()) + "-bit count of a " + fmt_name +
                         " image node (docs/memory-image.md)");
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
  // A packed image holds the scene box as the format rounds it, like the
  // splits and vertices: a datapath wider than the image (--image-format)
  // loads it exactly and clips to the box of the stored triangles (rounding
  // is monotone, so they stay inside). A datapath of the image's own format
  // loads the same value from either.
  for (int i = 0; i < 3; ++i) {
    h.bounds_min[i] = LoadedFloat(layout, StoredBits(layout, tree.bounds_min[i]));
    h.bounds_max[i] = LoadedFloat(layout, StoredBits(layout, tree.bounds_max[i]));
    h.frame_origin[i] = frame.origin[i];
  }
  h.frame_scale_log2 = frame.scale_log2;

  // 8 bytes of padding for SetBits while the image is written, cut below.
  std::vector<uint8_t> bytes(total + 8, 0);
  std::memcpy(bytes.data(), &h, sizeof(h));
  // tree.nodes is in layout order with positions as indices (img::Node,
  // binary32 splits); each goes to its slot with its indices re-encoded and
  // an inner node's empty children marked.
  const int w = layout.Width();
  const auto empty_leaf = [&tree](uint32_t p) { return tree.nodes[p].IsLeaf() && tree.nodes[p].Count() == 0; };
  for (size_t p = 0; p < tree.nodes.size(); ++p) {
    const img::Node& n = tree.nodes[p];
    const uint32_t index = layout.IndexOfPosition(static_cast<uint32_t>(p));
    uint8_t* beat = bytes.data() + node_offset + layout.NodeBeatOffset(index);
    const uint64_t at = static_cast<uint64_t>(layout.NodeBitOffset(index));
    if (n.IsLeaf()) {
      const uint64_t payload = uint64_t{n.FirstEntry()} | uint64_t{n.Count()} << layout.FirstBits();
      SetBits(beat, at, w, payload);
      SetBits(beat, at + w, 2, img::kLeaf);
      SetBits(beat, at + w + 2, layout.AboveBits(), payload >> w);
    } else {
      SetBits(beat, at, w, StoredBits(layout, n.Split()));
      SetBits(beat, at + w, 2, static_cast<uint64_t>(n.Axis()));
      SetBits(beat, at + w + 2, layout.ChildBits(), layout.IndexOfPosition(n.AboveChild()));
      const uint64_t marks =
          uint64_t{empty_leaf(static_cast<uint32_t>(p) + 1)} | uint64_t{empty_leaf(n.AboveChild())} << 1;
      SetBits(beat, at + w + 2 + layout.ChildBits(), 2, marks);
    }
  }
  if (!tree.lists.empty()) {
    std::memcpy(bytes.data() + list_offset, tree.lists.data(), tree.lists.size() * img::kListEntryBytes);
  }
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    uint8_t* line = bytes.data() + tri_offset + layout.TriangleLineOffset(static_cast<uint32_t>(i));
    const uint64_t at = static_cast<uint64_t>(layout.TriangleBitOffset(static_cast<uint32_t>(i)));
    const glm::vec3* v[3] = {&t.v0, &t.v1, &t.v2};
    for (int k = 0; k < 9; ++k) SetBits(line, at + k * w, w, StoredBits(layout, (*v[k / 3])[k % 3]));
    if (layout.TriangleHasId()) SetBits(line, at + 9ull * w, 32, static_cast<uint32_t>(i));
  }
  bytes.resize(total);
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

std::vector<uint8_t> RepackImage(const ImageView& fp32, const img::ImageLayout& layout) {
  const img::Header& h = fp32.header();
  if (!fp32.layout().IsFp32()) throw InputError("memory image", 0, "only an fp32 image can be repacked");
  // Rebuild the inputs of BuildMemoryImage from the fp32 image: the nodes in
  // position order, the lists, the triangles.
  Scene scene;
  scene.source = "memory image";
  scene.triangles.resize(h.tri_count);
  for (uint32_t i = 0; i < h.tri_count; ++i) {
    const img::TriangleRecord r = fp32.triangle(i);
    for (int k = 0; k < 3; ++k) {
      scene.triangles[i].v0[k] = r.v0[k];
      scene.triangles[i].v1[k] = r.v1[k];
      scene.triangles[i].v2[k] = r.v2[k];
    }
  }
  KdTree tree;
  tree.nodes.assign(fp32.raw_nodes(), fp32.raw_nodes() + h.node_count);
  tree.lists.assign(fp32.lists(), fp32.lists() + h.list_count);
  tree.stats.max_depth = h.max_depth;
  tree.stats.max_leaf_prims = h.max_leaf_prims;
  for (int i = 0; i < 3; ++i) {
    tree.bounds_min[i] = h.bounds_min[i];
    tree.bounds_max[i] = h.bounds_max[i];
  }
  return BuildMemoryImage(scene, tree, fp32.frame(), layout);
}

img::Node ImageView::DecodeNode(uint32_t i) const {
  const PaddedCopy<16> beat(data_ + header_->node_offset + layout_.NodeBeatOffset(i));
  const uint64_t at = static_cast<uint64_t>(layout_.NodeBitOffset(i));
  const int w = layout_.Width();
  const uint64_t lo = beat.Bits(at, w);
  const uint32_t tag = static_cast<uint32_t>(beat.Bits(at + w, 2));
  const uint64_t hi = beat.Bits(at + w + 2, layout_.AboveBits());
  if (tag == img::kLeaf) {
    const uint64_t payload = hi << w | lo;
    const uint64_t first = payload & layout_.MaxFirst();
    const uint64_t count = payload >> layout_.FirstBits();
    return img::Node::Leaf(static_cast<uint32_t>(first), static_cast<uint32_t>(count));
  }
  const uint64_t above = hi & ((uint64_t{1} << layout_.ChildBits()) - 1);
  const uint64_t marks = hi >> layout_.ChildBits();
  return img::Node::Inner(static_cast<int>(tag), LoadedFloat(layout_, static_cast<uint32_t>(lo)),
                          static_cast<uint32_t>(above))
      .WithEmptyChildren((marks & 1u) != 0, (marks & 2u) != 0);
}

img::TriangleRecord ImageView::DecodeTriangle(uint32_t id) const {
  const PaddedCopy<48> line(data_ + header_->tri_offset + layout_.TriangleLineOffset(id),
                            layout_.TriangleLineBytes());
  const uint64_t at = static_cast<uint64_t>(layout_.TriangleBitOffset(id));
  const int w = layout_.Width();
  img::TriangleRecord r{};
  float* v[3] = {r.v0, r.v1, r.v2};
  for (int k = 0; k < 9; ++k) {
    v[k / 3][k % 3] = LoadedFloat(layout_, static_cast<uint32_t>(line.Bits(at + k * w, w)));
  }
  // A record without room for its id (img::ImageLayout) reads as its index.
  r.id = layout_.TriangleHasId() ? static_cast<uint32_t>(line.Bits(at + 9ull * w, 32)) : id;
  return r;
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
  if (h.format_e < 2 || h.format_e > 8 || h.format_m < 1 || h.format_m > 23) {
    fail("number format e" + std::to_string(h.format_e) + "m" + std::to_string(h.format_m) +
         " is not one an image can hold (2 <= e <= 8, 1 <= m <= 23)");
  }
  layout_ = img::ImageLayout{static_cast<int>(h.format_e), static_cast<int>(h.format_m)};
  for (uint32_t r : h.reserved) {
    if (r != 0) fail("reserved header words are not zero");
  }
  auto check_section = [&](uint64_t off, uint64_t count, uint64_t elem, const char* what) {
    if (off % img::kSectionAlign != 0 || off < img::kHeaderBytes || off + count * elem > size) {
      fail(std::string(what) + " section out of bounds or misaligned");
    }
  };
  check_section(h.node_offset, layout_.NodeSectionBytes(h.node_count), 1, "node");
  check_section(h.list_offset, h.list_count, img::kListEntryBytes, "leaf list");
  check_section(h.tri_offset, layout_.TriangleSectionBytes(h.tri_count), 1, "triangle");
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
  packed_ = !layout_.IsFp32();
  // Node i in position order p; children must come after their parent
  // (which also rules out cycles) and name a slot that holds a node.
  const uint32_t last = layout_.IndexOfPosition(h.node_count - 1);
  auto valid_child = [&](uint32_t parent, uint32_t child) {
    return child > parent && child <= last && layout_.ValidIndex(child);
  };
  std::vector<uint32_t> depth(h.node_count, 0);
  uint32_t max_depth = 0;
  for (uint32_t p = 0; p < h.node_count; ++p) {
    const uint32_t i = layout_.IndexOfPosition(p);
    const img::Node n = node(i);
    max_depth = std::max(max_depth, depth[p]);
    if (n.IsLeaf()) {
      if (uint64_t{n.FirstEntry()} + n.Count() > h.list_count) fail("node " + std::to_string(i) + ": leaf list out of range");
      continue;
    }
    if (!valid_child(i, next(i)) || !valid_child(i, n.AboveChild())) {
      fail("node " + std::to_string(i) + ": child index out of range");
    }
    // The hardware skips a child marked empty without reading it: the marks
    // must be exactly the children that are empty leaves.
    const auto empty_leaf = [this](uint32_t c) {
      const img::Node child = node(c);
      return child.IsLeaf() && child.Count() == 0;
    };
    if (n.BelowEmpty() != empty_leaf(next(i)) || n.AboveEmpty() != empty_leaf(n.AboveChild())) {
      fail("node " + std::to_string(i) + ": its empty-child marks do not match its children");
    }
    // An fp32 split is finite; a packed one may have overflowed to an
    // infinity (a format too narrow for the scene: a warned case, traced as
    // the load from the fp32 image would), never NaN.
    if (layout_.IsFp32() ? !std::isfinite(n.Split()) : std::isnan(n.Split())) {
      fail("node " + std::to_string(i) + ": split position is not finite");
    }
    // Children come after their parents, so one forward pass finds every
    // node's depth; the header's max_depth sizes the hardware's stack and
    // must be the truth.
    for (uint32_t c : {next(i), n.AboveChild()}) {
      uint32_t& d = depth[layout_.PositionOfIndex(c)];
      d = std::max(d, depth[p] + 1);
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
