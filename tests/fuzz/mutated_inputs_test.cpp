// Mutated scene and ray files through the kdrt tool. A few seed files of each
// kind (tests/fuzz/seeds/, plus binary PLY and ray files made here) are
// mutated with a fixed seed: byte flips, truncation, NaN/Inf/huge numbers,
// wrong counts, garbage, long lines. Every case must end in one of two ways:
//   exit 0 with every output file complete (the JSON parses), or
//   exit 1 with exactly one "kdrt: error: FILE[:LINE]: ..." line and no
//   output file;
// never another exit status, a signal or a hang (a timeout per case), and
// never a raw byte of the file on the terminal. 96 cases by default;
// KDRT_LONG=1 runs 4000; KDRT_FUZZ_CASES=N runs the first N of the same
// sequence and KDRT_FUZZ_CASES=FIRST-END the cases FIRST..END-1 of it (a
// part of the long sequence, e.g. under the sanitizers); KDRT_FUZZ_BIN=PATH
// runs that kdrt binary.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/common/read_file.h"
#include "tests/common/run_kdrt.h"

namespace kdrt {
namespace {

namespace fs = std::filesystem;

// splitmix64: the same cases on every platform and standard library.
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}
  uint64_t Next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  size_t Below(size_t n) { return n == 0 ? 0 : static_cast<size_t>(Next() % n); }

 private:
  uint64_t state_;
};

struct Seed {
  std::string name;  // file name: its extension picks the reader
  std::string bytes;
  bool binary;
};

template <typename T>
void Append(std::string* s, T v, bool big_endian = false) {
  char raw[sizeof(T)];
  std::memcpy(raw, &v, sizeof v);
  if (big_endian) {
    for (size_t i = 0; i < sizeof v / 2; ++i) std::swap(raw[i], raw[sizeof v - 1 - i]);
  }
  s->append(raw, sizeof v);
}

// A binary PLY tetrahedron (float coordinates, a uchar-int face list).
std::string BinaryPly(bool big_endian) {
  std::string s = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
  const float v[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (float f : v) Append(&s, f, big_endian);
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& f : faces) {
    s += '\3';
    for (int i : f) Append(&s, i, big_endian);
  }
  return s;
}

// A version 2 ray file of four closest-hit rays towards plain.nff.
std::string RayFile() {
  std::string s = "KDRTRAYS";
  Append(&s, uint32_t{2});
  Append(&s, uint32_t{4});
  Append(&s, uint32_t{0});
  for (int i = 0; i < 4; ++i) {
    const float r[8] = {0.1f * i, 0.2f, 5, 0, 0, -1, 0, 1e30f};
    for (float f : r) Append(&s, f);
  }
  return s;
}

std::vector<Seed> Seeds() {
  std::vector<Seed> seeds;
  for (const auto& e : fs::directory_iterator(fs::path(KDRT_SOURCE_DIR) / "tests/fuzz/seeds")) {
    seeds.push_back({e.path().filename().string(), kdrt::testing::ReadFile(e.path()), false});
  }
  std::sort(seeds.begin(), seeds.end(), [](const Seed& a, const Seed& b) { return a.name < b.name; });
  seeds.push_back({"little.ply", BinaryPly(false), true});
  seeds.push_back({"big.ply", BinaryPly(true), true});
  seeds.push_back({"four.rays", RayFile(), true});
  return seeds;
}

// Positions of the number-like tokens of a text.
std::vector<std::pair<size_t, size_t>> Numbers(const std::string& s) {
  std::vector<std::pair<size_t, size_t>> out;
  size_t i = 0;
  while (i < s.size()) {
    if (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '-') {
      size_t j = i + 1;
      while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '.' || s[j] == '-')) ++j;
      out.emplace_back(i, j - i);
      i = j;
    } else {
      ++i;
    }
  }
  return out;
}

std::vector<size_t> LineStarts(const std::string& s) {
  std::vector<size_t> starts = {0};
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\n' && i + 1 < s.size()) starts.push_back(i + 1);
  }
  return starts;
}

// One or two mutations of the seed; `what` says which.
std::string Mutate(const Seed& seed, Rng& rng, std::string* what) {
  static const char* const kNumbers[] = {"nan",   "-nan", "inf",        "-inf",         "1e39",  "1e38",
                                         "-3e38", "1e-45", "0",         "-0",           "-1",    "65536",
                                         "2147483648", "99999999999999999999", "0x10", "1e",    "4294967295",
                                         "8192", "1.5"};
  std::string s = seed.bytes;
  const size_t count = 1 + rng.Below(2);
  for (size_t m = 0; m < count; ++m) {
    const size_t kind = rng.Below(seed.binary ? 5 : 9);
    if (s.empty()) s = "x";
    switch (kind) {
      case 0: {  // flip a bit
        s[rng.Below(s.size())] ^= static_cast<char>(1u << rng.Below(8));
        *what += "flip ";
        break;
      }
      case 1: {  // a byte set to a value that matters: NUL, ESC, 0xff, '\n', a digit, a space
        static const char kBytes[] = {'\0', '\x1b', '\xff', '\n', '9', ' ', '\x80', '-'};
        s[rng.Below(s.size())] = kBytes[rng.Below(sizeof kBytes)];
        *what += "byte ";
        break;
      }
      case 2: {  // truncate
        s.resize(rng.Below(s.size() + 1));
        *what += "truncate ";
        break;
      }
      case 3: {  // garbage bytes inserted
        std::string g;
        const size_t n = 1 + rng.Below(24);
        for (size_t i = 0; i < n; ++i) g += static_cast<char>(rng.Below(256));
        s.insert(rng.Below(s.size() + 1), g);
        *what += "garbage ";
        break;
      }
      case 4: {  // a 32-bit word of a binary file (counts, floats) set to an extreme
        static const uint32_t kWords[] = {0, 0xffffffffu, 0x7fc00000u, 0x7f800000u, 0xff800000u,
                                          0x7f7fffffu, 0x80000000u, 1000000u, 3u};
        const uint32_t w = kWords[rng.Below(sizeof kWords / sizeof kWords[0])];
        if (s.size() >= 4) std::memcpy(&s[rng.Below(s.size() - 3)], &w, 4);
        *what += "word ";
        break;
      }
      case 5:
      case 6: {  // a number replaced: NaN, Inf, huge, out of range, a wrong count
        const auto nums = Numbers(s);
        if (nums.empty()) break;
        const auto [at, len] = nums[rng.Below(nums.size())];
        s.replace(at, len, kNumbers[rng.Below(sizeof kNumbers / sizeof kNumbers[0])]);
        *what += "number ";
        break;
      }
      case 7: {  // a line removed or repeated
        const auto starts = LineStarts(s);
        const size_t l = rng.Below(starts.size());
        const size_t end = l + 1 < starts.size() ? starts[l + 1] : s.size();
        const std::string line = s.substr(starts[l], end - starts[l]);
        if (rng.Below(2)) {
          s.erase(starts[l], end - starts[l]);
        } else {
          s.insert(end, line.empty() || line.back() != '\n' ? "\n" + line : line);
        }
        *what += "line ";
        break;
      }
      case 8: {  // a long line
        const std::string longline(20000 + rng.Below(50000), "x 1.0"[rng.Below(5)]);
        s.insert(LineStarts(s)[rng.Below(LineStarts(s).size())], longline + "\n");
        *what += "longline ";
        break;
      }
    }
  }
  return s;
}

enum class Outcome { kOk, kError };

class MutatedInputs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("kdrt_fuzz_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

bool PrintableOutput(const std::string& s) {
  for (unsigned char c : s) {
    if (c != '\n' && (c < 0x20 || c >= 0x7f)) return false;
  }
  return true;
}

// "error 40, ok 50, ok with a warning 6, 0 failing": the count per class.
std::string Summary(const std::map<std::string, int>& classes, int failures) {
  std::string s;
  for (const auto& [k, n] : classes) s += k + " " + std::to_string(n) + ", ";
  return s + std::to_string(failures) + " failing";
}

TEST_F(MutatedInputs, EveryCaseRendersOrFailsCleanly) {
  const bool long_run = std::getenv("KDRT_LONG") != nullptr && std::string(std::getenv("KDRT_LONG")) == "1";
  // About half a second per kdrt run on a loaded two-core machine (process
  // start-up dominates): 96 cases keep the default run near a minute.
  size_t first = 0, cases = long_run ? 4000 : 96;
  if (const char* n = std::getenv("KDRT_FUZZ_CASES")) {
    unsigned long a = 0, b = 0;
    int used = 0;
    const bool range = std::sscanf(n, "%lu-%lu%n", &a, &b, &used) == 2 && n[used] == '\0' && a < b;
    const bool count = !range && std::sscanf(n, "%lu%n", &b, &used) == 1 && n[used] == '\0' && b > 0;
    ASSERT_TRUE(range || count) << "KDRT_FUZZ_CASES=" << n << ": expected N or FIRST-END (cases FIRST..END-1)";
    first = range ? a : 0;
    cases = b;
  }
  // KDRT_FUZZ_BIN: the corpus through another build of the tool (a
  // sanitizer build's kdrt, with this binary built as usual).
  const std::string kdrt = std::getenv("KDRT_FUZZ_BIN") ? std::getenv("KDRT_FUZZ_BIN") : KDRT_BIN;
  const std::vector<Seed> seeds = Seeds();
  const std::string scene_for_rays = (fs::path(KDRT_SOURCE_DIR) / "tests/fuzz/seeds/plain.nff").string();
  Rng rng(20261203);
  std::map<std::string, int> classes;  // "ok", "warning", "error"
  int failures = 0;
  size_t done = 0;  // fewer than `cases` when ten have failed
  for (size_t c = 0; c < cases && failures < 10; ++c) {
    const Seed& seed = seeds[c % seeds.size()];
    std::string what;
    // The first cases are the seeds themselves: they must render, warning-free.
    const std::string bytes = c < seeds.size() ? seed.bytes : Mutate(seed, rng, &what);
    if (c < first) continue;  // the mutation is made all the same: the sequence stays the same
    const std::string input = (dir_ / seed.name).string();
    std::ofstream(input, std::ios::binary) << bytes;
    const std::string out_png = (dir_ / "out.png").string(), out_json = (dir_ / "out.json").string();
    const std::string ext = fs::path(seed.name).extension().string();
    std::string cmd;
    std::vector<std::string> outputs = {out_json};
    if (ext == ".rays") {
      cmd = "render " + scene_for_rays + " --rays " + input + " -q -o " + out_png + " --json " + out_json;
      outputs.push_back(out_png);
    } else if (c % 3 == 1 && ext != ".nff") {  // info traces the scene's camera: NFF sets its size
      cmd = "info " + input + " --json " + out_json;
    } else if (c % 3 == 2) {
      cmd = "sim --model fast -q " + input + " --res 4x4 -o " + out_png + " --json " + out_json;
      outputs.push_back(out_png);
    } else {
      cmd = "render " + input + " -q --res 8x8 -o " + out_png + " --json " + out_json;
      outputs.push_back(out_png);
    }
    const testing::RunResult r =
        testing::RunCommand("timeout -s KILL 60 " + kdrt + " " + cmd);
    const std::string label = "case " + std::to_string(c) + " (" + seed.name + ": " + what + "): kdrt " + cmd;
    auto fail = [&](const std::string& why) {
      ++failures;
      // Kept for a look: the input that failed.
      const fs::path kept = fs::temp_directory_path() / ("kdrt_fuzz_case_" + std::to_string(c) + ext);
      std::ofstream(kept, std::ios::binary) << bytes;
      ADD_FAILURE() << label << "\n" << why << "\noutput:\n" << r.output << "\ninput kept in " << kept.string();
    };
    if (!PrintableOutput(r.output)) fail("raw bytes in the output");
    if (r.exit_code == 0) {
      bool complete = true;
      for (const std::string& o : outputs) complete &= fs::exists(o) && fs::file_size(o) > 0;
      nlohmann::json j;
      try {
        std::ifstream(out_json) >> j;
      } catch (const std::exception&) {
        complete = false;
      }
      if (!complete) fail("exit 0 without complete outputs");
      if (c < seeds.size() && r.output.find("warning") != std::string::npos) fail("a seed gives a warning");
      ++classes[r.output.find("kdrt: warning: ") != std::string::npos ? "ok with a warning" : "ok"];
    } else if (r.exit_code == 1) {
      // Exactly one error line, naming the input (or, for a ray file, the
      // ray file: the scene is a fixed seed) with an optional line number.
      std::istringstream lines(r.output);
      std::string line;
      int errors = 0;
      bool named = false;
      const std::regex named_line("kdrt: error: " + std::regex_replace(input, std::regex(R"([.^$|()\[\]{}*+?\\])"),
                                                                       R"(\$&)") +
                                  "(:[0-9]+)?: .+");
      while (std::getline(lines, line)) {
        if (line.rfind("kdrt: error: ", 0) == 0) {
          ++errors;
          named |= std::regex_match(line, named_line);
        } else if (line.rfind("kdrt: warning: ", 0) != 0 && line.rfind("kdrt: note: ", 0) != 0) {
          fail("unexpected line: " + line);
        }
      }
      if (errors != 1 || !named) fail("expected exactly one 'kdrt: error: " + input + "[:LINE]: ...' line");
      if (c < seeds.size()) fail("a seed fails");
      ++classes["error"];
    } else {
      fail("exit status " + std::to_string(r.exit_code) + (r.exit_code == 137 ? " (killed: a hang?)" : ""));
    }
    for (const auto& e : fs::directory_iterator(dir_)) {
      const bool output = std::find(outputs.begin(), outputs.end(), e.path().string()) != outputs.end();
      if (e.path() != input && !(r.exit_code == 0 && output)) fail("left behind: " + e.path().string());
    }
    for (const auto& e : fs::directory_iterator(dir_)) fs::remove_all(e.path());
    done = c + 1;
    // A long run (minutes to hours) says how far it is.
    if ((c + 1) % 250 == 0 && c + 1 < cases) {
      std::printf("mutated inputs: cases %zu..%zu of %zu..%zu: %s\n", first, c, first, cases - 1,
                  Summary(classes, failures).c_str());
      std::fflush(stdout);
    }
  }
  std::printf("mutated inputs: cases %zu..%zu of %zu..%zu from %zu seeds: %s\n", first, done - 1, first, cases - 1,
              seeds.size(), Summary(classes, failures).c_str());
  if (done - first >= 96) {  // the mutations reach the error paths and leave some files readable
    EXPECT_GT(classes["error"], 0);
    EXPECT_GT(classes["ok"], 0);
  }
}

}  // namespace
}  // namespace kdrt
