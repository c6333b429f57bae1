// End-to-end cases of bad or partly read scene and ray files through the kdrt
// tool: an error names the file (and line), exits 1 and leaves no output;
// data a reader leaves out is a warning on stderr and in the JSON
// "warnings", and --strict refuses it.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/common/run_kdrt.h"

namespace kdrt {
namespace {

namespace fs = std::filesystem;
using testing::RunKdrt;
using testing::RunResult;

const char kTriangleObj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
const char kPlyHeader[] =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n";

class BadInputCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("kdrt_badinput_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& bytes) const {
    std::ofstream(Path(name), std::ios::binary) << bytes;
    return Path(name);
  }
  size_t FileCount() const {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir_)) n += e.is_regular_file();
    return n;
  }
  // Renders `scene` (8x8) with an image and a JSON output.
  RunResult Render(const std::string& scene, const std::string& extra = "") const {
    return RunKdrt("render " + scene + " --res 8x8 -q -o " + Path("out.png") + " --json " + Path("out.json") + " " +
                   extra);
  }
  // Exit 1, exactly the one line "kdrt: error: <message>", nothing written.
  void ExpectError(const RunResult& r, const std::string& message, size_t inputs) const {
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_EQ(r.output, "kdrt: error: " + message + "\n");
    EXPECT_EQ(FileCount(), inputs) << "an output file was left";
  }
  // Exit 0; the warning on stderr and in the JSON.
  void ExpectWarning(const RunResult& r, const std::string& warning) const {
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("kdrt: warning: " + warning + "\n"), std::string::npos) << r.output;
    nlohmann::json j;
    std::ifstream(Path("out.json")) >> j;
    bool found = false;
    for (const auto& w : j["warnings"]) found |= w.get<std::string>() == warning;
    EXPECT_TRUE(found) << j["warnings"].dump();
  }
  fs::path dir_;
};

TEST_F(BadInputCli, RayFileThatIsADirectory) {
  fs::create_directories(dir_ / "rays");
  ExpectError(Render("gen:tetra:20", "--rays " + Path("rays")), Path("rays") + ": not a regular file", 0);
  ExpectError(RunKdrt("info gen:tetra:20 --rays " + Path("rays")), Path("rays") + ": not a regular file", 0);
}

TEST_F(BadInputCli, NffResolutionBeyondTheFrameLimit) {
  const std::string nff = Write("big.nff",
                                "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0\nresolution 65536 65536\n"
                                "p 3\n0 0 0\n1 0 0\n0 1 0\n");
  ExpectError(RunKdrt("info " + nff + " --json " + Path("out.json")),
              nff + ":7: resolution 65536 x 65536 is 4294967296 camera rays; at most 67108864 per frame (8192 x 8192)",
              1);
  ExpectError(RunKdrt("render gen:tetra:20 --res 16384x8192 -o " + Path("out.png")),
              "--res 16384x8192: 134217728 camera rays; at most 67108864 per frame (8192x8192)", 1);
}

TEST_F(BadInputCli, AutomaticCameraOutsideFloatNamesFileAndTriangle) {
  const std::string nff = Write("huge.nff", "p 3\n0 0 0\n1 0 0\n0 1 0\np 3\n-3e38 0 0\n3e38 0 0\n0 3e38 0\n");
  const RunResult r = Render(nff);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(r.output.rfind("kdrt: error: " + nff + ": no camera in the scene, and the automatic one does not fit "
                           "in float",
                           0),
            0u)
      << r.output;
  EXPECT_NE(r.output.find("triangle 1 reaches"), std::string::npos) << r.output;
  EXPECT_EQ(FileCount(), 1u);
  // An explicit camera needs no automatic one.
  const RunResult ok = Render(nff, "--camera \"0 0 5 0 0 0 0 1 0 45\"");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

TEST_F(BadInputCli, ObjUnknownStatementWarnsOrIsRefused) {
  const std::string obj = Write("q.obj", std::string(kTriangleObj) + "f 1 2 3\n? 1 2 4\nl 1 2\nl 2 3\n");
  ExpectWarning(Render(obj), obj + ":6: unknown OBJ statement '?' left out");
  ExpectWarning(Render(obj), obj + ":7: OBJ statement 'l' (not a polygon) left out (2 lines)");
  fs::remove(Path("out.png"));
  fs::remove(Path("out.json"));
  ExpectError(Render(obj, "--strict"), obj + ":6: unknown OBJ statement '?' left out (--strict)", 1);
}

TEST_F(BadInputCli, PlyDataAfterTheDeclaredElements) {
  const std::string ply = Write("t.ply", std::string(kPlyHeader) + "3 0 2 3\n3 1 2 3\n");
  const std::string warning = ply + ":15: 2 lines after the declared elements (vertex 4, face 1) left out";
  ExpectWarning(Render(ply), warning);
  fs::remove(Path("out.png"));
  fs::remove(Path("out.json"));
  ExpectError(Render(ply, "--strict"), warning + " (--strict)", 1);
  ExpectError(RunKdrt("info --strict " + ply + " --json " + Path("out.json")), warning + " (--strict)", 1);
}

TEST_F(BadInputCli, BinaryPlyBytesAfterTheDeclaredElements) {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  bytes.append(reinterpret_cast<const char*>(v), sizeof v);
  const int idx[3] = {0, 1, 2};
  bytes += '\3';
  bytes.append(reinterpret_cast<const char*>(idx), sizeof idx);
  bytes += '\3';
  bytes.append(reinterpret_cast<const char*>(idx), sizeof idx);  // a second face the header does not declare
  const std::string ply = Write("b.ply", bytes);
  const std::string warning = ply + ": 13 bytes after the declared elements (vertex 3, face 1) left out";
  ExpectWarning(Render(ply), warning);
  fs::remove(Path("out.png"));
  fs::remove(Path("out.json"));
  ExpectError(Render(ply, "--strict"), warning + " (--strict)", 1);
}

TEST_F(BadInputCli, OffFacesAfterTheDeclaredCount) {
  const std::string off = Write("t.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n# more\n3 1 2 3\n3 0 2 3\n");
  const std::string warning = off + ":9: 2 lines after the declared 4 vertices and 1 faces left out";
  ExpectWarning(Render(off), warning);
  fs::remove(Path("out.png"));
  fs::remove(Path("out.json"));
  ExpectError(RunKdrt("sim --model fast --strict -q " + off + " --res 8x8 -o " + Path("out.png")),
              warning + " (--strict)", 1);
}

TEST_F(BadInputCli, SceneOfDegenerateTrianglesOnly) {
  const std::string nff = Write("flat.nff", "p 3\n0 0 0\n1 1 1\n2 2 2\n");
  ExpectError(Render(nff), nff + ": scene has no triangle with an area (all 1 are degenerate: zero area in float)",
              1);
  const std::string obj = Write("flat.obj", std::string(kTriangleObj) + "f 1 1 2\nf 3 3 3\n");
  ExpectError(Render(obj), obj + ": scene has no triangle with an area (all 2 are degenerate: zero area in float)",
              2);
}

TEST_F(BadInputCli, RawBytesOfTheFileAreEscaped) {
  const std::string nff = Write("esc.nff", std::string("p 3\n0 0 0\n1 0 0\n0 1 0\n\x1b[31m\xff\x01 1 2 3\n"));
  ExpectError(Render(nff), nff + ":5: unknown keyword '\\x1b[31m\\xff\\x01'", 1);
  const std::string obj = Write("esc.obj", std::string(kTriangleObj) + "f 1 2 \x1b\\\x80\n");
  ExpectError(Render(obj), obj + ":5: face vertex '\\x1b\\\\\\x80' is not an index", 2);
  const std::string off = Write("esc.off", "OFF\n3 1\n0 0 0\n1 0 \xc3\x28\n0 1 0\n3 0 1 2\n");
  ExpectError(Render(off), off + ":4: vertex coordinate: expected a number, got '\\xc3('", 3);
  const std::string ply = Write("esc.ply", "ply\nformat ascii 1.0\n\x07\x7f 1\nend_header\n");
  ExpectError(Render(ply), ply + ":3: unknown PLY header keyword '\\x07\\x7f'", 4);
}

TEST_F(BadInputCli, GeneratorSpecMustBeWhole) {
  ExpectError(Render("gen:room:1e3"), "gen:room:1e3: size '1e3' is not a whole number", 0);
  ExpectError(Render("gen:room:10:extra"),
              "gen:room:10:extra: expected gen:NAME or gen:NAME:SIZE (one size, no more fields)", 0);
  ExpectError(Render("gen:room:0"), "gen:room:0: size 0 is outside 1..10000000", 0);
  ExpectError(Render("gen:nope:10"), "gen:nope:10: unknown scene generator 'nope' (known: room, balls, rings, "
                                     "tetra, tree, gears, strips, hoops)",
              0);
}

}  // namespace
}  // namespace kdrt
