#include "scene/text_fields.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "common/error.h"

namespace kdrt {

void SplitFields(std::string_view line, std::vector<std::string_view>* fields) {
  fields->clear();
  size_t i = 0;
  const size_t n = line.size();
  while (i < n) {
    while (i < n && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    size_t start = i;
    while (i < n && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) fields->push_back(line.substr(start, i - start));
  }
}

bool LineCursor::Next(std::vector<std::string_view>* fields, bool skip_comments) {
  while (offset_ < text_.size()) {
    size_t end = text_.find('\n', offset_);
    if (end == std::string::npos) end = text_.size();
    std::string_view line(text_.data() + offset_, end - offset_);
    offset_ = end + 1;
    ++line_;
    if (skip_comments) line = line.substr(0, line.find('#'));
    SplitFields(line, fields);
    if (fields->empty() && skip_comments) continue;
    return true;
  }
  return false;
}

void FailNotFinite(const TextPos& pos, const std::string& what) {
  throw InputError(*pos.file, pos.line, what + " is not finite (NaN or Inf)");
}

namespace {

std::string Quote(std::string_view s) { return QuoteBytes(s); }

// from_chars rejects a leading '+', which C's printf never writes but
// hand-written files sometimes do. A second sign after it stays, so that
// from_chars still rejects "+-1".
std::string_view WithoutPlus(std::string_view field) {
  if (field.size() >= 2 && field[0] == '+' && field[1] != '+' && field[1] != '-') {
    field.remove_prefix(1);
  }
  return field;
}

}  // namespace

bool ParseDouble(std::string_view field, double* value) {
  std::string_view digits = WithoutPlus(field);
  const char* end = digits.data() + digits.size();
  auto [ptr, ec] = std::from_chars(digits.data(), end, *value);
  return ec == std::errc() && ptr == end && !digits.empty();
}

bool ParseFloatBits(std::string_view field, float* value) {
  std::string_view digits = WithoutPlus(field);
  const char* end = digits.data() + digits.size();
  auto [ptr, ec] = std::from_chars(digits.data(), end, *value);
  if (ec == std::errc::result_out_of_range && ptr == end) {
    // Beyond float's range: the IEEE result (an infinity, or a zero), which
    // the caller's finiteness check then names.
    double wide;
    if (!ParseDouble(field, &wide)) return false;
    *value = static_cast<float>(wide);
    return true;
  }
  return ec == std::errc() && ptr == end && !digits.empty();
}

bool ParseInteger(std::string_view field, long long* value) {
  std::string_view digits = WithoutPlus(field);
  const char* end = digits.data() + digits.size();
  auto [ptr, ec] = std::from_chars(digits.data(), end, *value);
  return ec == std::errc() && ptr == end && !digits.empty();
}

float ParseFloat(std::string_view field, const TextPos& pos, const char* what) {
  std::string_view digits = WithoutPlus(field);
  float value = 0.0f;
  const char* end = digits.data() + digits.size();
  auto [ptr, ec] = std::from_chars(digits.data(), end, value);
  if (ec == std::errc::result_out_of_range) {
    throw InputError(*pos.file, pos.line,
                     std::string(what) + " " + Quote(field) + " is out of float range");
  }
  if (ec != std::errc() || ptr != end || digits.empty()) {
    throw InputError(*pos.file, pos.line,
                     std::string(what) + ": expected a number, got " + Quote(field));
  }
  RequireFinite(value, pos, [&] { return std::string(what) + " " + Quote(field); });
  return value;
}

int ParseInt(std::string_view field, const TextPos& pos, const char* what, int lo, int hi) {
  long long value = 0;
  const char* end = field.data() + field.size();
  auto [ptr, ec] = std::from_chars(field.data(), end, value);
  if (ec == std::errc::result_out_of_range || (ec == std::errc() && ptr == end &&
                                               (value < lo || value > hi))) {
    throw InputError(*pos.file, pos.line,
                     std::string(what) + " " + Quote(field) + " is outside " +
                         std::to_string(lo) + ".." + std::to_string(hi));
  }
  if (ec != std::errc() || ptr != end) {
    throw InputError(*pos.file, pos.line,
                     std::string(what) + ": expected an integer, got " + Quote(field));
  }
  return static_cast<int>(value);
}

glm::vec3 ParseVec3(const std::vector<std::string_view>& f, size_t first, const TextPos& pos,
                    const char* what) {
  return glm::vec3(ParseFloat(f[first], pos, what), ParseFloat(f[first + 1], pos, what),
                   ParseFloat(f[first + 2], pos, what));
}

std::string ReadWholeFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, 0, "no such file");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, 0, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open file");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(path, 0, "read error");
  return ss.str();
}

}  // namespace kdrt
