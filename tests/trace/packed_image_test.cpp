// Memory images in a format's own width (docs/memory-image.md, "Packed
// formats"): the layout rule, the stored values, the same hits as from the
// fp32 image in every format, and the errors for what does not fit.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "common/error.h"
#include "fp/format.h"
#include "tests/common/test_cores.h"
#include "trace_test_util.h"

namespace kdrt {
namespace {

using testing::Prepared;

std::vector<fp::Format> FormatsUnderTest() {
  std::vector<fp::Format> f = fp::Presets();
  for (const char* name : {"e5m7", "e6m9", "e4m3", "e8m15", "e2m1"}) f.push_back(fp::ParseFormat(name));
  return f;
}

TEST(PackedImage, LayoutOfThePresets) {
  struct Want {
    fp::Format f;
    int nodes_per_beat, node_bits, above_bits, count_bits, line_bytes, per_line;
    bool id;
  };
  // W > 16: two 64-bit nodes per beat; W <= 16: three of 42 bits. A
  // triangle line takes the beats its 9 W-bit coordinates need, or holds two
  // records in 3 beats where one would take 2 (15 <= W <= 21); the id goes
  // where it fits.
  for (const Want& w :
       {Want{fp::kFp32, 2, 64, 30, 30, 48, 1, true}, Want{fp::kFp24, 2, 64, 38, 30, 32, 1, true},
        Want{fp::kBf16, 3, 42, 24, 16, 48, 2, true}, Want{fp::kFp16, 3, 42, 24, 16, 48, 2, true},
        Want{fp::ParseFormat("e5m7"), 3, 42, 27, 16, 16, 1, false},
        Want{fp::ParseFormat("e4m3"), 3, 42, 32, 16, 16, 1, true}}) {
    const img::ImageLayout l = LayoutFor(w.f);
    EXPECT_EQ(l.NodesPerBeat(), w.nodes_per_beat) << w.f.Name();
    EXPECT_EQ(l.NodeBits(), w.node_bits) << w.f.Name();
    EXPECT_EQ(l.AboveBits(), w.above_bits) << w.f.Name();
    EXPECT_EQ(l.CountBits(), w.count_bits) << w.f.Name();
    EXPECT_EQ(l.TriangleLineBytes(), static_cast<uint32_t>(w.line_bytes)) << w.f.Name();
    EXPECT_EQ(l.TrianglesPerLine(), w.per_line) << w.f.Name();
    EXPECT_EQ(l.TriangleHasId(), w.id) << w.f.Name();
    EXPECT_LE(l.NodesPerBeat() * l.NodeBits(), 128) << w.f.Name();
    EXPECT_LE(9 * l.Width() + (w.id ? 32 : 0), l.TriangleSlotBits()) << w.f.Name();
    EXPECT_LE(l.TrianglesPerLine() * l.TriangleSlotBits(), 8 * static_cast<int>(l.TriangleLineBytes())) << w.f.Name();
    EXPECT_EQ(l.TriangleSectionBytes(5), (5 + w.per_line - 1) / w.per_line * uint64_t(w.line_bytes)) << w.f.Name();
  }
  // fp64 traces the fp32 image.
  EXPECT_TRUE(LayoutFor(fp::kFp64).IsFp32());
}

TEST(PackedImage, SlotIndicesSkipTheFourthSlotOfABeat) {
  const img::ImageLayout l = LayoutFor(fp::kFp16);
  for (uint32_t p = 0; p < 1000; ++p) {
    const uint32_t i = l.IndexOfPosition(p);
    EXPECT_TRUE(l.ValidIndex(i));
    EXPECT_EQ(l.PositionOfIndex(i), p);
    EXPECT_EQ(l.NextNode(i), l.IndexOfPosition(p + 1)) << p;
    EXPECT_EQ(l.NodeBeatOffset(i), uint64_t{p / 3} * 16);
    EXPECT_EQ(l.NodeBitOffset(i), static_cast<int>(p % 3) * 42);
  }
  const img::ImageLayout l32 = LayoutFor(fp::kFp32);
  for (uint32_t p = 0; p < 100; ++p) {
    EXPECT_EQ(l32.IndexOfPosition(p), p);
    EXPECT_EQ(l32.NodeBeatOffset(p) + static_cast<uint64_t>(l32.NodeBitOffset(p) / 8), uint64_t{p} * img::kNodeBytes);
  }
}

TEST(PackedImage, Fp32LayoutIsTheFp32RecordsByteForByte) {
  Prepared p(GenerateScene("balls", 2000));
  const ImageView v = p.view();
  EXPECT_TRUE(v.layout().IsFp32());
  EXPECT_EQ(RepackImage(v, img::ImageLayout{}), p.bytes);
  // The nodes and triangles are img::Node and img::TriangleRecord as stored.
  const img::Header& h = v.header();
  // An inner node marks its children that are empty leaves (the tree's own
  // nodes leave the marks zero).
  const auto& nodes = p.image.tree.nodes;
  const auto empty_leaf = [&nodes](uint32_t c) { return nodes[c].IsLeaf() && nodes[c].Count() == 0; };
  uint32_t marked = 0;
  for (uint32_t i = 0; i < h.node_count; ++i) {
    img::Node n = nodes[i];
    if (!n.IsLeaf()) {
      n = n.WithEmptyChildren(empty_leaf(i + 1), empty_leaf(n.AboveChild()));
      marked += n.BelowEmpty() + n.AboveEmpty();
    }
    ASSERT_EQ(std::memcmp(p.bytes.data() + h.node_offset + 8ull * i, &n, 8), 0) << i;
  }
  EXPECT_GT(marked, 0u);
  for (uint32_t t = 0; t < h.tri_count; ++t) {
    img::TriangleRecord r;
    std::memcpy(&r, p.bytes.data() + h.tri_offset + 48ull * t, 48);
    ASSERT_EQ(r.id, t);
    ASSERT_EQ(r.pad[0] | r.pad[1], 0u);
  }
}

// fp16 and bf16 put two records in a 3-beat line (image version 4), so their
// triangles take half of fp32's bytes, the second record of a line at bit
// 192 (its own id there too); an odd count leaves one slot of the last line zero.
TEST(PackedImage, Fp16TrianglesTakeHalfOfFp32sBytes) {
  Prepared p(GenerateScene("balls", 2000));
  const ImageView fp32 = p.view();
  const uint32_t n = fp32.header().tri_count;
  for (const fp::Format& f : {fp::kFp16, fp::kBf16}) {
    const img::ImageLayout l = LayoutFor(f);
    const std::vector<uint8_t> bytes = RepackImage(fp32, l);
    const ImageView v(bytes);
    const uint64_t fp32_tris = uint64_t{n} * img::kTriangleBytes;
    EXPECT_EQ(l.TriangleSectionBytes(n), (n + 1) / 2 * 48ull) << f.Name();
    EXPECT_LE(2 * l.TriangleSectionBytes(n), fp32_tris + 48) << f.Name();
    EXPECT_LT(bytes.size(), p.bytes.size() * 2 / 3) << f.Name();
    const uint8_t* tris = bytes.data() + v.header().tri_offset;
    for (uint32_t t = 0; t < n; ++t) {
      uint32_t id;
      std::memcpy(&id, tris + 48ull * (t / 2) + 24 * (t % 2) + 18, 4);
      ASSERT_EQ(id, t) << f.Name();
    }
    if (n % 2 == 1) {
      for (int k = 24; k < 48; ++k) ASSERT_EQ(tris[48ull * (n / 2) + k], 0) << f.Name();
    }
  }
}

// Every split and coordinate is the fp32 image's rounded once to the format
// (what the datapath's load computes), the structure is the same tree.
TEST(PackedImage, StoresTheRoundedValuesOfTheFp32Image) {
  Prepared p(GenerateScene("tetra", 3000));
  const ImageView fp32 = p.view();
  for (const fp::Format& f : FormatsUnderTest()) {
    const img::ImageLayout l = LayoutFor(f);
    const std::vector<uint8_t> bytes = RepackImage(fp32, l);
    const ImageView v(bytes);
    ASSERT_EQ(v.header().node_count, fp32.header().node_count);
    for (uint32_t pos = 0; pos < v.header().node_count; ++pos) {
      const img::Node want = p.image.tree.nodes[pos];
      const img::Node got = v.node(l.IndexOfPosition(pos));
      ASSERT_EQ(got.IsLeaf(), want.IsLeaf()) << f.Name() << " node " << pos;
      if (want.IsLeaf()) {
        ASSERT_EQ(got.FirstEntry(), want.FirstEntry());
        ASSERT_EQ(got.Count(), want.Count());
      } else {
        ASSERT_EQ(got.Axis(), want.Axis());
        ASSERT_EQ(got.AboveChild(), l.IndexOfPosition(want.AboveChild()));
        const float rounded = fp::ToFloat(f, fp::FromFloat(f, want.Split()));
        const float split = got.Split();
        ASSERT_EQ(std::memcmp(&split, &rounded, 4), 0) << f.Name() << " node " << pos;
      }
    }
    for (uint32_t t = 0; t < v.header().tri_count; ++t) {
      const img::TriangleRecord want = fp32.triangle(t), got = v.triangle(t);
      ASSERT_EQ(got.id, t);
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(got.v0[k], fp::ToFloat(f, fp::FromFloat(f, want.v0[k])));
        ASSERT_EQ(got.v1[k], fp::ToFloat(f, fp::FromFloat(f, want.v1[k])));
        ASSERT_EQ(got.v2[k], fp::ToFloat(f, fp::FromFloat(f, want.v2[k])));
      }
    }
  }
}

// A packed image stores the scene box as it stores the vertices, rounded to
// its format, so every stored triangle lies inside the stored box: a datapath
// wider than the image (--image-format) clips to the box of the triangles it
// reads. (With the fp32 box, a floor on the box's face rounded outside it and
// an fp32 datapath reading the fp16 image of gen:rings lost half its hits.)
TEST(PackedImage, StoredBoxHoldsTheStoredTriangles) {
  for (const std::string& gen : GeneratorNames()) {
    Prepared p(GenerateScene(gen, 1500));
    for (const fp::Format& f : FormatsUnderTest()) {
      if (f.e < 4) continue;  // the frame's coordinates overflow: every value is infinite
      const std::vector<uint8_t> bytes = RepackImage(p.view(), LayoutFor(f));
      const ImageView v(bytes);
      const img::Header& h = v.header();
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(h.bounds_min[a], fp::ToFloat(f, fp::FromFloat(f, p.view().header().bounds_min[a])))
            << gen << " " << f.Name();
        EXPECT_EQ(h.bounds_max[a], fp::ToFloat(f, fp::FromFloat(f, p.view().header().bounds_max[a])))
            << gen << " " << f.Name();
      }
      size_t outside = 0;
      for (uint32_t t = 0; t < h.tri_count; ++t) {
        const img::TriangleRecord r = v.triangle(t);
        for (const float* vert : {r.v0, r.v1, r.v2}) {
          for (int a = 0; a < 3; ++a) outside += vert[a] < h.bounds_min[a] || vert[a] > h.bounds_max[a];
        }
      }
      EXPECT_EQ(outside, 0u) << gen << " " << f.Name();
    }
  }
}

// The reference tracer in format F gives the same records, and makes the same
// fetches, from F's packed image as from the fp32 image: the packing is the
// rounding the load did before. 16x16 camera rays and 256 from inside the
// scene per generator and format; KDRT_LONG=1: 48x48 and 1500.
TEST(PackedImage, SameHitsAsTheFp32ImageInEveryFormat) {
  const bool long_run = testing::LongRun();
  for (const std::string& gen : GeneratorNames()) {
    Prepared p(GenerateScene(gen, 1500));
    const ImageView fp32 = p.view();
    std::vector<Ray> rays = testing::CameraRays(p.scene, long_run ? 48 : 16);
    std::mt19937 rng(5);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    for (int i = 0; i < (long_run ? 1500 : 256); ++i) {  // from inside the scene, every direction
      const Ray& c = rays[static_cast<size_t>(i) % rays.size()];
      Ray r = c;
      r.o = c.o + c.d * (0.5f + std::abs(gauss(rng)));
      r.d = glm::vec3(gauss(rng), gauss(rng), gauss(rng));
      rays.push_back(r);
    }
    for (const fp::Format& f : FormatsUnderTest()) {
      const img::ImageLayout l = LayoutFor(f);
      const std::vector<uint8_t> bytes = RepackImage(fp32, l);
      if (l.Width() < 32) {
        EXPECT_LT(bytes.size(), p.bytes.size()) << gen << " " << f.Name();
      }
      TraceOptions to;
      to.format = f;
      TraceStats from_fp32, from_packed;
      const std::vector<Hit> a = TraceRays(fp32, rays, to, &from_fp32);
      const std::vector<Hit> b = TraceRays(ImageView(bytes), rays, to, &from_packed);
      size_t differ = 0, first = 0;
      for (size_t i = 0; i < rays.size(); ++i) {
        if (!testing::SameBits(a[i], b[i]) && differ++ == 0) first = i;
      }
      EXPECT_EQ(differ, 0u) << gen << " " << f.Name() << ": first at ray " << first;
      EXPECT_EQ(from_packed.totals.nodes, from_fp32.totals.nodes) << gen << " " << f.Name();
      EXPECT_EQ(from_packed.totals.tri_tests, from_fp32.totals.tri_tests) << gen << " " << f.Name();
      // e2m1 cannot hold the frame's coordinates (they overflow): it hits
      // nothing, but from both images alike.
      if (f.e >= 4) {
        EXPECT_GT(from_fp32.hits, 0u) << gen << " " << f.Name();
      }
    }
  }
}

TEST(PackedImage, ALeafLargerThanTheCountFieldIsRefused) {
  Scene scene;
  scene.source = "big-leaf";
  scene.triangles.resize(1);
  scene.triangles[0].v1 = glm::vec3(1, 0, 0);
  scene.triangles[0].v2 = glm::vec3(0, 1, 0);
  KdTree tree;
  tree.lists.assign(70000, 0);  // one leaf naming triangle 0 70,000 times
  tree.nodes.push_back(img::Node::Leaf(0, 70000));
  tree.stats.max_leaf_prims = 70000;
  tree.bounds_max = glm::vec3(1, 1, 0);
  EXPECT_NO_THROW(ImageView(BuildMemoryImage(scene, tree, Frame{})));
  try {
    BuildMemoryImage(scene, tree, Frame{}, LayoutFor(fp::kFp16));
    FAIL() << "a 70,000-triangle leaf fit a 16-bit count";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("16-bit count of a fp16 image node"), std::string::npos) << e.what();
  }
}

TEST(PackedImage, RejectsCorruptPackedImages) {
  Prepared p(GenerateScene("tetra", 500));
  const std::vector<uint8_t> good = RepackImage(p.view(), LayoutFor(fp::kFp16));
  EXPECT_NO_THROW(ImageView{good});
  auto corrupt = [&](auto mutate) {
    std::vector<uint8_t> b = good;
    mutate(b);
    return b;
  };
  auto header = [](std::vector<uint8_t>& b) { return reinterpret_cast<img::Header*>(b.data()); };
  EXPECT_THROW(ImageView(corrupt([&](auto& b) { header(b)->format_e = 9; })), InputError);
  EXPECT_THROW(ImageView(corrupt([&](auto& b) { header(b)->format_m = 0; })), InputError);
  EXPECT_THROW(ImageView(corrupt([&](auto& b) { header(b)->reserved[3] = 1; })), InputError);
  // The root's above child moved to slot 3 of its beat, which holds no node:
  // bits [39:18] of the root are its index.
  EXPECT_THROW(ImageView(corrupt([&](auto& b) {
                 uint8_t* root = b.data() + header(b)->node_offset;
                 uint64_t bits = 0;
                 std::memcpy(&bits, root, 8);
                 const uint64_t above = 7;  // beat 1, slot 3
                 bits = (bits & ~(((uint64_t{1} << 22) - 1) << 18)) | above << 18;
                 std::memcpy(root, &bits, 8);
               })),
               InputError);
  // Either empty-child mark of the root flipped (bits 40, 41): the core would
  // skip a child with triangles or fetch an empty one.
  for (int bit : {40, 41}) {
    try {
      ImageView(corrupt([&](auto& b) { b[header(b)->node_offset + bit / 8] ^= uint8_t(1u << (bit % 8)); }));
      FAIL() << "a flipped empty-child mark (bit " << bit << ") was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("empty-child marks"), std::string::npos) << e.what();
    }
  }
  // An fp16 image read as if it were fp32 (wrong format in the header).
  EXPECT_THROW(ImageView(corrupt([&](auto& b) {
                 header(b)->format_e = 8;
                 header(b)->format_m = 23;
               })),
               InputError);
}

}  // namespace
}  // namespace kdrt
