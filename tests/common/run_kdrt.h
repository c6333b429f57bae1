// Runs the kdrt tool built with the tests (KDRT_BIN) and captures its exit
// status and output, for the end-to-end tests of the command line.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace kdrt::testing {

struct RunResult {
  int exit_code;
  std::string output;  // stdout and stderr
};

// Runs a shell command line; stdout and stderr together.
inline RunResult RunCommand(const std::string& command) {
  const std::string cmd = command + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

inline RunResult RunKdrt(const std::string& args) { return RunCommand(std::string(KDRT_BIN) + " " + args); }

}  // namespace kdrt::testing
