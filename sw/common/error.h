// Errors that reach the user. Every bad input becomes an InputError whose
// message already names the file, the line (when there is one) and what is
// wrong; the CLI prints it and exits non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace kdrt {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
  // "file:line: what"; line 0 means the file as a whole.
  InputError(const std::string& file, int line, const std::string& what)
      : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) +
                           ": " + what) {}
};

}  // namespace kdrt
