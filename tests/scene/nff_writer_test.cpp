#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include <gtest/gtest.h>

#include "scene/nff_writer.h"
#include "scene/scene.h"
#include "scenes/gen/generators.h"
#include "tests/common/read_file.h"
#include "tests/scene/scene_test_util.h"

namespace kdrt {
namespace {

using testing::TempDir;

bool SameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void ExpectBitIdentical(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (size_t i = 0; i < a.triangles.size(); ++i) {
    const Triangle& x = a.triangles[i];
    const Triangle& y = b.triangles[i];
    ASSERT_TRUE(SameBits(x.v0, y.v0) && SameBits(x.v1, y.v1) && SameBits(x.v2, y.v2))
        << "triangle " << i;
    ASSERT_TRUE(SameBits(a.colors[a.material[i]], b.colors[b.material[i]])) << "colour " << i;
    const auto finish = [](const Scene& s, size_t k) {
      return s.material[k] < s.finishes.size() ? s.finishes[s.material[k]] : Finish{};
    };
    const Finish fa = finish(a, i), fb = finish(b, i);
    ASSERT_EQ(std::memcmp(&fa, &fb, sizeof(Finish)), 0) << "finish " << i;
  }
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_TRUE(SameBits(a.lights[i].position, b.lights[i].position)) << "light " << i;
    EXPECT_EQ(a.lights[i].has_color, b.lights[i].has_color) << "light " << i;
    if (a.lights[i].has_color) {
      EXPECT_TRUE(SameBits(a.lights[i].color, b.lights[i].color)) << "light " << i;
    }
  }
  EXPECT_TRUE(SameBits(a.background, b.background));
  ASSERT_EQ(a.camera.has_value(), b.camera.has_value());
  if (a.camera) {
    EXPECT_TRUE(SameBits(a.camera->from, b.camera->from));
    EXPECT_TRUE(SameBits(a.camera->at, b.camera->at));
    EXPECT_TRUE(SameBits(a.camera->up, b.camera->up));
    EXPECT_EQ(std::memcmp(&a.camera->angle_deg, &b.camera->angle_deg, 4), 0);
    EXPECT_EQ(std::memcmp(&a.camera->hither, &b.camera->hither, 4), 0);
    EXPECT_EQ(a.camera->width, b.camera->width);
    EXPECT_EQ(a.camera->height, b.camera->height);
  }
}

TEST(NffWriter, RoundTripOfAwkwardFloatsIsBitExact) {
  Scene s;
  const float awkward[] = {1.0f / 3.0f,  -0.0f,   0.1f,     3.4028235e38f, -1.17549435e-38f,
                           1.0e-40f,     1.4e-45f, 16777217.0f, -2.5e-7f,   123456.789f};
  for (int i = 0; i < 10; ++i) {
    float a = awkward[i], b = awkward[(i + 3) % 10], c = awkward[(i + 7) % 10];
    s.triangles.push_back({{a, b, c}, {b, c, a}, {c, a, b}});
    s.material.push_back(i % 3);
  }
  s.colors = {{0.1f, 0.2f, 0.3f}, {1.0f / 3.0f, -0.0f, 0.7f}, {0.1f, 0.2f, 0.3f}};
  s.finishes = {Finish{0.7f, 0.3f, 4.0f}, Finish{1.0f / 3.0f, 0.0f, 100.0f}, Finish{0.7f, 0.3f, 4.0f}};
  Light plain, colored;
  plain.position = {1e-7f, -3.0f, 1.0f / 3.0f};
  colored.position = {5.0f, 5.0f, 5.0f};
  colored.color = {0.25f, 1.0f / 7.0f, 1.0f};
  colored.has_color = true;
  s.lights = {plain, colored};
  s.background = glm::vec3(0.3f, 1.0f / 7.0f, 0.0f);
  Camera cam;
  cam.from = glm::vec3(0.1f, 0.2f, 1.0f / 3.0f);
  cam.at = glm::vec3(-1e-7f, 0.0f, -5.5f);
  cam.up = glm::vec3(0.0f, 1.0f, 1e-3f);
  cam.angle_deg = 33.3f;
  cam.hither = 1e-4f;
  cam.width = 640;
  cam.height = 480;
  s.camera = cam;
  TempDir dir;
  std::string path = dir.File("awkward.nff");
  WriteNff(s, path);
  Scene back = LoadScene(path);
  ExpectBitIdentical(s, back);
  // Written again, the file is the same byte for byte (after the comment
  // line, which names the source).
  std::string again = dir.File("again.nff");
  back.source = s.source;
  WriteNff(back, again);
  EXPECT_EQ(kdrt::testing::ReadFile(path), kdrt::testing::ReadFile(again));
}

TEST(NffWriter, GeneratedSceneRoundTrip) {
  Scene s = GenerateScene("room", 2000);
  TempDir dir;
  std::string path = dir.File("room.nff");
  WriteNff(s, path);
  ExpectBitIdentical(s, LoadScene(path));
}

TEST(NffWriter, NoPartialFileOnError) {
  TempDir dir;
  Scene s;
  s.triangles.push_back({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  s.triangles.push_back({{0, 0, 0}, {1, std::numeric_limits<float>::quiet_NaN(), 0}, {0, 1, 0}});
  s.material = {0, 0};
  s.colors = {{1, 1, 1}};
  std::string path = dir.File("bad.nff");
  EXPECT_THROW(WriteNff(s, path), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));  // no file, no temporary
  s.material = {0, 5};  // colour index out of range
  s.triangles[1].v1.y = 0.0f;
  EXPECT_THROW(WriteNff(s, path), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
  EXPECT_THROW(WriteNff(s, dir.File("no/such/dir/x.nff")), InputError);
  // An existing file survives a failed write.
  s.material = {0, 0};
  WriteNff(s, path);
  auto size = std::filesystem::file_size(path);
  s.triangles[0].v0.x = std::numeric_limits<float>::infinity();
  EXPECT_THROW(WriteNff(s, path), InputError);
  EXPECT_EQ(std::filesystem::file_size(path), size);
}

}  // namespace
}  // namespace kdrt
