// Line and number scanning shared by the text loaders. Numbers are read with
// std::from_chars: locale-independent and correctly rounded straight to
// float, so "%.9g" output reads back bit-exactly.
#pragma once

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

// Throw InputError at `pos` unless the whole field is a finite float / an int
// in [lo, hi]. `what` names the field in the message.
float ParseFloat(std::string_view field, const TextPos& pos, const char* what);
int ParseInt(std::string_view field, const TextPos& pos, const char* what, int lo, int hi);

// Three consecutive fields starting at `first`.
glm::vec3 ParseVec3(const std::vector<std::string_view>& f, size_t first, const TextPos& pos,
                    const char* what);

// Reads a whole file; InputError if it cannot.
std::string ReadWholeFile(const std::string& path);

}  // namespace kdrt
