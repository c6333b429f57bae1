// OFF (Geomview object file format), text only: an `[ST][C][N]OFF` header,
// the counts `vertices faces [edges]`, then one vertex and one face per line;
// '#' comments and blank lines anywhere. kdrt takes x y z of each vertex and
// the indices of each face (fanned in file order, the numbering contract);
// colours, normals and texture coordinates are checked as numbers and
// ignored. One pass checks and reads. Lines after the declared faces are
// left out with a warning (Scene::warnings; --strict refuses them).
#include <string>
#include <string_view>
#include <vector>

#include "common/error.h"
#include "scene/loaders.h"
#include "scene/scene_builder.h"
#include "scene/text_fields.h"

namespace kdrt {

Scene LoadOff(const std::string& path, const LoadOptions& options) {
  const std::string bytes = ReadWholeFile(path);
  LineCursor lines(bytes);
  std::vector<std::string_view> f;
  auto fail = [&](const std::string& what) { throw InputError(path, lines.line(), what); };
  auto need_line = [&](const std::string& what) {
    if (!lines.Next(&f, true)) fail("file ends before " + what);
  };
  auto quote = [](std::string_view s) { return QuoteBytes(s); };

  need_line("the OFF header");
  const std::string_view magic = f[0];
  const bool ok_magic = magic.size() >= 3 && magic.substr(magic.size() - 3) == "OFF" &&
                        magic.find_first_not_of("STCN") == magic.size() - 3;
  if (!ok_magic) fail("not an OFF file (expected 'OFF' header)");
  if (f.size() > 1 && f[1] == "BINARY") fail("binary OFF is not supported");
  std::vector<std::string_view> counts(f.begin() + 1, f.end());
  if (counts.empty()) {
    need_line("the vertex and face counts");
    counts = f;
  }
  long long nv = -1, nf = -1;
  if (counts.size() < 2 || counts.size() > 3 || !ParseInteger(counts[0], &nv) ||
      !ParseInteger(counts[1], &nf) || nv < 0 || nf < 0) {
    fail("OFF counts line needs 'vertices faces [edges]'");
  }
  if (static_cast<unsigned long long>(nv) > bytes.size() ||
      static_cast<unsigned long long>(nf) > bytes.size()) {
    fail("OFF counts exceed the file size");
  }

  std::vector<glm::vec3> vertices;
  vertices.reserve(static_cast<size_t>(nv));
  for (long long i = 0; i < nv; ++i) {
    need_line("vertex " + std::to_string(i) + " of " + std::to_string(nv));
    if (f.size() < 3) fail("OFF vertex needs x y z");
    const TextPos pos{&path, lines.line()};
    glm::vec3 v;
    for (int axis = 0; axis < 3; ++axis) {
      if (!ParseFloatBits(f[axis], &v[axis])) {
        fail("vertex coordinate: expected a number, got " + quote(f[axis]));
      }
      RequireFinite(v[axis], pos, [&] { return "vertex coordinate " + quote(f[axis]); });
    }
    double ignored;
    for (size_t k = 3; k < f.size(); ++k) {
      if (!ParseDouble(f[k], &ignored)) fail("OFF vertex has a non-number " + quote(f[k]));
    }
    vertices.push_back(v);
  }

  Scene scene;
  scene.source = path;
  SceneBuilder builder(&scene);
  std::vector<glm::vec3> polygon;
  for (long long i = 0; i < nf; ++i) {
    need_line("face " + std::to_string(i) + " of " + std::to_string(nf));
    long long n = 0;
    if (!ParseInteger(f[0], &n)) fail("OFF face needs a vertex count");
    if (n < 3) fail("face with " + std::to_string(n) + " vertices (needs at least 3)");
    if (n > static_cast<long long>(f.size()) - 1) fail("OFF face has fewer indices than its count");
    // Values after the indices (a face colour) are ignored.
    polygon.clear();
    for (long long k = 1; k <= n; ++k) {
      long long idx;
      if (!ParseInteger(f[k], &idx) || idx < 0 || idx >= nv) {
        fail("OFF face vertex " + quote(f[k]) + " is not an index in 0.." + std::to_string(nv - 1));
      }
      polygon.push_back(vertices[idx]);
    }
    builder.AddFan(polygon.data(), polygon.size());
  }
  int first = 0;
  long more = 0;
  while (lines.Next(&f, true)) {
    if (more++ == 0) first = lines.line();
  }
  if (more > 0) {
    IgnoredData(&scene, options, path, first,
                std::to_string(more) + " line" + (more > 1 ? "s" : "") + " after the declared " +
                    std::to_string(nv) + " vertices and " + std::to_string(nf) + " faces left out");
  }
  return scene;
}

}  // namespace kdrt
