#include "scene/mesh_check.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

#include "common/error.h"
#include "scene/text_fields.h"

namespace kdrt {

namespace {

// Line cursor over a text (or the text part of a binary file).
class Lines {
 public:
  explicit Lines(const std::string& bytes) : bytes_(bytes) {}
  // Next line split into fields; `skip_comments` drops '#' to end of line
  // and blank lines. False at the end.
  bool Next(std::vector<std::string_view>* fields, bool skip_comments) {
    while (offset_ < bytes_.size()) {
      size_t end = bytes_.find('\n', offset_);
      if (end == std::string::npos) end = bytes_.size();
      std::string_view line(bytes_.data() + offset_, end - offset_);
      offset_ = end + 1;
      ++line_;
      if (skip_comments) line = line.substr(0, line.find('#'));
      SplitFields(line, fields);
      if (fields->empty() && skip_comments) continue;
      return true;
    }
    return false;
  }
  int line() const { return line_; }
  size_t offset() const { return offset_; }

 private:
  const std::string& bytes_;
  size_t offset_ = 0;
  int line_ = 0;
};

bool ParseNumber(std::string_view s, double* value) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, *value);
  return ec == std::errc() && ptr == end && !s.empty();
}

bool ParseIndex(std::string_view s, long long* value) {
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, *value);
  return ec == std::errc() && ptr == end && !s.empty();
}

// ---------------------------------------------------------------- PLY

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

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

template <typename T>
double Load(const unsigned char* raw) {
  T v;
  std::memcpy(&v, raw, sizeof v);
  return static_cast<double>(v);
}

bool IsFloatType(PlyType t) { return t == PlyType::kFloat32 || t == PlyType::kFloat64; }

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // item type for lists
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> props;
  int line = 0;
};

enum class PlyFormat { kAscii, kBinaryLittle, kBinaryBig };

// What the checks need to know about a property.
enum class Role { kOther, kCoordinate, kFaceIndices };

Role RoleOf(const PlyElement& e, const PlyProperty& p) {
  if (e.name == "vertex" && !p.is_list && (p.name == "x" || p.name == "y" || p.name == "z")) {
    return Role::kCoordinate;
  }
  if (e.name == "face" && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
    return Role::kFaceIndices;
  }
  return Role::kOther;
}

class PlyChecker {
 public:
  PlyChecker(const std::string& path, const std::string& bytes)
      : path_(path), bytes_(bytes), lines_(bytes) {}

  void Run() {
    ReadHeader();
    if (format_ == PlyFormat::kAscii) {
      CheckAscii();
    } else {
      CheckBinary();
    }
  }

 private:
  [[noreturn]] void Fail(int line, const std::string& what) const {
    throw InputError(path_, line, what);
  }

  void ReadHeader() {
    std::vector<std::string_view> f;
    if (!lines_.Next(&f, false) || f.size() != 1 || f[0] != "ply") {
      Fail(1, "not a PLY file (first line must be 'ply')");
    }
    bool have_format = false;
    while (true) {
      if (!lines_.Next(&f, false)) Fail(lines_.line(), "PLY header has no end_header line");
      if (f.empty()) continue;
      const int line = lines_.line();
      if (f[0] == "end_header") break;
      if (f[0] == "comment" || f[0] == "obj_info") continue;
      if (f[0] == "format") {
        if (f.size() != 3) Fail(line, "PLY format line needs 2 fields");
        if (f[1] == "ascii") {
          format_ = PlyFormat::kAscii;
        } else if (f[1] == "binary_little_endian") {
          format_ = PlyFormat::kBinaryLittle;
        } else if (f[1] == "binary_big_endian") {
          format_ = PlyFormat::kBinaryBig;
        } else {
          Fail(line, "unknown PLY format '" + std::string(f[1].substr(0, 40)) + "'");
        }
        have_format = true;
      } else if (f[0] == "element") {
        long long count = 0;
        if (f.size() != 3 || !ParseIndex(f[2], &count) || count < 0) {
          Fail(line, "PLY element line needs a name and a count");
        }
        PlyElement e;
        e.name = std::string(f[1]);
        e.count = static_cast<uint64_t>(count);
        e.line = line;
        elements_.push_back(e);
      } else if (f[0] == "property") {
        if (elements_.empty()) Fail(line, "PLY property before any element");
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
        if (!ok) Fail(line, "malformed PLY property line");
        elements_.back().props.push_back(p);
      } else {
        Fail(line, "unknown PLY header keyword '" + std::string(f[0].substr(0, 40)) + "'");
      }
    }
    if (!have_format) Fail(lines_.line(), "PLY header has no format line");
    for (const PlyElement& e : elements_) {
      if (e.name == "vertex") vertices_ = e.count;
      if (e.count > 0 && e.props.empty()) Fail(e.line, "PLY element without properties");
      // Every entry takes at least one byte, so a count beyond the file size
      // can only be a broken header (and must not reach an allocator).
      if (e.count > bytes_.size()) {
        Fail(e.line, "PLY element '" + e.name + "' count exceeds the file size");
      }
    }
  }

  void CheckIndexCount(long long n, const std::string& where, int line) const {
    if (n < 3) {
      Fail(line, where + ": face with " + std::to_string(n) + " vertices (needs at least 3)");
    }
  }
  void CheckIndex(long long idx, const std::string& where, int line) const {
    if (idx < 0 || static_cast<uint64_t>(idx) >= vertices_) {
      Fail(line, where + ": vertex index " + std::to_string(idx) + " out of range (" +
                     std::to_string(vertices_) + " vertices)");
    }
  }

  void CheckAscii() {
    std::vector<std::string_view> f;
    for (const PlyElement& e : elements_) {
      for (uint64_t i = 0; i < e.count; ++i) {
        const std::string where = e.name + " " + std::to_string(i);
        do {
          if (!lines_.Next(&f, false)) {
            Fail(lines_.line(), "file ends in PLY element '" + e.name + "' after " +
                                    std::to_string(i) + " of " + std::to_string(e.count));
          }
        } while (f.empty());
        const int line = lines_.line();
        size_t k = 0;
        auto next = [&]() -> std::string_view {
          if (k >= f.size()) Fail(line, where + ": too few values");
          return f[k++];
        };
        for (const PlyProperty& p : e.props) {
          Role role = RoleOf(e, p);
          if (!p.is_list) {
            std::string_view tok = next();
            double v;
            if (!ParseNumber(tok, &v)) {
              Fail(line, where + ": '" + std::string(tok.substr(0, 40)) + "' is not a number");
            }
            if (role == Role::kCoordinate && !std::isfinite(static_cast<float>(v))) {
              Fail(line, where + ": coordinate " + p.name + " is NaN or Inf");
            }
            continue;
          }
          long long n;
          std::string_view tok = next();
          if (!ParseIndex(tok, &n) || n < 0) Fail(line, where + ": bad list length");
          if (role == Role::kFaceIndices) CheckIndexCount(n, where, line);
          for (long long j = 0; j < n; ++j) {
            std::string_view item = next();
            double v;
            long long idx;
            if (role == Role::kFaceIndices) {
              if (!ParseIndex(item, &idx)) Fail(line, where + ": vertex index is not an integer");
              CheckIndex(idx, where, line);
            } else if (!ParseNumber(item, &v)) {
              Fail(line, where + ": '" + std::string(item.substr(0, 40)) + "' is not a number");
            }
          }
        }
        if (k != f.size()) Fail(line, where + ": too many values");
      }
    }
  }

  double ReadBinary(PlyType t, size_t* pos, const std::string& where) const {
    size_t n = PlySize(t);
    if (*pos + n > bytes_.size()) Fail(0, where + ": file ends inside PLY binary data");
    unsigned char raw[8];
    std::memcpy(raw, bytes_.data() + *pos, n);
    *pos += n;
    if (format_ == PlyFormat::kBinaryBig) {
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

  void CheckBinary() {
    size_t pos = lines_.offset();
    for (const PlyElement& e : elements_) {
      for (uint64_t i = 0; i < e.count; ++i) {
        const std::string where = e.name + " " + std::to_string(i);
        for (const PlyProperty& p : e.props) {
          Role role = RoleOf(e, p);
          if (!p.is_list) {
            double v = ReadBinary(p.type, &pos, where);
            if (role == Role::kCoordinate && !std::isfinite(static_cast<float>(v))) {
              Fail(0, where + ": coordinate " + p.name + " is NaN or Inf");
            }
            continue;
          }
          long long n = static_cast<long long>(ReadBinary(p.count_type, &pos, where));
          if (n < 0) Fail(0, where + ": negative list length");
          if (role == Role::kFaceIndices) CheckIndexCount(n, where, 0);
          if (role != Role::kFaceIndices) {
            size_t skip = static_cast<size_t>(n) * PlySize(p.type);
            if (pos + skip > bytes_.size()) Fail(0, where + ": file ends inside PLY binary data");
            pos += skip;
            continue;
          }
          for (long long j = 0; j < n; ++j) {
            double idx = ReadBinary(p.type, &pos, where);
            if (idx != std::floor(idx)) Fail(0, where + ": vertex index is not an integer");
            CheckIndex(static_cast<long long>(idx), where, 0);
          }
        }
      }
    }
  }

  const std::string& path_;
  const std::string& bytes_;
  Lines lines_;
  PlyFormat format_ = PlyFormat::kAscii;
  std::vector<PlyElement> elements_;
  uint64_t vertices_ = 0;
};

}  // namespace

void CheckPly(const std::string& path, const std::string& bytes) { PlyChecker(path, bytes).Run(); }

// ---------------------------------------------------------------- OFF

void CheckOff(const std::string& path, const std::string& bytes) {
  Lines lines(bytes);
  std::vector<std::string_view> f;
  auto need_line = [&](const std::string& what) {
    if (!lines.Next(&f, true)) throw InputError(path, lines.line(), "file ends before " + what);
  };
  need_line("the OFF header");
  std::string_view magic = f[0];
  bool ok_magic = magic.size() >= 3 && magic.substr(magic.size() - 3) == "OFF" &&
                  magic.find_first_not_of("STCN") == magic.size() - 3;
  if (!ok_magic) throw InputError(path, lines.line(), "not an OFF file (expected 'OFF' header)");
  if (f.size() > 1 && f[1] == "BINARY") {
    throw InputError(path, lines.line(), "binary OFF is not supported");
  }
  std::vector<std::string_view> counts(f.begin() + 1, f.end());
  if (counts.empty()) {
    need_line("the vertex and face counts");
    counts = f;
  }
  const int count_line = lines.line();
  long long nv = -1, nf = -1;
  if (counts.size() < 2 || counts.size() > 3 || !ParseIndex(counts[0], &nv) ||
      !ParseIndex(counts[1], &nf) || nv < 0 || nf < 0) {
    throw InputError(path, count_line, "OFF counts line needs 'vertices faces [edges]'");
  }
  if (static_cast<unsigned long long>(nv) > bytes.size() ||
      static_cast<unsigned long long>(nf) > bytes.size()) {
    throw InputError(path, count_line, "OFF counts exceed the file size");
  }
  const TextPos pos{&path, 0};
  for (long long i = 0; i < nv; ++i) {
    need_line("vertex " + std::to_string(i) + " of " + std::to_string(nv));
    TextPos here{pos.file, lines.line()};
    if (f.size() < 3) throw InputError(path, lines.line(), "OFF vertex needs x y z");
    ParseVec3(f, 0, here, "vertex coordinate");
    double v;
    for (size_t k = 3; k < f.size(); ++k) {
      if (!ParseNumber(f[k], &v)) {
        throw InputError(path, lines.line(), "OFF vertex has a non-number");
      }
    }
  }
  for (long long i = 0; i < nf; ++i) {
    need_line("face " + std::to_string(i) + " of " + std::to_string(nf));
    long long n = 0;
    if (!ParseIndex(f[0], &n)) {
      throw InputError(path, lines.line(), "OFF face needs a vertex count");
    }
    if (n < 3) {
      throw InputError(path, lines.line(),
                       "face with " + std::to_string(n) + " vertices (needs at least 3)");
    }
    if (static_cast<long long>(f.size()) < n + 1) {
      throw InputError(path, lines.line(), "OFF face has fewer indices than its count");
    }
    for (long long k = 1; k <= n; ++k) {
      long long idx;
      if (!ParseIndex(f[k], &idx) || idx < 0 || idx >= nv) {
        throw InputError(path, lines.line(),
                         "OFF face vertex '" + std::string(f[k].substr(0, 40)) +
                             "' is not an index in 0.." + std::to_string(nv - 1));
      }
    }
  }
}

}  // namespace kdrt
