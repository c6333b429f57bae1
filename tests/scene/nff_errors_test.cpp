// Every malformed NFF input gives an InputError naming the file and line.
#include <gtest/gtest.h>

#include "scene/scene.h"
#include "tests/scene/scene_test_util.h"

namespace kdrt {
namespace {

using testing::ExpectInputError;
using testing::TempDir;

const char kTri[] = "p 3\n0 0 0\n1 0 0\n0 1 0\n";

struct BadCase {
  const char* name;
  std::string text;
  int line;
  const char* fragment;
};

class NffErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(NffErrors, NamesFileAndLine) {
  const BadCase& c = GetParam();
  TempDir dir;
  std::string path = dir.Write(std::string(c.name) + ".nff", c.text);
  ExpectInputError([&] { LoadScene(path); }, path, c.line, c.fragment);
}

const std::string kView = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n";

INSTANTIATE_TEST_SUITE_P(
    Cases, NffErrors,
    ::testing::Values(
        BadCase{"unknown_keyword", std::string(kTri) + "# ok\nq 1 2 3\n", 6, "unknown keyword 'q'"},
        BadCase{"too_few_fields", "b 1 2\n" + std::string(kTri), 1, "needs 4 fields, got 3"},
        BadCase{"too_many_fields", std::string(kTri) + "s 0 0 0 1 2\n", 5, "needs 5 fields"},
        BadCase{"fill_fields", "f 1 0 0\n" + std::string(kTri), 1, "needs 9 fields"},
        BadCase{"fill_negative", "f 1 0 0 -0.5 0 1 0 1\n" + std::string(kTri), 1, "must not be negative"},
        BadCase{"light_fields", std::string(kTri) + "l 1 2 3 4\n", 5, "needs 4 or 7 fields"},
        BadCase{"light_nan", "l 1 nan 3\n" + std::string(kTri), 1, "not finite"},
        BadCase{"non_numeric", "p 3\n0 0 0\n1 zero 0\n0 1 0\n", 3, "expected a number, got 'zero'"},
        BadCase{"trailing_garbage", "p 3\n0 0 0\n1 0 0x\n0 1 0\n", 3, "'0x'"},
        BadCase{"nan", "\n\np 3\n0 0 0\n1 0 0\nnan 1 0\n", 6, "not finite"},
        BadCase{"inf", std::string(kTri) + "s 0 -inf 0 1\n", 5, "not finite"},
        BadCase{"overflow", "p 3\n0 0 0\n1e39 0 0\n0 1 0\n", 3, "out of float range"},
        BadCase{"truncated_polygon", "b 0 0 0\np 4\n0 0 0\n1 0 0\n1 1 0\n", 2,
                "declares 4 vertices but the file ends after 3"},
        BadCase{"vertex_fields", "p 3\n0 0 0\n1 0\n0 1 0\n", 3, "needs 3 numbers, got 2"},
        BadCase{"patch_vertex_fields", "pp 3\n0 0 0 0 0 1\n1 0 0\n0 1 0 0 0 1\n", 3,
                "needs 6 numbers, got 3"},
        BadCase{"two_vertices", std::string(kTri) + "p 2\n0 0 0\n1 0 0\n", 5,
                "2 vertices (needs at least 3)"},
        BadCase{"negative_count", "p -3\n", 1, "outside"},
        BadCase{"count_not_integer", "p 3.5\n0 0 0\n1 0 0\n0 1 0\n", 1, "expected an integer"},
        BadCase{"empty_scene", "# nothing\nb 0 0 0\n", 0, "no triangles"},
        BadCase{"empty_file", "", 0, "no triangles"},
        BadCase{"view_order", "v\nat 0 0 0\n", 2, "expected 'from'"},
        BadCase{"view_truncated", "v\nfrom 0 0 5\nat 0 0 0\n", 3, "file ends inside view block"},
        BadCase{"view_same_points", "v\nfrom 1 1 1\nat 1 1 1\n", 3, "'at' equals 'from'"},
        BadCase{"view_up_parallel", "v\nfrom 0 0 5\nat 0 0 0\nup 0 0 2\n", 4, "parallel"},
        BadCase{"view_angle", "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 180\n", 5, "angle"},
        BadCase{"view_resolution", kView.substr(0, kView.size() - 4) + "0 8\n", 7, "outside"},
        BadCase{"sphere_radius", "s 0 0 0 0\n", 1, "radius must be positive"},
        BadCase{"cone_truncated", std::string(kTri) + "c\n0 0 0 1\n", 6, "file ends inside cone"},
        BadCase{"cone_fields", "c\n0 0 0 1\n0 0 1\n", 3, "needs 4 numbers"},
        BadCase{"cone_flat", "c\n0 0 0 1\n0 0 0 2\n", 3, "apex equals its base"}),
    [](const ::testing::TestParamInfo<BadCase>& info) { return info.param.name; });

TEST(NffErrorsExtra, MissingFileAndUnknownExtension) {
  TempDir dir;
  std::string missing = dir.File("missing.nff");
  ExpectInputError([&] { LoadScene(missing); }, missing, 0, "no such file");
  std::string odd = dir.Write("scene.xyz", kTri);
  ExpectInputError([&] { LoadScene(odd); }, odd, 0, "unknown scene file extension");
  std::string none = dir.Write("scene", kTri);
  ExpectInputError([&] { LoadScene(none); }, none, 0, "unknown scene file extension");
  ExpectInputError([&] { LoadScene(dir.path() + "/"); }, dir.path() + "/", 0, "");
}

TEST(NffErrorsExtra, ValidViewBlockIsAccepted) {
  // The error cases above only mean something if the same text with the
  // mistake removed loads.
  TempDir dir;
  Scene s = LoadScene(dir.Write("ok.nff", kView + kTri));
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_EQ(s.camera->width, 8);
  EXPECT_EQ(s.camera->hither, 1.0f);
}

}  // namespace
}  // namespace kdrt
