// Errors that reach the user. Every bad input becomes an InputError whose
// message already names the file, the line (when there is one) and what is
// wrong; the CLI prints it and exits non-zero.
#pragma once

#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace kdrt {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
  // "file:line: what"; line 0 means the file as a whole.
  InputError(const std::string& file, int line, const std::string& what)
      : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) +
                           ": " + what) {}
};

// Bytes of an input file as they may appear in a message: printable ASCII as
// is, a backslash doubled, every other byte (control characters, ESC,
// invalid or any non-ASCII UTF-8) as \xHH, so a message never carries raw
// bytes of the file to the terminal. At most `max` bytes of `s` are shown
// ("..." marks the cut). The one quoting every reader uses.
inline std::string EscapeBytes(std::string_view s, size_t max = 40) {
  std::string out;
  for (size_t i = 0; i < s.size() && i < max; ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c == '\\') {
      out += "\\\\";
    } else if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  if (s.size() > max) out += "...";
  return out;
}

// EscapeBytes in single quotes: 'field'.
inline std::string QuoteBytes(std::string_view s, size_t max = 40) { return "'" + EscapeBytes(s, max) + "'"; }

}  // namespace kdrt
