// Helpers for the scene tests: a private temporary directory and a check
// that an InputError names the file and the line.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "common/error.h"

namespace kdrt::testing {

class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "kdrt_scene_XXXXXX").string();
    char* made = mkdtemp(tmpl.data());
    if (made == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = made;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string File(const std::string& name) const { return path_ + "/" + name; }
  std::string Write(const std::string& name, const std::string& text) const {
    std::string p = File(name);
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Runs `fn`, expects an InputError whose message starts with
// "<file>:<line>: " (or "<file>: " for line 0) and contains `fragment`.
template <typename Fn>
void ExpectInputError(Fn fn, const std::string& file, int line, const std::string& fragment) {
  try {
    fn();
    ADD_FAILURE() << "no InputError; expected one at " << file << ":" << line;
  } catch (const InputError& e) {
    std::string msg = e.what();
    std::string prefix = file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": ";
    EXPECT_EQ(msg.rfind(prefix, 0), 0u) << "message: " << msg << "\nexpected prefix: " << prefix;
    EXPECT_NE(msg.find(fragment), std::string::npos)
        << "message: " << msg << "\nexpected to contain: " << fragment;
  }
}

}  // namespace kdrt::testing
