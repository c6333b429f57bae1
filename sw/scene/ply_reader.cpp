// PLY (Stanford polygon file): ASCII and binary little/big-endian, read in
// one pass that checks everything as it goes, so a broken file always fails
// with file:line (text) or element and index (binary) and never yields a
// partial scene. kdrt needs `x y z` of the `vertex` element and the
// `vertex_indices` (or `vertex_index`) list of the `face` element; every
// other value is checked for syntax and skipped. Faces are fanned in file
// order (the numbering contract). Data after the declared elements is left
// out with a warning (Scene::warnings; --strict refuses it).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/error.h"
#include "scene/loaders.h"
#include "scene/ply_header.h"
#include "scene/scene_builder.h"
#include "scene/text_fields.h"

namespace kdrt {

namespace {

// Values of ASCII data: one element entry per line, blank lines skipped.
class AsciiValues {
 public:
  AsciiValues(const std::string& path, LineCursor* lines) : path_(path), lines_(lines) {}

  void BeginEntry(const PlyElement& e, uint64_t i) {
    element_ = &e;
    index_ = i;
    next_ = 0;
    do {
      if (!lines_->Next(&fields_, false)) {
        throw InputError(path_, lines_->line(),
                         "file ends in PLY element " + QuoteBytes(e.name) + " after " + std::to_string(i) +
                             " of " + std::to_string(e.count));
      }
    } while (fields_.empty());
  }
  void EndEntry() {
    if (next_ != fields_.size()) Fail("too many values");
  }

  float Coordinate(PlyType t) {
    std::string_view s = Next();
    if (t == PlyType::kFloat32) {
      float v;
      if (ParseFloatBits(s, &v)) return v;
    } else if (t == PlyType::kFloat64) {
      double v;
      if (ParseDouble(s, &v)) return static_cast<float>(v);
    } else {
      long long v;
      if (ParseInteger(s, &v)) return static_cast<float>(v);
    }
    Fail(Quote(s) + " is not a number of type " + TypeName(t));
  }
  // The token decides, whatever the declared type: "3" in a float list is 3.
  long long Integer(PlyType /*type*/, const char* what) {
    std::string_view s = Next();
    long long v;
    if (!ParseInteger(s, &v)) Fail(std::string(what) + " " + Quote(s) + " is not an integer");
    return v;
  }
  void Skip(PlyType t) {
    std::string_view s = Next();
    double d;
    long long i;
    if (IsFloatType(t) ? !ParseDouble(s, &d) : !ParseInteger(s, &i)) {
      Fail(Quote(s) + " is not a number of type " + TypeName(t));
    }
  }
  void SkipItems(PlyType t, long long n) {
    for (long long j = 0; j < n; ++j) Skip(t);
  }

  TextPos Pos() const { return TextPos{&path_, lines_->line()}; }
  std::string Where() const { return EscapeBytes(element_->name) + " " + std::to_string(index_); }
  [[noreturn]] void Fail(const std::string& what) const {
    throw InputError(path_, lines_->line(), Where() + ": " + what);
  }

 private:
  std::string_view Next() {
    if (next_ >= fields_.size()) Fail("too few values");
    return fields_[next_++];
  }
  static std::string Quote(std::string_view s) { return QuoteBytes(s); }
  static const char* TypeName(PlyType t) {
    return IsFloatType(t) ? "float" : "integer";
  }

  const std::string& path_;
  LineCursor* lines_;
  std::vector<std::string_view> fields_;
  size_t next_ = 0;
  const PlyElement* element_ = nullptr;
  uint64_t index_ = 0;
};

template <typename T>
double Load(const unsigned char* raw) {
  T v;
  std::memcpy(&v, raw, sizeof v);
  return static_cast<double>(v);
}

// Values of binary data (little-endian host assumed, as on x86 and arm).
class BinaryValues {
 public:
  BinaryValues(const std::string& path, const std::string& bytes, size_t offset, bool big_endian)
      : path_(path), bytes_(bytes), pos_(offset), big_endian_(big_endian) {}

  void BeginEntry(const PlyElement& e, uint64_t i) {
    element_ = &e;
    index_ = i;
  }
  void EndEntry() {}

  // A double holds every PLY value exactly, so this rounds once.
  float Coordinate(PlyType t) { return static_cast<float>(Read(t)); }
  long long Integer(PlyType t, const char* what) {
    const double v = Read(t);
    if (v != std::floor(v) || std::fabs(v) > 1e18) Fail(std::string(what) + " is not an integer");
    return static_cast<long long>(v);
  }
  void Skip(PlyType t) { SkipItems(t, 1); }
  void SkipItems(PlyType t, long long n) {
    // n < 2^62 keeps n * size from wrapping around.
    const size_t left = bytes_.size() - pos_;
    if (static_cast<unsigned long long>(n) > left || static_cast<size_t>(n) * PlySize(t) > left) {
      Fail("file ends inside PLY binary data");
    }
    const size_t size = static_cast<size_t>(n) * PlySize(t);
    pos_ += size;
  }

  TextPos Pos() const { return TextPos{&path_, 0}; }
  std::string Where() const { return EscapeBytes(element_->name) + " " + std::to_string(index_); }
  [[noreturn]] void Fail(const std::string& what) const {
    throw InputError(path_, 0, Where() + ": " + what);
  }
  size_t BytesLeft() const { return bytes_.size() - pos_; }

 private:
  double Read(PlyType t) {
    const size_t n = PlySize(t);
    if (n > bytes_.size() - pos_) Fail("file ends inside PLY binary data");
    unsigned char raw[8];
    std::memcpy(raw, bytes_.data() + pos_, n);
    pos_ += n;
    if (big_endian_) {
      for (size_t i = 0; i < n / 2; ++i) std::swap(raw[i], raw[n - 1 - i]);
    }
    switch (t) {
      case PlyType::kInt8:
        return Load<int8_t>(raw);
      case PlyType::kUint8:
        return Load<uint8_t>(raw);
      case PlyType::kInt16:
        return Load<int16_t>(raw);
      case PlyType::kUint16:
        return Load<uint16_t>(raw);
      case PlyType::kInt32:
        return Load<int32_t>(raw);
      case PlyType::kUint32:
        return Load<uint32_t>(raw);
      case PlyType::kFloat32:
        return Load<float>(raw);
      case PlyType::kFloat64:
        return Load<double>(raw);
    }
    return 0.0;
  }

  const std::string& path_;
  const std::string& bytes_;
  size_t pos_;
  bool big_endian_;
  const PlyElement* element_ = nullptr;
  uint64_t index_ = 0;
};

// The element walk shared by both encodings; `Values` supplies the numbers.
template <typename Values>
void ReadData(const PlyHeader& header, Values* in, SceneBuilder* builder) {
  std::vector<glm::vec3> vertices;
  std::vector<glm::vec3> polygon;
  for (const PlyElement& e : header.elements) {
    const bool is_vertex = e.name == "vertex";
    const bool is_face = e.name == "face";
    if (is_vertex) vertices.reserve(e.count);
    for (uint64_t i = 0; i < e.count; ++i) {
      in->BeginEntry(e, i);
      glm::vec3 xyz(0.0f);  // a missing coordinate property reads as 0, as in assimp
      for (const PlyProperty& p : e.props) {
        if (p.role == PlyRole::kX || p.role == PlyRole::kY || p.role == PlyRole::kZ) {
          const int axis = p.role == PlyRole::kX ? 0 : p.role == PlyRole::kY ? 1 : 2;
          xyz[axis] = in->Coordinate(p.type);
          RequireFinite(xyz[axis], in->Pos(), [&] { return in->Where() + ": coordinate " + p.name; });
          continue;
        }
        const long long n = p.is_list ? in->Integer(p.count_type, "list length") : 1;
        if (n < 0) in->Fail("negative list length");
        if (!p.is_list) {
          in->Skip(p.type);
        } else if (p.role != PlyRole::kFaceIndices) {
          in->SkipItems(p.type, n);
        } else {
          if (n < 3) in->Fail("face with " + std::to_string(n) + " vertices (needs at least 3)");
          polygon.clear();  // a second index list replaces the first, as in assimp
          for (long long j = 0; j < n; ++j) {
            const long long v = in->Integer(p.type, "vertex index");
            if (v < 0 || static_cast<uint64_t>(v) >= vertices.size()) {
              in->Fail("vertex index " + std::to_string(v) + " out of range (" +
                       std::to_string(vertices.size()) + " vertices)");
            }
            polygon.push_back(vertices[v]);
          }
        }
      }
      in->EndEntry();
      if (is_vertex) vertices.push_back(xyz);
      if (is_face) builder->AddFan(polygon.data(), polygon.size());
    }
  }
}

// "vertex 4, face 1": the header's elements and counts, for messages.
std::string DeclaredElements(const PlyHeader& header) {
  std::string s;
  for (const PlyElement& e : header.elements) {
    s += (s.empty() ? "" : ", ") + EscapeBytes(e.name) + " " + std::to_string(e.count);
  }
  return s;
}

}  // namespace

Scene LoadPly(const std::string& path, const LoadOptions& options) {
  const std::string bytes = ReadWholeFile(path);
  LineCursor lines(bytes);
  const PlyHeader header = ReadPlyHeader(path, bytes, &lines);
  Scene scene;
  scene.source = path;
  SceneBuilder builder(&scene);
  const std::string declared = DeclaredElements(header);
  if (header.format == PlyFormat::kAscii) {
    AsciiValues in(path, &lines);
    ReadData(header, &in, &builder);
    std::vector<std::string_view> f;
    int first = 0;
    long more = 0;
    while (lines.Next(&f, false)) {
      if (f.empty()) continue;
      if (more++ == 0) first = lines.line();
    }
    if (more > 0) {
      IgnoredData(&scene, options, path, first,
                  std::to_string(more) + " line" + (more > 1 ? "s" : "") + " after the declared elements (" +
                      declared + ") left out");
    }
  } else {
    BinaryValues in(path, bytes, std::min(bytes.size(), lines.offset()),
                    header.format == PlyFormat::kBinaryBig);
    ReadData(header, &in, &builder);
    if (in.BytesLeft() > 0) {
      IgnoredData(&scene, options, path, 0,
                  std::to_string(in.BytesLeft()) + " bytes after the declared elements (" + declared +
                      ") left out");
    }
  }
  return scene;
}

}  // namespace kdrt
