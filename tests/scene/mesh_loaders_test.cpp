// OBJ (tinyobjloader), PLY and OFF (kdrt's own readers): polygons are fanned
// by kdrt in file order, bad numbers and indices become InputError.
#include <cstdint>
#include <cstring>

#include <gtest/gtest.h>

#include "scene/scene.h"
#include "tests/scene/scene_test_util.h"

namespace kdrt {
namespace {

using testing::ExpectInputError;
using testing::TempDir;

// Checks the fan of a quad a b c d: (a b c), (a c d).
void ExpectQuadFan(const Scene& s, size_t first, glm::vec3 a, glm::vec3 b, glm::vec3 c,
                   glm::vec3 d) {
  ASSERT_GE(s.triangles.size(), first + 2);
  EXPECT_EQ(s.triangles[first].v0, a);
  EXPECT_EQ(s.triangles[first].v1, b);
  EXPECT_EQ(s.triangles[first].v2, c);
  EXPECT_EQ(s.triangles[first + 1].v0, a);
  EXPECT_EQ(s.triangles[first + 1].v1, c);
  EXPECT_EQ(s.triangles[first + 1].v2, d);
}

uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

TEST(ObjLoader, QuadFansInFileOrderAcrossGroups) {
  TempDir dir;
  std::string path = dir.Write("quad.obj",
                               "# quad then triangle\n"
                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                               "v 0 0 3\nv 1 0 3\nv 0 1 3\n"
                               "g first\n"
                               "f 1 2 3 4\n"
                               "g second\n"
                               "f 5/1 6/1 7/1\n"
                               "g first\n"
                               "f -4 -2 -1\n");
  Scene s = LoadScene(path);
  ASSERT_EQ(s.triangles.size(), 4u);
  ExpectQuadFan(s, 0, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  EXPECT_EQ(s.triangles[2].v0, glm::vec3(0, 0, 3));
  EXPECT_EQ(s.triangles[2].v2, glm::vec3(0, 1, 3));
  EXPECT_EQ(s.triangles[3].v0, glm::vec3(0, 1, 0));  // -4 counts back from v 7
  EXPECT_EQ(s.triangles[3].v1, glm::vec3(1, 0, 3));
  EXPECT_EQ(s.triangles[3].v2, glm::vec3(0, 1, 3));
  EXPECT_FALSE(s.camera.has_value());
}

TEST(ObjLoader, MaterialDiffuseColour) {
  TempDir dir;
  dir.Write("m.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n");
  std::string path = dir.Write("coloured.obj",
                               "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                               "f 1 2 3\nusemtl blue\nf 1 2 3\nusemtl red\nf 3 2 1\n");
  Scene s = LoadScene(path);
  ASSERT_EQ(s.triangles.size(), 3u);
  EXPECT_EQ(s.colors[s.material[0]], glm::vec3(1, 1, 1));
  EXPECT_EQ(s.colors[s.material[1]], glm::vec3(0, 0, 1));
  EXPECT_EQ(s.colors[s.material[2]], glm::vec3(1, 0, 0));
  EXPECT_EQ(s.triangles[2].v0, glm::vec3(0, 1, 0));
}

TEST(ObjLoader, Errors) {
  TempDir dir;
  std::string nan = dir.Write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 NaN 0\nf 1 2 3\n");
  ExpectInputError([&] { LoadScene(nan); }, nan, 3, "not finite");
  std::string word = dir.Write("word.obj", "v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n");
  ExpectInputError([&] { LoadScene(word); }, word, 3, "expected a number");
  std::string range = dir.Write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n");
  ExpectInputError([&] { LoadScene(range); }, range, 5, "out of range");
  std::string zero = dir.Write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  ExpectInputError([&] { LoadScene(zero); }, zero, 4, "out of range");
  std::string two = dir.Write("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  ExpectInputError([&] { LoadScene(two); }, two, 3, "needs at least 3");
  std::string empty = dir.Write("empty.obj", "v 0 0 0\n");
  ExpectInputError([&] { LoadScene(empty); }, empty, 0, "no triangles");
  std::string missing = dir.File("missing.obj");
  ExpectInputError([&] { LoadScene(missing); }, missing, 0, "no such file");
}

const char kPlyHeader[] =
    "ply\n"
    "format ascii 1.0\n"
    "element vertex 7\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "element face 3\n"
    "property list uchar int vertex_indices\n"
    "end_header\n";

TEST(PlyLoader, QuadFansAndFaceOrderIsKept) {
  TempDir dir;
  std::string path = dir.Write("mesh.ply", std::string(kPlyHeader) +
                                               "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                                               "0 0 2\n2 0 2\n0 2 2\n"
                                               "3 4 5 6\n"
                                               "4 0 1 2 3\n"
                                               "3 6 5 4\n");
  Scene s = LoadScene(path);
  ASSERT_EQ(s.triangles.size(), 4u);
  EXPECT_EQ(s.triangles[0].v0, glm::vec3(0, 0, 2));
  EXPECT_EQ(s.triangles[0].v1, glm::vec3(2, 0, 2));
  EXPECT_EQ(s.triangles[0].v2, glm::vec3(0, 2, 2));
  ExpectQuadFan(s, 1, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  EXPECT_EQ(s.triangles[3].v0, glm::vec3(0, 2, 2));
  EXPECT_EQ(s.triangles[3].v2, glm::vec3(0, 0, 2));
}

TEST(PlyLoader, NanCoordinateIsAnError) {
  TempDir dir;
  std::string path = dir.Write("nan.ply", std::string(kPlyHeader) +
                                              "0 0 0\n1 0 0\n1 nan 0\n0 1 0\n"
                                              "0 0 2\n2 0 2\n0 2 2\n"
                                              "3 4 5 6\n4 0 1 2 3\n3 6 5 4\n");
  ExpectInputError([&] { LoadScene(path); }, path, 12, "NaN");
}

TEST(PlyLoader, BrokenFilesAreErrorsWithLines) {
  TempDir dir;
  // assimp 5.2's PLY reader loops forever on this one.
  std::string no_end = dir.Write("noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  ExpectInputError([&] { LoadScene(no_end); }, no_end, 3, "no end_header");
  std::string garbage = dir.Write("garbage.PLY", "this is not a ply file at all\n");
  ExpectInputError([&] { LoadScene(garbage); }, garbage, 1, "not a PLY file");
  const std::string body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 2\n2 0 2\n0 2 2\n3 4 5 6\n";
  // assimp read the missing indices as 0.
  std::string short_face = dir.Write("short.ply", kPlyHeader + body + "4 0 1 2\n3 6 5 4\n");
  ExpectInputError([&] { LoadScene(short_face); }, short_face, 18, "too few values");
  std::string range = dir.Write("range.ply", kPlyHeader + body + "4 0 1 2 7\n3 6 5 4\n");
  ExpectInputError([&] { LoadScene(range); }, range, 18, "out of range");
  std::string truncated = dir.Write("trunc.ply", kPlyHeader + body);
  ExpectInputError([&] { LoadScene(truncated); }, truncated, 17, "file ends");
  std::string huge = dir.Write("huge.ply",
                               "ply\nformat binary_little_endian 1.0\nelement vertex 300000000\n"
                               "property float x\nproperty float y\nproperty float z\n"
                               "end_header\n");
  ExpectInputError([&] { LoadScene(huge); }, huge, 3, "exceeds the file size");
}

TEST(PlyLoader, BinaryLittleEndianQuad) {
  std::string data =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const float xyz[12] = {0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0};
  data.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  data.push_back(4);
  const int32_t idx[4] = {3, 2, 1, 0};  // little-endian host assumed (x86, arm)
  data.append(reinterpret_cast<const char*>(idx), sizeof idx);
  TempDir dir;
  std::string path = dir.Write("bin.ply", data);
  Scene s = LoadScene(path);
  ExpectQuadFan(s, 0, {0, 2, 0}, {2, 2, 0}, {2, 0, 0}, {0, 0, 0});
  EXPECT_EQ(s.triangles.size(), 2u);
  // One index byte short.
  std::string cut = dir.Write("cut.ply", data.substr(0, data.size() - 1));
  ExpectInputError([&] { LoadScene(cut); }, cut, 0, "file ends inside PLY binary data");
}

TEST(PlyLoader, BinaryBigEndianDoublesAndOtherTypes) {
  // Big-endian: doubles for x y z, a skipped uchar colour, ushort list
  // counts with uint indices, and an edge element after the faces.
  auto be = [](auto v) {
    std::string raw(reinterpret_cast<const char*>(&v), sizeof v);  // little-endian host
    return std::string(raw.rbegin(), raw.rend());
  };
  std::string data =
      "ply\nformat binary_big_endian 1.0\ncomment c\nelement vertex 4\nproperty double x\n"
      "property uchar red\nproperty double y\nproperty double z\nelement face 1\n"
      "property list ushort uint vertex_index\nelement edge 1\nproperty int vertex1\n"
      "end_header\n";
  const double xyz[12] = {0, 0, 0, 0.1, 0, 0, 0.1, 3, 0, 0, 3, -1e300 * 1e-300};
  for (int v = 0; v < 4; ++v) {
    data += be(xyz[3 * v]) + std::string(1, '\xff') + be(xyz[3 * v + 1]) + be(xyz[3 * v + 2]);
  }
  data += be(uint16_t{4});
  for (uint32_t i : {0u, 1u, 2u, 3u}) data += be(i);
  data += be(int32_t{7});
  TempDir dir;
  std::string path = dir.Write("be.ply", data);
  Scene s = LoadScene(path);
  ASSERT_EQ(s.triangles.size(), 2u);
  ExpectQuadFan(s, 0, {0, 0, 0}, {0.1f, 0, 0}, {0.1f, 3, 0}, {0, 3, -1});
  std::string cut = dir.Write("cut.ply", data.substr(0, data.size() - 5));
  ExpectInputError([&] { LoadScene(cut); }, cut, 0, "file ends inside PLY binary data");
}

TEST(PlyLoader, ExtraPropertiesAndElementsAreSkipped) {
  TempDir dir;
  std::string path = dir.Write("extra.ply",
                               "ply\nformat ascii 1.0\nobj_info x\nelement vertex 3\n"
                               "property float nx\nproperty float x\nproperty list uchar float w\n"
                               "property float y\nproperty int z\nproperty uchar red\n"
                               "element face 1\nproperty uchar flags\n"
                               "property list uchar int vertex_indices\n"
                               "property list uchar float texcoord\nend_header\n"
                               "nan 0 0 0 +0 255\r\n"
                               "\n"
                               "1 1 2 0.5 1.5 0 -3 7\n"
                               "0 0 0 1 1 200\n"
                               "0 3 2 1 0 2 .5 .25\n");
  Scene s = LoadScene(path);
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.triangles[0].v0, glm::vec3(0, 1, 1));
  EXPECT_EQ(s.triangles[0].v1, glm::vec3(1, 0, -3));
  EXPECT_EQ(s.triangles[0].v2, glm::vec3(0, 0, 0));
}

TEST(PlyLoader, DecimalsReadToTheSameBitsInEveryFormat) {
  // One number, one float: PLY, OFF and NFF all round to the nearest float
  // (1.18 is 0x3f970a3d; assimp 5.2's PLY/OFF reader gives
  // 0x3f970a3e). A double property is rounded once, from the exact value.
  TempDir dir;
  std::string ply = dir.Write("r.ply",
                              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                              "property float y\nproperty double z\nelement face 1\n"
                              "property list uchar int vertex_indices\nend_header\n"
                              "1.18 3.4028235e38 1.18\n0.1 1e-3 0.1\n-0 2 0\n3 0 1 2\n");
  Scene s = LoadScene(ply);
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(Bits(s.triangles[0].v0.x), 0x3f970a3du);
  EXPECT_EQ(Bits(s.triangles[0].v0.y), 0x7f7fffffu);
  EXPECT_EQ(Bits(s.triangles[0].v0.z), 0x3f970a3du);
  EXPECT_EQ(Bits(s.triangles[0].v1.x), 0x3dcccccdu);
  EXPECT_EQ(Bits(s.triangles[0].v1.y), 0x3a83126fu);
  EXPECT_EQ(Bits(s.triangles[0].v2.x), 0x80000000u);
  std::string off = dir.Write("r.off", "OFF\n3 1 0\n1.18 0 0\n0 1 0\n0 0 1\n3 0 1 2\n");
  EXPECT_EQ(Bits(LoadScene(off).triangles[0].v0.x), 0x3f970a3du);
  std::string nff = dir.Write("r.nff", "p 3\n1.18 0 0\n0 1 0\n0 0 1\n");
  EXPECT_EQ(Bits(LoadScene(nff).triangles[0].v0.x), 0x3f970a3du);
}

TEST(PlyLoader, LayoutsKdrtCannotReadAreErrors) {
  TempDir dir;
  const std::string head = "ply\nformat ascii 1.0\n";
  const std::string vertex3 =
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string face1 = "element face 1\nproperty list uchar int vertex_indices\n";
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  std::string strips = dir.Write(
      "strips.ply", head + vertex3 + "element tristrips 1\nproperty list int int vertex_indices\n" +
                        "end_header\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2 -1\n");
  ExpectInputError([&] { LoadScene(strips); }, strips, 7, "tristrips");
  std::string twice = dir.Write("twice.ply", head + vertex3 + vertex3 + face1 + "end_header\n" +
                                                 "0 0 0\n1 0 0\n0 1 0\n" + body);
  ExpectInputError([&] { LoadScene(twice); }, twice, 7, "second PLY 'vertex' element");
  std::string face_first =
      dir.Write("first.ply", head + face1 + vertex3 + "end_header\n3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n");
  ExpectInputError([&] { LoadScene(face_first); }, face_first, 3, "without a vertex element");
  std::string no_list = dir.Write("nolist.ply", head + vertex3 + "element face 1\nproperty int n\n" +
                                                    "end_header\n0 0 0\n1 0 0\n0 1 0\n3\n");
  ExpectInputError([&] { LoadScene(no_list); }, no_list, 7, "no vertex_indices list");
  // assimp read "1.5" in an integer property as 1 and gave ".5" to the next one.
  std::string int_dec = dir.Write(
      "intdec.ply", head + "element vertex 3\nproperty float x\nproperty uchar red\n" +
                        "property float y\nproperty float z\n" + face1 + "end_header\n" +
                        "0 1 0 0\n1 1.5 0 0\n0 1 1 0\n3 0 1 2\n");
  ExpectInputError([&] { LoadScene(int_dec); }, int_dec, 12, "'1.5' is not a number of type integer");
  std::string inf = dir.Write("inf.ply", head + vertex3 + face1 + "end_header\n" +
                                             "0 0 0\n1 0 0\n0 1 1e39\n3 0 1 2\n");
  ExpectInputError([&] { LoadScene(inf); }, inf, 12, "vertex 2: coordinate z is not finite");
}

TEST(OffLoader, LargePolygonsCommentsAndTwoCounts) {
  // assimp dropped faces of 10 or more vertices, read the first number of
  // the next line as the edge count when it was missing, and counted a
  // comment line among the faces as a face.
  TempDir dir;
  std::string path = dir.Write("big.off",
                               "OFF\n"
                               "10 3\n"
                               "1 0 0\n2 0 0\n3 0 0\n4 0 0\n5 0 0\n"
                               "6 0 0\n7 0 0\n8 0 0\n9 0 0\n9 9 0\n"
                               "10 0 1 2 3 4 5 6 7 8 9\n"
                               "# a comment\n"
                               "\n"
                               "3 9 8 7 255 0 0\n"
                               "3 0 5 9\n");
  Scene s = LoadScene(path);
  ASSERT_EQ(s.triangles.size(), 10u);
  EXPECT_EQ(s.triangles[0].v0, glm::vec3(1, 0, 0));
  EXPECT_EQ(s.triangles[7].v1, glm::vec3(9, 0, 0));
  EXPECT_EQ(s.triangles[7].v2, glm::vec3(9, 9, 0));
  EXPECT_EQ(s.triangles[8].v0, glm::vec3(9, 9, 0));
  EXPECT_EQ(s.triangles[9].v1, glm::vec3(6, 0, 0));
}

TEST(OffLoader, QuadFansAndFaceOrderIsKept) {
  TempDir dir;
  std::string path = dir.Write("mesh.off",
                               "OFF\n"
                               "7 3 0\n"
                               "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                               "0 0 2\n2 0 2\n0 2 2\n"
                               "3 4 5 6\n"
                               "4 0 1 2 3\n"
                               "3 6 5 4\n");
  Scene s = LoadScene(path);
  ASSERT_EQ(s.triangles.size(), 4u);
  EXPECT_EQ(s.triangles[0].v0, glm::vec3(0, 0, 2));
  EXPECT_EQ(s.triangles[0].v1, glm::vec3(2, 0, 2));
  ExpectQuadFan(s, 1, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  EXPECT_EQ(s.triangles[3].v1, glm::vec3(2, 0, 2));
}

TEST(OffLoader, BrokenFilesAreErrorsWithLines) {
  TempDir dir;
  std::string path = dir.Write("short.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n");
  ExpectInputError([&] { LoadScene(path); }, path, 4, "file ends before vertex 2 of 4");
  // assimp clamped this index to the last vertex.
  std::string range = dir.Write("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n");
  ExpectInputError([&] { LoadScene(range); }, range, 6, "'5' is not an index");
  std::string nan = dir.Write("nan.off", "OFF\n# comment\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  ExpectInputError([&] { LoadScene(nan); }, nan, 5, "not finite");
  std::string two = dir.Write("two.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
  ExpectInputError([&] { LoadScene(two); }, two, 6, "needs at least 3");
}

}  // namespace
}  // namespace kdrt
