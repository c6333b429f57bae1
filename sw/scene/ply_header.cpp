#include "scene/ply_header.h"

#include <algorithm>
#include <string_view>

#include "common/error.h"

namespace kdrt {

size_t PlySize(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 1;
}

bool IsFloatType(PlyType t) { return t == PlyType::kFloat32 || t == PlyType::kFloat64; }

namespace {

bool ParsePlyType(std::string_view s, PlyType* t) {
  struct Name {
    const char* a;
    const char* b;
    PlyType t;
  };
  static const Name kNames[] = {
      {"char", "int8", PlyType::kInt8},       {"uchar", "uint8", PlyType::kUint8},
      {"short", "int16", PlyType::kInt16},    {"ushort", "uint16", PlyType::kUint16},
      {"int", "int32", PlyType::kInt32},      {"uint", "uint32", PlyType::kUint32},
      {"float", "float32", PlyType::kFloat32}, {"double", "float64", PlyType::kFloat64}};
  for (const Name& n : kNames) {
    if (s == n.a || s == n.b) {
      *t = n.t;
      return true;
    }
  }
  return false;
}

PlyRole RoleOf(const PlyElement& e, const PlyProperty& p) {
  if (e.name == "vertex" && !p.is_list) {
    if (p.name == "x") return PlyRole::kX;
    if (p.name == "y") return PlyRole::kY;
    if (p.name == "z") return PlyRole::kZ;
  }
  if (e.name == "face" && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
    return PlyRole::kFaceIndices;
  }
  return PlyRole::kSkip;
}

// The fewest bytes one entry of `e` can take, to reject absurd counts before
// anything is allocated.
size_t MinEntryBytes(const PlyElement& e, PlyFormat format) {
  if (format == PlyFormat::kAscii) return e.props.size();  // one character per value
  size_t n = 0;
  for (const PlyProperty& p : e.props) n += PlySize(p.is_list ? p.count_type : p.type);
  return n;
}

}  // namespace

PlyHeader ReadPlyHeader(const std::string& path, const std::string& bytes, LineCursor* lines) {
  auto fail = [&](int line, const std::string& what) { throw InputError(path, line, what); };
  std::vector<std::string_view> f;
  if (!lines->Next(&f, false) || f.size() != 1 || f[0] != "ply") {
    fail(1, "not a PLY file (first line must be 'ply')");
  }
  PlyHeader h;
  bool have_format = false;
  while (true) {
    if (!lines->Next(&f, false)) fail(lines->line(), "PLY header has no end_header line");
    if (f.empty()) continue;
    const int line = lines->line();
    if (f[0] == "end_header") break;
    if (f[0] == "comment" || f[0] == "obj_info") continue;
    if (f[0] == "format") {
      if (f.size() != 3) fail(line, "PLY format line needs 2 fields");
      if (f[1] == "ascii") {
        h.format = PlyFormat::kAscii;
      } else if (f[1] == "binary_little_endian") {
        h.format = PlyFormat::kBinaryLittle;
      } else if (f[1] == "binary_big_endian") {
        h.format = PlyFormat::kBinaryBig;
      } else {
        fail(line, "unknown PLY format " + QuoteBytes(f[1]));
      }
      have_format = true;
    } else if (f[0] == "element") {
      long long count = 0;
      if (f.size() != 3 || !ParseInteger(f[2], &count) || count < 0) {
        fail(line, "PLY element line needs a name and a count");
      }
      PlyElement e;
      e.name = std::string(f[1]);
      e.count = static_cast<uint64_t>(count);
      e.line = line;
      // Readers such as assimp 5.2 misread these (strips lose triangles, a
      // second face element loses faces, a second vertex element replaces
      // the first); an error is better than a wrong scene.
      for (const PlyElement& before : h.elements) {
        if (before.name == e.name && (e.name == "vertex" || e.name == "face")) {
          fail(line, "second PLY '" + e.name + "' element");
        }
      }
      if (e.name == "tristrips") fail(line, "PLY 'tristrips' elements are not supported");
      h.elements.push_back(e);
    } else if (f[0] == "property") {
      if (h.elements.empty()) fail(line, "PLY property before any element");
      PlyProperty p;
      bool ok;
      if (f.size() == 5 && f[1] == "list") {
        p.is_list = true;
        ok = ParsePlyType(f[2], &p.count_type) && ParsePlyType(f[3], &p.type) &&
             !IsFloatType(p.count_type);
        p.name = std::string(f[4]);
      } else {
        ok = f.size() == 3 && ParsePlyType(f[1], &p.type);
        p.name = std::string(f.size() == 3 ? f[2] : std::string_view());
      }
      if (!ok) fail(line, "malformed PLY property line");
      p.role = RoleOf(h.elements.back(), p);
      h.elements.back().props.push_back(p);
    } else {
      fail(line, "unknown PLY header keyword " + QuoteBytes(f[0]));
    }
  }
  if (!have_format) fail(lines->line(), "PLY header has no format line");
  const size_t data_bytes = bytes.size() - std::min(bytes.size(), lines->offset());
  bool have_vertex = false;
  for (const PlyElement& e : h.elements) {
    have_vertex |= e.name == "vertex";
    if (e.count == 0) continue;
    if (e.props.empty()) fail(e.line, "PLY element without properties");
    if (e.count > data_bytes / MinEntryBytes(e, h.format)) {
      fail(e.line, "PLY element " + QuoteBytes(e.name) + " count exceeds the file size");
    }
    if (e.name != "face") continue;
    // Faces are fanned as they are read, so their vertices must be known.
    if (!have_vertex) fail(e.line, "PLY face element without a vertex element before it");
    bool has_indices = false;
    for (const PlyProperty& p : e.props) has_indices |= p.role == PlyRole::kFaceIndices;
    if (!has_indices) fail(e.line, "PLY face element has no vertex_indices list");
  }
  return h;
}

}  // namespace kdrt
