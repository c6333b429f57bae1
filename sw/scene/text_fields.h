// Line and number scanning shared by the text loaders. Numbers are read with
// std::from_chars: locale-independent and correctly rounded straight to
// float, so "%.9g" output reads back bit-exactly, and a number reads to the
// same bits in NFF, OBJ, PLY and OFF.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace kdrt {

// Splits on spaces and tabs; a trailing '\r' is dropped.
void SplitFields(std::string_view line, std::vector<std::string_view>* fields);

// A reader's position, for "file:line: what" messages.
struct TextPos {
  const std::string* file;
  int line;
};

// Line cursor over a text (or the text header of a binary file).
class LineCursor {
 public:
  explicit LineCursor(const std::string& text) : text_(text) {}
  // Splits the next line into `fields`; false at the end. With
  // `skip_comments`, '#' to the end of the line is dropped and blank lines are
  // skipped.
  bool Next(std::vector<std::string_view>* fields, bool skip_comments);
  int line() const { return line_; }      // 1-based number of the last line read
  size_t offset() const { return offset_; }  // first byte after that line

 private:
  const std::string& text_;
  size_t offset_ = 0;
  int line_ = 0;
};

// The one rule every format applies to a number that becomes scene data: it
// must be finite. Throws "file:line: <what()> is not finite (NaN or Inf)";
// `what` is only called then, so hot loops build no message.
[[noreturn]] void FailNotFinite(const TextPos& pos, const std::string& what);
template <typename What>
void RequireFinite(float value, const TextPos& pos, const What& what) {
  if (!std::isfinite(value)) FailNotFinite(pos, what());
}

// Throw InputError at `pos` unless the whole field is a finite float / an int
// in [lo, hi]. `what` names the field in the message.
float ParseFloat(std::string_view field, const TextPos& pos, const char* what);
int ParseInt(std::string_view field, const TextPos& pos, const char* what, int lo, int hi);

// Syntax checks without a message: true if the whole field is a number
// (double range; "nan" and "inf" included) / an integer.
bool ParseDouble(std::string_view field, double* value);
// The whole field as the nearest float (the rounding ParseFloat uses, so a
// number reads to the same bits in every format).
bool ParseFloatBits(std::string_view field, float* value);
bool ParseInteger(std::string_view field, long long* value);

// Three consecutive fields starting at `first`.
glm::vec3 ParseVec3(const std::vector<std::string_view>& f, size_t first, const TextPos& pos,
                    const char* what);

// Reads a whole file; InputError if it cannot.
std::string ReadWholeFile(const std::string& path);

}  // namespace kdrt
