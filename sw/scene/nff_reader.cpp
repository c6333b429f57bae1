// Neutral File Format reader (Eric Haines, as written by the Standard
// Procedural Databases). One keyword per line; the `v` block and the vertex
// lines of `p`, `pp` and `c` follow their keyword line, blank and `#` lines
// may appear anywhere.
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "scene/loaders.h"
#include "scene/scene_builder.h"
#include "scene/tessellate.h"
#include "scene/text_fields.h"

namespace kdrt {

namespace {

constexpr int kMaxPolygonVertices = 1 << 28;
constexpr int kMaxResolution = 65536;

class NffReader {
 public:
  NffReader(const std::string& path, const LoadOptions& options)
      : path_(path), options_(options), builder_(&scene_) {
    text_ = ReadWholeFile(path);
    scene_.source = path;
  }

  Scene Read() {
    while (NextDataLine()) {
      std::string_view key = fields_[0];
      if (key == "v") {
        ExpectFields(1);
        ReadView();
      } else if (key == "b") {
        ExpectFields(4);
        scene_.background = ParseVec3(fields_, 1, Pos(), "background colour");
      } else if (key == "l") {
        if (fields_.size() != 4 && fields_.size() != 7) ExpectFields(4, "or 7");
        Light light;
        light.position = ParseVec3(fields_, 1, Pos(), "light position");
        if (fields_.size() == 7) {
          light.color = ParseVec3(fields_, 4, Pos(), "light colour");
          light.has_color = true;
        }
        scene_.lights.push_back(light);
      } else if (key == "f") {
        ExpectFields(9);
        glm::vec3 rgb = ParseVec3(fields_, 1, Pos(), "fill colour");
        Finish finish;
        finish.kd = ParseFloat(fields_[4], Pos(), "fill Kd");
        finish.ks = ParseFloat(fields_[5], Pos(), "fill Ks");
        finish.shine = ParseFloat(fields_[6], Pos(), "fill Shine");
        for (size_t i = 7; i < 9; ++i) ParseFloat(fields_[i], Pos(), "fill parameter");
        if (finish.kd < 0 || finish.ks < 0 || finish.shine < 0) Fail("fill Kd, Ks and Shine must not be negative");
        builder_.SetColor(rgb, finish);
      } else if (key == "p" || key == "pp") {
        ExpectFields(2);
        ReadPolygon(key == "pp");
      } else if (key == "s") {
        ExpectFields(5);
        ReadSphere();
      } else if (key == "c") {
        ExpectFields(1);
        ReadCone();
      } else {
        Fail("unknown keyword " + QuoteBytes(key));
      }
    }
    if (sliver_cones_ > 0) {
      scene_.warnings.push_back(
          InputError(path_, first_sliver_line_,
                     std::to_string(sliver_cones_) +
                         " cones or cylinders tessellated as one band of slivers more than 16 times longer than "
                         "wide, which kd-tree cells cannot separate (--cone-aspect 4 cuts them into bands, which "
                         "--empty-bonus 0.2 separates within the tree's depth limit; docs/kdtree.md, \"Cylinders "
                         "cut into bands\")")
              .what());
    }
    return std::move(scene_);
  }

 private:
  TextPos Pos() const { return TextPos{&path_, line_no_}; }
  [[noreturn]] void Fail(const std::string& what) const { throw InputError(path_, line_no_, what); }

  // Advances to the next line that is neither blank nor a comment and splits
  // it into fields_. False at the end of the file.
  bool NextDataLine() {
    while (offset_ < text_.size()) {
      size_t end = text_.find('\n', offset_);
      if (end == std::string::npos) end = text_.size();
      std::string_view line(text_.data() + offset_, end - offset_);
      offset_ = end + 1;
      ++line_no_;
      SplitFields(line, &fields_);
      if (fields_.empty() || fields_[0][0] == '#') continue;
      return true;
    }
    return false;
  }

  void ExpectFields(size_t n, const char* alternative = nullptr) const {
    if (fields_.size() == n) return;
    std::string want = std::to_string(n) + (alternative ? std::string(" ") + alternative : "");
    Fail(QuoteBytes(fields_[0]) + " line needs " + want + " fields, got " +
         std::to_string(fields_.size()));
  }

  // The next data line must start with `key` and have `n` fields.
  void ExpectLine(const char* key, size_t n, const char* context) {
    if (!NextDataLine()) {
      throw InputError(path_, line_no_,
                       std::string("file ends inside ") + context + " (expected '" + key + "')");
    }
    if (fields_[0] != key) {
      Fail(std::string("expected '") + key + "' in " + context + ", got '" +
           EscapeBytes(fields_[0]) + "'");
    }
    ExpectFields(n);
  }

  void ReadView() {
    Camera cam;
    const char* ctx = "view block";
    ExpectLine("from", 4, ctx);
    cam.from = ParseVec3(fields_, 1, Pos(), "from");
    ExpectLine("at", 4, ctx);
    cam.at = ParseVec3(fields_, 1, Pos(), "at");
    if (cam.at == cam.from) Fail("'at' equals 'from': no view direction");
    ExpectLine("up", 4, ctx);
    cam.up = ParseVec3(fields_, 1, Pos(), "up");
    glm::dvec3 dir = glm::dvec3(cam.at) - glm::dvec3(cam.from);
    if (glm::cross(dir, glm::dvec3(cam.up)) == glm::dvec3(0.0)) {
      Fail("'up' is zero or parallel to the view direction");
    }
    ExpectLine("angle", 2, ctx);
    cam.angle_deg = ParseFloat(fields_[1], Pos(), "angle");
    if (!(cam.angle_deg > 0.0f && cam.angle_deg < 180.0f)) {
      Fail("angle must be in (0, 180) degrees");
    }
    ExpectLine("hither", 2, ctx);
    cam.hither = ParseFloat(fields_[1], Pos(), "hither");
    if (cam.hither < 0.0f) Fail("hither must not be negative");
    ExpectLine("resolution", 3, ctx);
    cam.width = ParseInt(fields_[1], Pos(), "resolution", 1, kMaxResolution);
    cam.height = ParseInt(fields_[2], Pos(), "resolution", 1, kMaxResolution);
    const long long pixels = static_cast<long long>(cam.width) * cam.height;
    if (pixels > kMaxCameraPixels) {
      Fail("resolution " + std::to_string(cam.width) + " x " + std::to_string(cam.height) + " is " +
           std::to_string(pixels) + " camera rays; at most " + std::to_string(kMaxCameraPixels) +
           " per frame (8192 x 8192)");
    }
    scene_.camera = cam;
  }

  void ReadPolygon(bool patch) {
    const int start_line = line_no_;
    const char* what = patch ? "polygon patch" : "polygon";
    int n = ParseInt(fields_[1], Pos(), "vertex count", 0, kMaxPolygonVertices);
    if (n < 3) {
      Fail(std::string(what) + " with " + std::to_string(n) + " vertices (needs at least 3)");
    }
    const size_t want = patch ? 6 : 3;  // patch lines: x y z nx ny nz
    poly_.clear();
    for (int i = 0; i < n; ++i) {
      if (!NextDataLine()) {
        throw InputError(path_, start_line,
                         std::string(what) + " declares " + std::to_string(n) +
                             " vertices but the file ends after " + std::to_string(i));
      }
      if (fields_.size() != want) {
        Fail(std::string(what) + " vertex " + std::to_string(i + 1) + " of " + std::to_string(n) +
             " needs " + std::to_string(want) + " numbers, got " +
             std::to_string(fields_.size()));
      }
      poly_.push_back(ParseVec3(fields_, 0, Pos(), "vertex"));
      if (patch) ParseVec3(fields_, 3, Pos(), "normal");  // checked, then ignored
    }
    builder_.AddFan(poly_.data(), poly_.size());
  }

  void ReadSphere() {
    glm::vec3 c = ParseVec3(fields_, 1, Pos(), "sphere centre");
    float r = ParseFloat(fields_[4], Pos(), "sphere radius");
    if (!(r > 0.0f)) Fail("sphere radius must be positive");
    AddSphere(builder_, glm::dvec3(c), r, options_.sphere_segments);
  }

  void ReadConeLine(const char* which) {
    if (!NextDataLine()) {
      Fail(std::string("file ends inside cone (expected ") + which + " x y z radius)");
    }
    if (fields_.size() != 4) {
      Fail(std::string("cone ") + which + " line needs 4 numbers (x y z radius), got " +
           std::to_string(fields_.size()));
    }
  }

  void ReadCone() {
    const int cone_line = line_no_;
    ReadConeLine("base");
    glm::vec3 base = ParseVec3(fields_, 0, Pos(), "cone base");
    float rb = ParseFloat(fields_[3], Pos(), "cone base radius");
    ReadConeLine("apex");
    glm::vec3 apex = ParseVec3(fields_, 0, Pos(), "cone apex");
    float ra = ParseFloat(fields_[3], Pos(), "cone apex radius");
    // NFF gives a sign to both radii to mark one-sided surfaces; the shape
    // is the same, so only the magnitude matters here.
    rb = std::fabs(rb);
    ra = std::fabs(ra);
    if (base == apex) Fail("cone apex equals its base");
    if (rb == 0.0f && ra == 0.0f) Fail("cone with both radii zero");
    const glm::dvec3 b(base), a(apex);
    const int segments = options_.cone_segments;
    AddCone(builder_, b, rb, a, ra, segments, ConeBands(b, rb, a, ra, segments, options_.cone_aspect));
    if (options_.cone_aspect == 0.0 && ConeBands(b, rb, a, ra, segments, kSliverAspect) > 1) {
      if (sliver_cones_++ == 0) first_sliver_line_ = cone_line;
    }
  }

  // One band of cells longer than this makes slivers whose boxes fill the
  // kd-tree cells they cross (docs/kdtree.md, "Long thin cylinders").
  static constexpr double kSliverAspect = 16.0;
  int sliver_cones_ = 0;
  int first_sliver_line_ = 0;

  std::string path_;
  LoadOptions options_;
  std::string text_;
  size_t offset_ = 0;
  int line_no_ = 0;
  std::vector<std::string_view> fields_;
  std::vector<glm::vec3> poly_;
  Scene scene_;
  SceneBuilder builder_;
};

}  // namespace

Scene LoadNff(const std::string& path, const LoadOptions& options) {
  return NffReader(path, options).Read();
}

}  // namespace kdrt
