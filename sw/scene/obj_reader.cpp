// Wavefront OBJ through tinyobjloader, with its triangulation turned off so
// polygons are fanned here in file order (the numbering contract).
// tinyobjloader silently reads a malformed number as 0 and does not say on
// which line a face is wrong, so kdrt's own pass over the `v` and `f` lines
// is the one validation: numbers, face sizes and indices, with file:line.
// What tinyobjloader then returns is used as is (it also reads the .mtl
// colours and keeps tinyobjloader's rounding of the numbers). Statements
// that are not OBJ, and points, lines, curves and surfaces (not polygons),
// are left out with a warning per keyword (Scene::warnings; --strict
// refuses them).
#include <algorithm>
#include <charconv>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <tiny_obj_loader.h>

#include "common/error.h"
#include "scene/loaders.h"
#include "scene/scene_builder.h"
#include "scene/text_fields.h"

namespace kdrt {

namespace {

// One face corner "v", "v/t", "v//n" or "v/t/n": only the position index
// matters; OBJ indices start at 1 and negative ones count back from the
// latest vertex.
void CheckCorner(std::string_view corner, long vertices, const TextPos& pos) {
  std::string_view index = corner.substr(0, corner.find('/'));
  long value = 0;
  const char* end = index.data() + index.size();
  auto [ptr, ec] = std::from_chars(index.data(), end, value);
  if (ec != std::errc() || ptr != end || index.empty()) {
    throw InputError(*pos.file, pos.line,
                     "face vertex " + QuoteBytes(corner) + " is not an index");
  }
  if (value == 0 || value > vertices || value < -vertices) {
    throw InputError(*pos.file, pos.line,
                     "face vertex index " + std::to_string(value) + " is out of range (" +
                         std::to_string(vertices) + " vertices so far)");
  }
}

// OBJ statements without geometry kdrt would draw, or read by tinyobjloader.
bool IsObjStatement(std::string_view key) {
  static const char* const kKeys[] = {"v",      "vt",     "vn",       "vp",       "f",          "g",
                                      "o",      "s",      "usemtl",   "mtllib",   "cstype",     "deg",
                                      "bmat",   "step",   "parm",     "trim",     "hole",       "scrv",
                                      "sp",     "end",    "con",      "mg",       "bevel",      "c_interp",
                                      "d_interp", "lod",  "shadow_obj", "trace_obj", "ctech",   "stech",
                                      "maplib", "usemap", "call",     "csh"};
  return std::find(std::begin(kKeys), std::end(kKeys), key) != std::end(kKeys);
}

// Geometry that is not a polygon: read by no part of kdrt.
bool IsNonPolygonGeometry(std::string_view key) {
  return key == "p" || key == "l" || key == "curv" || key == "curv2" || key == "surf";
}

struct Ignored {
  int first_line = 0;
  long count = 0;
};

void CheckObjText(const std::string& path, const LoadOptions& options, Scene* scene) {
  const std::string text = ReadWholeFile(path);
  LineCursor lines(text);
  std::vector<std::string_view> fields;
  long vertices = 0;
  std::map<std::string, Ignored> ignored;  // by keyword
  while (lines.Next(&fields, false)) {
    if (fields.empty() || fields[0][0] == '#') continue;
    const int line_no = lines.line();
    const TextPos pos{&path, line_no};
    if (!IsObjStatement(fields[0])) {
      Ignored& i = ignored[std::string(fields[0])];
      if (i.count++ == 0) i.first_line = line_no;
      if (options.strict) break;  // the first one is refused below
      continue;
    }
    if (fields[0] == "v") {
      // x y z, optionally w, or x y z r g b (vertex colours).
      if (fields.size() != 4 && fields.size() != 5 && fields.size() != 7) {
        throw InputError(path, line_no,
                         "vertex line needs 3, 4 or 6 numbers, got " +
                             std::to_string(fields.size() - 1));
      }
      for (size_t i = 1; i < fields.size(); ++i) ParseFloat(fields[i], pos, "vertex coordinate");
      ++vertices;
    } else if (fields[0] == "f") {
      if (fields.size() < 4) {
        throw InputError(path, line_no,
                         "face with " + std::to_string(fields.size() - 1) +
                             " vertices (needs at least 3)");
      }
      for (size_t i = 1; i < fields.size(); ++i) CheckCorner(fields[i], vertices, pos);
    }
  }
  // One warning per keyword, in the order of their first lines.
  std::vector<std::pair<std::string, Ignored>> by_line(ignored.begin(), ignored.end());
  std::sort(by_line.begin(), by_line.end(),
            [](const auto& a, const auto& b) { return a.second.first_line < b.second.first_line; });
  for (const auto& [key, i] : by_line) {
    const std::string what = IsNonPolygonGeometry(key) ? "OBJ statement " + QuoteBytes(key) +
                                                             " (not a polygon) left out"
                                                       : "unknown OBJ statement " + QuoteBytes(key) + " left out";
    const std::string more = i.count > 1 ? " (" + std::to_string(i.count) + " lines)" : "";
    IgnoredData(scene, options, path, i.first_line, what + more);
  }
}

}  // namespace

Scene LoadObj(const std::string& path, const LoadOptions& options) {
  Scene scene;
  CheckObjText(path, options, &scene);

  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    std::string err = reader.Error();
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    throw InputError(path, 0, "OBJ: " + (err.empty() ? std::string("cannot parse") : EscapeBytes(err, 200)));
  }
  const std::vector<tinyobj::real_t>& xyz = reader.GetAttrib().vertices;
  const std::vector<tinyobj::material_t>& materials = reader.GetMaterials();

  scene.source = path;
  SceneBuilder builder(&scene);
  std::vector<glm::vec3> polygon;
  // tinyobjloader keeps faces in file order within a shape, and shapes in
  // the order their groups start.
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t next = 0;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const size_t n = mesh.num_face_vertices[f];
      polygon.clear();
      // Checked accesses: not a second validation (CheckObjText vouches for
      // the indices), only so that a disagreement with tinyobjloader can
      // never read out of bounds.
      for (size_t k = 0; k < n; ++k) {
        const size_t vi = static_cast<size_t>(mesh.indices.at(next + k).vertex_index);
        polygon.emplace_back(xyz.at(3 * vi), xyz.at(3 * vi + 1), xyz.at(3 * vi + 2));
      }
      next += n;
      int mat = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      if (mat >= 0 && static_cast<size_t>(mat) < materials.size()) {
        const tinyobj::real_t* kd = materials[mat].diffuse;
        builder.SetColor(glm::vec3(kd[0], kd[1], kd[2]));
      } else {
        builder.SetColor(glm::vec3(1.0f));
      }
      builder.AddFan(polygon.data(), polygon.size());
    }
  }
  return scene;
}

}  // namespace kdrt
