#include "trade/area.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/text_file.h"

namespace kdrt::trade {
namespace {

namespace fs = std::filesystem;

// rt_core's units (see CoreArea in area.h for what is left out and why).
const char* const kFormatUnits[] = {"rt_trav_unit", "rt_clip_unit", "rt_ray_setup", "rt_isect_unit",
                                    "rt_hit_out",   "rt_leaf_exit", "rt_hit_merge"};
const char* const kFixedUnits[] = {"rt_list_unit", "rt_mem_system", "rt_thread_fsm", "rt_perf_events"};

const char* const kTablePath = "docs/synth-table.md";
const char* const kScriptPath = "scripts/synth-unit.sh";

struct Numbers {
  int64_t cells = 0;
  int64_t flip_flops = 0;
  int depth = 0;
  int64_t sram_bits = 0;
};

// The quantities the estimate fits, in Fit::coef's order.
constexpr int kQuantities = 4;
double Quantity(const Numbers& n, int q) {
  return q == 0 ? n.cells : q == 1 ? n.flip_flops : q == 2 ? n.depth : n.sram_bits;
}

// One unit at one format; plain units (no E and M) have their defaults.
struct UnitKey {
  std::string unit;
  bool plain = false;
  int e = 0, m = 0;

  // The cache file's suffix: "e4m3" or "default".
  std::string Suffix() const { return plain ? "default" : "e" + std::to_string(e) + "m" + std::to_string(m); }
  std::string FormatName() const { return plain ? "defaults" : fp::Format{e, m}.Name(); }
  std::string Label() const { return unit + " " + FormatName(); }
};

// A unit's numbers and, for the detail text, where they were found.
struct Found {
  UnitArea area;
  std::string where;
};

std::string SourceDir(const AreaOptions& o) { return o.source_dir.empty() ? KDRT_TRADE_SOURCE_DIR : o.source_dir; }
std::string CacheDir(const AreaOptions& o) {
  return o.cache_dir.empty() ? std::string(KDRT_TRADE_BUILD_DIR) + "/synth-cache" : o.cache_dir;
}

std::string Percent(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * fraction);
  return buf;
}

std::string Trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::optional<int64_t> ParseCount(const std::string& s) {
  if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return std::stoll(s);
}

// ---- docs/synth-table.md ----

struct TableRow {
  UnitKey key;
  Numbers n;
};

// The rows of scripts/synth.sh's markdown table; FAILED rows are skipped (no
// numbers). A missing file is an empty table: the cache and synthesis remain.
std::vector<TableRow> ReadSynthTable(const std::string& path) {
  std::vector<TableRow> rows;
  std::ifstream in(path);
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    // The unit table comes first; the default core's table follows a heading.
    if (line.rfind("## ", 0) == 0) break;
    if (line.rfind("|", 0) != 0) continue;
    std::vector<std::string> cols;
    std::stringstream ss(line.substr(1));
    std::string col;
    while (std::getline(ss, col, '|')) cols.push_back(Trim(col));
    // | unit | preset | latency | cells | flip-flops | depth | SRAM bits |
    if (cols.size() < 6 || cols[0] == "unit" || cols[0].rfind("---", 0) == 0) continue;
    const auto cells = ParseCount(cols[3]), ffs = ParseCount(cols[4]), depth = ParseCount(cols[5]);
    if (!cells || !ffs || !depth) {
      if (cols[3].rfind("FAILED", 0) == 0) continue;
      throw InputError(path, lineno, "expected numbers of cells, flip-flops and logic depth");
    }
    TableRow row;
    row.key.unit = cols[0];
    if (cols[1] == "defaults") {
      row.key.plain = true;
    } else {
      fp::Format f;
      try {
        f = fp::ParseFormat(cols[1]);
      } catch (const InputError& e) {
        throw InputError(path, lineno, e.what());
      }
      row.key.e = f.e;
      row.key.m = f.m;
    }
    row.n = {*cells, *ffs, static_cast<int>(*depth), 0};
    if (cols.size() >= 7 && !cols[6].empty()) {
      const auto bits = ParseCount(cols[6]);
      if (!bits) throw InputError(path, lineno, "expected a number of SRAM bits, not '" + cols[6] + "'");
      row.n.sram_bits = *bits;
    }
    rows.push_back(row);
  }
  return rows;
}

std::optional<Numbers> FindInTable(const std::vector<TableRow>& table, const UnitKey& key) {
  for (const TableRow& r : table) {
    if (r.key.unit == key.unit && r.key.plain == key.plain && (key.plain || (r.key.e == key.e && r.key.m == key.m))) {
      return r.n;
    }
  }
  return std::nullopt;
}

// ---- the cache of on-demand syntheses ----

std::string CachePath(const std::string& dir, const UnitKey& key, const char* ext) {
  return dir + "/" + key.unit + "_" + key.Suffix() + ext;
}

// synth-unit.sh's JSON, if it is there and is about this unit and format;
// anything else counts as missing (and is overwritten by a new synthesis).
std::optional<Numbers> ReadCached(const std::string& path, const UnitKey& key) {
  std::ifstream f(path);
  if (!f) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(f);
    if (j.at("unit").get<std::string>() != key.unit) return std::nullopt;
    if (key.plain ? !(j.at("E").is_null() && j.at("M").is_null())
                  : (j.at("E").get<int>() != key.e || j.at("M").get<int>() != key.m)) {
      return std::nullopt;
    }
    // A unit that keeps SRAM must have been synthesized so (an older
    // cache file without the bits is stale).
    if (KeepsSram(key.unit) && !j.contains("sram_bits")) return std::nullopt;
    return Numbers{j.at("cells").get<int64_t>(), j.at("flip_flops").get<int64_t>(), j.at("depth").get<int>(),
                   j.value("sram_bits", int64_t{0})};
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

// ---- the estimate ----

// cells, flip-flops, depth and SRAM bits of one unit as a + b*W + c*p^2 with
// W = 1+E+M the word width and p = M+1 the significand width: registers,
// delay lines, muxes and memories (the stacks' intervals, the hit records'
// u and v) grow with W, the multipliers with p^2 (adders and shifters
// with p are absorbed by the other two terms). Checked against synthesis when
// written: max residual 2.7 % on the presets (a quadratic in p alone: 7.1 %);
// e6m12, between the presets, within 3 % per unit and 0.0 % on the core's
// cells; e4m3, extrapolated, within 18 % per unit and 2.4 % on the core (the
// quadratic in p: 35 % and 7 %). Depth is the weakest: 3-5 gates high.
std::array<double, 3> Basis(int e, int m) { return {1.0, 1.0 + e + m, (m + 1.0) * (m + 1.0)}; }

struct Fit {
  std::array<double, 3> coef[kQuantities] = {};  // [cells, flip-flops, depth, SRAM bits][a, b, c]
  double residual = 0;                 // max relative residual on the fitted rows
  int points = 0;
  int w_min = 0, w_max = 0, p_min = 0, p_max = 0;  // the fitted rows' range

  Numbers At(int e, int m) const {
    const std::array<double, 3> x = Basis(e, m);
    double v[kQuantities];
    for (int q = 0; q < kQuantities; ++q) {
      v[q] = std::max(0.0, std::round(coef[q][0] * x[0] + coef[q][1] * x[1] + coef[q][2] * x[2]));
    }
    return {static_cast<int64_t>(v[0]), static_cast<int64_t>(v[1]), static_cast<int>(v[2]),
            static_cast<int64_t>(v[3])};
  }
};

// Least squares through the normal equations (3x3, Gauss-Jordan with partial
// pivoting): well enough conditioned for W <= 32, p <= 24. nullopt when the
// rows do not determine the three coefficients.
std::optional<std::array<double, 3>> LeastSquares(const std::vector<std::array<double, 3>>& x,
                                                  const std::vector<double>& y) {
  double a[3][4] = {};
  for (size_t i = 0; i < x.size(); ++i) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) a[r][c] += x[i][r] * x[i][c];
      a[r][3] += x[i][r] * y[i];
    }
  }
  const double scale = std::max({std::fabs(a[0][0]), std::fabs(a[1][1]), std::fabs(a[2][2])});
  for (int col = 0; col < 3; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 3; ++r) {
      if (std::fabs(a[r][col]) > std::fabs(a[pivot][col])) pivot = r;
    }
    std::swap(a[col], a[pivot]);
    if (std::fabs(a[col][col]) <= 1e-12 * scale) return std::nullopt;
    for (int r = 0; r < 3; ++r) {
      if (r == col) continue;
      const double k = a[r][col] / a[col][col];
      for (int c = col; c < 4; ++c) a[r][c] -= k * a[col][c];
    }
  }
  return std::array<double, 3>{a[0][3] / a[0][0], a[1][3] / a[1][1], a[2][3] / a[2][2]};
}

double RelativeError(double estimate, double actual) {
  return std::fabs(estimate - actual) / std::max(1.0, std::fabs(actual));
}

Fit FitUnit(const std::vector<TableRow>& table, const std::string& unit) {
  std::vector<const TableRow*> rows;
  for (const TableRow& r : table) {
    if (r.key.unit == unit && !r.key.plain) rows.push_back(&r);
  }
  const auto no_fit = [&]() {
    return InputError("cannot estimate the area of " + unit + ": its " + std::to_string(rows.size()) + " rows in " +
                      kTablePath + " do not determine the fit (run `make synth`, or synthesize instead)");
  };
  if (rows.size() < 3) throw no_fit();
  Fit fit;
  fit.points = static_cast<int>(rows.size());
  fit.w_min = fit.p_min = 1 << 20;
  std::vector<std::array<double, 3>> x;
  for (const TableRow* r : rows) {
    x.push_back(Basis(r->key.e, r->key.m));
    fit.w_min = std::min(fit.w_min, 1 + r->key.e + r->key.m);
    fit.w_max = std::max(fit.w_max, 1 + r->key.e + r->key.m);
    fit.p_min = std::min(fit.p_min, r->key.m + 1);
    fit.p_max = std::max(fit.p_max, r->key.m + 1);
  }
  for (int q = 0; q < kQuantities; ++q) {
    std::vector<double> y;
    for (const TableRow* r : rows) y.push_back(Quantity(r->n, q));
    const auto coef = LeastSquares(x, y);
    if (!coef) throw no_fit();
    fit.coef[q] = *coef;
  }
  // On the rounded values that At() returns, so that the bound in Area holds
  // as reported.
  for (const TableRow* r : rows) {
    const Numbers e = fit.At(r->key.e, r->key.m);
    for (int q = 0; q < kQuantities; ++q) {
      fit.residual = std::max(fit.residual, RelativeError(Quantity(e, q), Quantity(r->n, q)));
    }
  }
  return fit;
}

// ---- synthesis ----

struct Job {
  UnitKey key;
  std::string json, log;
};

std::string FindBash() {
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "");
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/bash";
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "/bin/bash";
}

// Runs `bash script args...` with stdout and stderr to `log`; its exit status.
// Everything the child needs is prepared before fork: other threads may be
// forking too.
int RunScript(const std::string& bash, const std::vector<std::string>& args, const std::string& log) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(bash.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) _exit(126);
    dup2(fd, 1);
    dup2(fd, 2);
    close(fd);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Synthesizes the jobs, up to options.jobs at once; stops starting new ones
// after a failure, and throws InputError for the first one that failed.
void Synthesize(const std::vector<Job>& jobs, const std::string& script, const AreaOptions& options) {
  if (jobs.empty()) return;
  if (!fs::exists(script)) {
    throw InputError("cannot synthesize " + jobs.front().key.Label() + ": no " + script +
                     " (or estimate the area instead)");
  }
  const std::string bash = FindBash();
  std::mutex mu;  // guards progress, failure
  std::optional<std::string> failure;
  std::atomic<size_t> next{0};
  auto report = [&](const std::string& message) {
    if (options.progress) options.progress(message);
  };
  auto worker = [&]() {
    while (true) {
      const size_t i = next++;
      if (i >= jobs.size()) return;
      const Job& job = jobs[i];
      const std::string count = " (" + std::to_string(i + 1) + "/" + std::to_string(jobs.size()) + ")";
      {
        std::lock_guard<std::mutex> lock(mu);
        if (failure) return;
        report("synthesizing " + job.key.Label() + " with Yosys" + count + "...");
      }
      const auto start = std::chrono::steady_clock::now();
      const std::string e = job.key.plain ? "-" : std::to_string(job.key.e);
      const std::string m = job.key.plain ? "-" : std::to_string(job.key.m);
      int rc;
      try {
        std::vector<std::string> args = {script, job.key.unit, e, m, job.json};
        if (KeepsSram(job.key.unit)) args.insert(args.begin() + 1, "--sram");
        rc = RunScript(bash, args, job.log);
      } catch (const std::exception& ex) {
        std::lock_guard<std::mutex> lock(mu);
        if (!failure) failure = "synthesizing " + job.key.Label() + ": " + ex.what();
        return;
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::lock_guard<std::mutex> lock(mu);
      if (rc != 0 || !ReadCached(job.json, job.key)) {
        if (!failure) {
          const std::string tail = LastLines(job.log, 20);
          const bool no_yosys = tail.find("command not found") != std::string::npos;
          failure = "synthesizing " + job.key.Label() + " failed (" + script + " exit status " + std::to_string(rc) +
                    "; log " + job.log + "). Its end:\n" + tail +
                    (no_yosys ? "(Yosys is not installed, or set YOSYS=path; an estimate needs no synthesis)" : "");
        }
        return;
      }
      char buf[64];
      std::snprintf(buf, sizeof buf, " in %.0f s", seconds);
      report("synthesized " + job.key.Label() + buf + count);
    }
  };
  const size_t n = std::min(jobs.size(), static_cast<size_t>(std::max(1, options.jobs)));
  std::vector<std::thread> pool;
  for (size_t t = 0; t < n; ++t) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  if (failure) throw InputError(*failure);
}

// ---- putting a format together ----

void CheckHasRtl(const fp::Format& f) {
  if (f.IsFp64() || f.e < 2 || f.e > 8 || f.m < 1 || f.m > 23) {
    throw InputError("no area for number format " + f.Name() +
                     ": the RTL exists for 2 <= exponent bits <= 8 and 1 <= mantissa bits <= 23 only");
  }
}

// "4 units from docs/synth-table.md; 7 units from estimate: ...": one group
// per place, in the order first seen; just the place when there is one.
std::string Detail(const std::vector<Found>& found) {
  std::vector<std::pair<std::string, int>> groups;
  for (const Found& f : found) {
    auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == f.where; });
    if (it == groups.end()) {
      groups.emplace_back(f.where, 1);
    } else {
      ++it->second;
    }
  }
  if (groups.size() == 1) return groups.front().first;
  std::string out;
  for (const auto& [where, count] : groups) {
    out += (out.empty() ? "" : "; ") + std::to_string(count) + (count == 1 ? " unit from " : " units from ") + where;
  }
  return out;
}

Area Sum(const std::vector<Found>& found) {
  Area a;
  bool estimated = false, synthesized = false;
  for (const Found& f : found) {
    a.cells += f.area.cells;
    a.flip_flops += f.area.flip_flops;
    a.sram_bits += f.area.sram_bits;
    a.depth = std::max(a.depth, f.area.depth);
    a.max_residual = std::max(a.max_residual, f.area.residual);
    estimated |= f.area.source == "estimate";
    synthesized |= f.area.source == "yosys";
    a.units.push_back(f.area);
  }
  a.source = estimated ? "estimate" : synthesized ? "yosys" : "cache";
  a.detail = Detail(found);
  return a;
}

std::string EstimateWhere(const Fit& fit, const fp::Format& f, double max_residual) {
  std::string s = "estimate: per-unit least-squares fit a + b*W + c*p^2 (W = 1+E+M, p = M+1) to the " +
                  std::to_string(fit.points) + " presets of " + kTablePath + ", max residual " +
                  Percent(max_residual) + " on them";
  const int w = 1 + f.e + f.m, p = f.m + 1;
  if (w < fit.w_min || w > fit.w_max || p < fit.p_min || p > fit.p_max) {
    s += ", extrapolated to W = " + std::to_string(w) + ", p = " + std::to_string(p) + " (presets: W " +
         std::to_string(fit.w_min) + ".." + std::to_string(fit.w_max) + ", p " + std::to_string(fit.p_min) + ".." +
         std::to_string(fit.p_max) + ")";
  }
  return s;
}

void Set(Found& out, const Numbers& n, const std::string& source, std::string where) {
  out.area.cells = n.cells;
  out.area.flip_flops = n.flip_flops;
  out.area.depth = n.depth;
  out.area.sram_bits = n.sram_bits;
  out.area.source = source;
  out.where = std::move(where);
}

// Fills the estimated units. Each unit's residual is its own; the text names
// the largest, so that Detail() groups all estimated units under one text.
void EstimateUnits(const fp::Format& f, const std::vector<TableRow>& table, const std::vector<size_t>& slots,
                   std::vector<Found>& found) {
  std::vector<Fit> fits;
  double max_residual = 0;
  for (size_t i : slots) {
    fits.push_back(FitUnit(table, found[i].area.unit));
    max_residual = std::max(max_residual, fits.back().residual);
  }
  for (size_t j = 0; j < slots.size(); ++j) {
    Found& out = found[slots[j]];
    Set(out, fits[j].At(f.e, f.m), "estimate", EstimateWhere(fits[j], f, max_residual));
    out.area.residual = fits[j].residual;
  }
}

Area Compute(const fp::Format& f, const AreaOptions& options, bool force_estimate) {
  CheckHasRtl(f);
  const bool estimate = options.estimate || force_estimate;
  const std::string src = SourceDir(options);
  const std::vector<TableRow> table = ReadSynthTable(src + "/" + kTablePath);
  const std::string cache = CacheDir(options) + "/" + RtlHash(src);

  std::vector<UnitKey> keys;
  for (const char* u : kFormatUnits) keys.push_back({u, false, f.e, f.m});
  for (const char* u : kFixedUnits) keys.push_back({u, true, 0, 0});

  std::vector<Found> found(keys.size());
  std::vector<size_t> to_estimate, to_synthesize;
  std::vector<Job> jobs;
  for (size_t i = 0; i < keys.size(); ++i) {
    const UnitKey& k = keys[i];
    found[i].area.unit = k.unit;
    found[i].area.format = k.FormatName();
    const std::string json = CachePath(cache, k, ".json");
    std::optional<Numbers> n;
    if (force_estimate && !k.plain) {
      to_estimate.push_back(i);
    } else if ((n = FindInTable(table, k))) {
      Set(found[i], *n, "cache", kTablePath);
    } else if ((n = ReadCached(json, k))) {
      Set(found[i], *n, "cache", cache);
    } else if (estimate && !k.plain) {
      to_estimate.push_back(i);
    } else if (estimate) {
      throw InputError("cannot estimate the area of " + k.unit + " (it does not depend on the format): no row in " +
                       src + "/" + kTablePath + " and no synthesis in " + cache + " (run `make synth`)");
    } else {
      to_synthesize.push_back(i);
      jobs.push_back({k, json, CachePath(cache, k, ".log")});
    }
  }
  if (!to_estimate.empty()) EstimateUnits(f, table, to_estimate, found);
  if (!jobs.empty()) {
    fs::create_directories(cache);
    Synthesize(jobs, src + "/" + kScriptPath, options);
    for (size_t j = 0; j < jobs.size(); ++j) {
      const Numbers n = *ReadCached(jobs[j].json, jobs[j].key);  // checked by Synthesize
      Set(found[to_synthesize[j]], n, "yosys", "Yosys in this run (scripts/synth-unit.sh; kept in " + cache + ")");
    }
  }
  return Sum(found);
}

}  // namespace

bool KeepsSram(const std::string& unit) {
  return unit == "rt_mem_system" || unit == "rt_leaf_exit" || unit == "rt_hit_merge" || unit == "rt_list_unit" ||
         unit == "rt_thread_stack";
}

std::string RtlHash(const std::string& source_dir) {
  const fs::path rtl = fs::path(source_dir) / "rtl";
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(rtl, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == ".sv") files.push_back(it->path());
  }
  if (files.empty()) throw InputError("no RTL (rtl/*.sv) in " + source_dir);
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return a.filename().string() < b.filename().string();
  });
  files.push_back(fs::path(source_dir) / kScriptPath);
  files.push_back(fs::path(source_dir) / "scripts/synth-common.sh");  // sourced by the script

  uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a 64
  auto add = [&h](const std::string& bytes) {
    for (unsigned char c : bytes) {
      h ^= c;
      h *= 0x100000001b3ull;
    }
  };
  for (const fs::path& p : files) {
    std::ifstream f(p, std::ios::binary);
    const std::string contents((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    // The NULs keep "ab"+"c" and "a"+"bc" apart.
    add(p.filename().string());
    add(std::string(1, '\0'));
    add(contents);
    add(std::string(1, '\0'));
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

Area CoreArea(const fp::Format& f, const AreaOptions& options) { return Compute(f, options, false); }

Area EstimateCoreArea(const fp::Format& f, const AreaOptions& options) { return Compute(f, options, true); }

std::string UnitSizesNote(int threads, int cache_mshrs, int cache_targets, int list_prefetch) {
  if (threads == kUnitThreads && cache_mshrs == kUnitCacheMshrs && cache_targets == kUnitCacheTargets &&
      list_prefetch == kUnitListPrefetch) {
    return "";
  }
  const auto core = [](int t, int r, int g, int f) {
    return std::to_string(t) + " threads, " + std::to_string(r) + " miss registers of " + std::to_string(g) +
           " requests, list prefetch " + std::to_string(f);
  };
  return "area counts the thread- and miss-register-sized units (rt_thread_fsm, rt_perf_events, rt_leaf_exit, "
         "rt_hit_merge, rt_list_unit, rt_mem_system) at their module defaults, a core of " +
         core(kUnitThreads, kUnitCacheMshrs, kUnitCacheTargets, kUnitListPrefetch) + ", not the simulated core of " +
         core(threads, cache_mshrs, cache_targets, list_prefetch) +
         ": its cells and flip-flops understate that core, and rays per cycle per 1,000 cells overstate it "
         "(docs/trade.md)";
}

}  // namespace kdrt::trade
