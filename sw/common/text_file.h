// Small helpers for text files the tools read back (build and synthesis logs).
#pragma once

#include <cstddef>
#include <fstream>
#include <string>
#include <vector>

namespace kdrt {

// The last `lines` lines of a text file, each ending in '\n' ("" if the file
// cannot be read): the part of a failed tool's log worth showing.
inline std::string LastLines(const std::string& path, size_t lines) {
  std::ifstream f(path);
  std::vector<std::string> all;
  std::string line;
  while (std::getline(f, line)) all.push_back(line);
  std::string out;
  for (size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) out += all[i] + "\n";
  return out;
}

}  // namespace kdrt
