#include "sim/phys.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace kdrt::sim {
namespace {

namespace fs = std::filesystem;

// Stillmaker & Baas, Integration 58 (2017): the nodes kdrt reports and the
// ones it interpolates between. Area: the paper's table of area scaling
// factors, 180 nm row (180 -> 45 nm x0.053, 32 nm x0.025, 20 nm x0.011, 7 nm
// x0.0032). Delay: the paper's fitted delay equations d(V) = a3 V^3 + a2 V^2
// + a1 V + a0 (180 nm bulk; 45, 32, 20 and 7 nm high-performance PTM models)
// at each node's nominal Vdd.
struct PaperNode {
  int nm;
  double vdd;
  double area;      // from 180 nm
  double delay[4];  // a3, a2, a1, a0
};
constexpr PaperNode kPaper[] = {
    {180, 1.8, 1.0, {0, 97.09, -356.7, 406.5}},
    {45, 1.0, 0.053, {-501.6, 1567, -1619, 566.1}},
    {32, 0.9, 0.025, {-1047, 2982, -2797, 873.5}},
    {20, 0.9, 0.011, {0, 34.63, -66.37, 41.15}},
    {7, 0.7, 0.0032, {-28.58, 76.6, -70.26, 24.69}},
};

double DelayPoly(const PaperNode& n) {
  const double v = n.vdd;
  return ((n.delay[0] * v + n.delay[1]) * v + n.delay[2]) * v + n.delay[3];
}

NodeScale FromPaper(const PaperNode& n) {
  NodeScale s;
  s.nm = n.nm;
  s.vdd = n.vdd;
  s.area = n.area;
  s.delay = DelayPoly(n) / DelayPoly(kPaper[0]);
  return s;
}

const PaperNode& Paper(int nm) {
  for (const PaperNode& n : kPaper) {
    if (n.nm == nm) return n;
  }
  throw std::logic_error("no such node in the scaling table");
}

// A node between two of the paper's: log(factor) linear in log(node).
NodeScale Interpolate(int nm, int upper, int lower) {
  const NodeScale a = FromPaper(Paper(upper)), b = FromPaper(Paper(lower));
  const double t = std::log(double(upper) / nm) / std::log(double(upper) / lower);
  auto lerp = [t](double x, double y) { return std::exp(std::log(x) + t * (std::log(y) - std::log(x))); };
  NodeScale s;
  s.nm = nm;
  s.vdd = a.vdd + t * (b.vdd - a.vdd);
  s.area = lerp(a.area, b.area);
  s.delay = lerp(a.delay, b.delay);
  s.interpolated_from[0] = upper;
  s.interpolated_from[1] = lower;
  return s;
}

[[noreturn]] void Bad(const std::string& path, const std::string& what) {
  throw InputError(path + ": " + what + " (a core.json of scripts/synth-core.sh; 'kdrt synth' writes it again)");
}

const nlohmann::json& Field(const nlohmann::json& j, const char* name, const std::string& path,
                            const std::string& where) {
  if (!j.is_object() || !j.contains(name)) Bad(path, "no \"" + std::string(name) + "\"" + where);
  return j[name];
}

double Number(const nlohmann::json& j, const char* name, const std::string& path, const std::string& where = "",
              bool positive = false) {
  const nlohmann::json& v = Field(j, name, path, where);
  if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0 ||
      (positive && !(v.get<double>() > 0))) {
    Bad(path, "\"" + std::string(name) + "\"" + where + " is not a " + (positive ? "positive" : "non-negative") +
                  " number");
  }
  return v.get<double>();
}

std::string Text(const nlohmann::json& j, const char* name, const std::string& path, const std::string& where = "") {
  const nlohmann::json& v = Field(j, name, path, where);
  if (!v.is_string()) Bad(path, "\"" + std::string(name) + "\"" + where + " is not a string");
  return v.get<std::string>();
}

// Every field PhysicalBlock and PrintPhysical read, and the params of `config`.
void CheckCoreJson(const nlohmann::json& core, const std::string& path, const CoreConfig& config) {
  if (!core.is_object()) Bad(path, "not a JSON object");
  Text(core, "library", path);
  Number(core, "clock_ns", path, "", true);
  Text(core, "critical_unit", path);
  const nlohmann::json& area = Field(core, "area_um2", path, "");
  for (const char* k : {"logic", "sram", "total"}) Number(area, k, path, " in \"area_um2\"");
  const nlohmann::json& params = Field(core, "params", path, "");
  if (!params.is_object()) Bad(path, "\"params\" is not an object");
  for (int i = 0; i < kParamCount; ++i) {
    const char* name = kCoreParams[i].sv_name;
    if (!params.contains(name) || !params[name].is_number_integer()) {
      Bad(path, "\"params\" has no integer " + std::string(name));
    }
    if (params[name].get<int>() != config.value[i]) {
      Bad(path, "synthesized with " + std::string(name) + "=" + std::to_string(params[name].get<int>()) +
                    ", but this configuration (" + config.Key() + ") has " + std::to_string(config.value[i]));
    }
  }
  const nlohmann::json& units = Field(core, "units", path, "");
  if (!units.is_array() || units.empty()) Bad(path, "\"units\" is not a non-empty array");
  for (size_t k = 0; k < units.size(); ++k) {
    const nlohmann::json& u = units[k];
    const std::string where = " in units[" + std::to_string(k) + "]";
    Text(u, "unit", path, where);
    Number(u, "count", path, where);
    Number(u, "area_um2", path, where);
    Number(u, "flip_flops", path, where);
    Number(u, "crit_ns", path, where);
    if (u.contains("estimated") && !u["estimated"].is_boolean()) Bad(path, "\"estimated\"" + where + " is not true/false");
    if (u.contains("params") && !u["params"].is_object()) Bad(path, "\"params\"" + where + " is not an object");
    if (u.contains("srams") && !u["srams"].is_array()) Bad(path, "\"srams\"" + where + " is not an array");
  }
  if (core.contains("notes") && !core["notes"].is_array()) Bad(path, "\"notes\" is not an array");
}

std::string Fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// A shell word: the paths are the user's build tree.
std::string Quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

std::string PhysDir() {
  const char* env = std::getenv("KDRT_PHYS_DIR");
  if (env && *env) return env;
  return std::string(KDRT_SIM_BUILD_DIR) + "/phys";
}

std::string PhysPath(const CoreConfig& config) { return PhysDir() + "/" + config.Key() + "/core.json"; }

std::vector<NodeScale> PaperNodes() {
  std::vector<NodeScale> v;
  for (const PaperNode& n : kPaper) v.push_back(FromPaper(n));
  return v;
}

std::vector<NodeScale> ScaledNodes() {
  return {FromPaper(Paper(45)), Interpolate(28, 32, 20), FromPaper(Paper(7))};
}

nlohmann::json PhysicalBlock(const nlohmann::json& core, const std::string& path, const CoreConfig& config,
                             double cycles_per_ray) {
  CheckCoreJson(core, path, config);
  const double clock_ns = core["clock_ns"].get<double>();
  const nlohmann::json& a = core["area_um2"];
  const double logic = a["logic"].get<double>() * 1e-6, sram = a["sram"].get<double>() * 1e-6,
               total = a["total"].get<double>() * 1e-6;
  // One core: cycles_per_ray > 0 (an empty run has none, and no rate).
  const double mrays = cycles_per_ray > 0 ? 1e3 / clock_ns / cycles_per_ray : 0.0;
  nlohmann::json p = {{"source", path},
                      {"key", config.Key()},
                      {"library", core["library"]},
                      {"scope", core.value("scope", "")},
                      {"period_target_ns", core.value("period_target_ns", 0.0)},
                      {"clock_ns", clock_ns},
                      {"clock_mhz", 1e3 / clock_ns},
                      {"critical_unit", core["critical_unit"]},
                      {"area_mm2", {{"logic", logic}, {"sram", sram}, {"total", total}}},
                      {"cycles_per_ray", cycles_per_ray},
                      {"mrays_per_s", mrays},
                      {"mrays_per_s_per_mm2", total > 0 ? mrays / total : 0.0},
                      {"units", core["units"]}};
  nlohmann::json estimated = nlohmann::json::array();
  for (const nlohmann::json& u : core["units"]) {
    if (u.value("estimated", false)) {
      estimated.push_back({{"unit", u["unit"]}, {"method", u.value("method", std::string("not stated"))}});
    }
  }
  p["estimated_units"] = estimated;
  nlohmann::json scaled = nlohmann::json::object();
  for (const NodeScale& s : ScaledNodes()) {
    const double c = clock_ns * s.delay;
    const double t = total * s.area;
    const double r = cycles_per_ray > 0 ? 1e3 / c / cycles_per_ray : 0.0;
    nlohmann::json e = {{"method", "scaled"},
                        {"source", "Stillmaker & Baas, Integration 58 (2017): area factor table, fitted delay "
                                   "equations at nominal Vdd"},
                        {"area_factor", s.area},
                        {"delay_factor", s.delay},
                        {"vdd", s.vdd},
                        {"clock_ns", c},
                        {"area_mm2", {{"logic", logic * s.area}, {"sram", sram * s.area}, {"total", t}}},
                        {"mrays_per_s", r},
                        {"mrays_per_s_per_mm2", t > 0 ? r / t : 0.0}};
    if (s.interpolated_from[0]) {
      e["interpolated_from_nm"] = {s.interpolated_from[0], s.interpolated_from[1]};
    }
    scaled[std::to_string(s.nm) + "nm"] = e;
  }
  p["scaled"] = scaled;
  nlohmann::json notes = core.value("notes", nlohmann::json::array());
  notes.push_back(
      "scaled: the 180 nm figures times Stillmaker & Baas's factors; the SRAM area and access time scaled like the logic's; 28 nm "
      "is interpolated between the paper's 32 and 20 nm nodes");
  p["notes"] = notes;
  return p;
}

std::string SourcesHash() {
  const fs::path root(KDRT_SIM_SOURCE_DIR);
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(root / "rtl", ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == ".sv") files.push_back(it->path());
  }
  if (ec || files.empty()) {
    throw InputError((root / "rtl").string() + ": cannot be read (the RTL a synthesis is checked against)");
  }
  std::sort(files.begin(), files.end(),
            [](const fs::path& a, const fs::path& b) { return a.filename().string() < b.filename().string(); });
  files.push_back(root / "scripts" / "sram_model.txt");
  uint64_t h = 0xCBF29CE484222325ull;
  auto add = [&h](const std::string& bytes) {
    for (unsigned char c : bytes) h = (h ^ c) * 0x100000001B3ull;
  };
  for (const fs::path& f : files) {
    std::ifstream in(f, std::ios::binary);
    if (!in) throw InputError(f.string() + ": cannot be read (a source of the synthesis)");
    std::ostringstream text;
    text << in.rdbuf();
    add(f.filename().string() + '\0' + text.str() + '\0');
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

nlohmann::json ReadCoreJson(const CoreConfig& config) {
  const std::string path = PhysPath(config);
  std::error_code ec;
  if (!fs::exists(path, ec)) return nullptr;
  std::ifstream f(path);
  if (!f) throw InputError(path + ": cannot be read");
  nlohmann::json core;
  try {
    core = nlohmann::json::parse(f);
  } catch (const nlohmann::json::parse_error& e) {
    Bad(path, std::string("not valid JSON: ") + e.what());
  }
  CheckCoreJson(core, path, config);
  if (core.value("sources_fnv1a64", std::string()) != SourcesHash()) return nullptr;
  return core;
}

bool HasSynthesisOfOtherSources(const CoreConfig& config) {
  std::error_code ec;
  return fs::exists(PhysPath(config), ec);
}

std::string NoSynthesisLine(const CoreConfig& config) {
  if (HasSynthesisOfOtherSources(config)) {
    return "physical: the synthesis of this configuration (" + PhysPath(config) +
           ") was made from other sources (rtl/*.sv or scripts/sram_model.txt changed since), so its figures "
           "are another design's; run 'kdrt synth' with the same scene and options again (units whose RTL did "
           "not change stay cached), or 'kdrt sim --synth'";
  }
  return "physical: no synthesis of this configuration (" + config.Key() +
         "); run 'kdrt synth' with the same scene and options, or 'kdrt sim --synth' (takes minutes)";
}

std::string SynthesisState(const CoreConfig& config, const nlohmann::json& core) {
  if (!core.is_null()) return "synthesized";
  return HasSynthesisOfOtherSources(config) ? "made from other sources than this tree's" : "none yet";
}

void PrintPhysical(const nlohmann::json& p, const CoreConfig& config, std::FILE* out) {
  if (p.is_null()) {
    std::fprintf(out, "%s\n", NoSynthesisLine(config).c_str());
    return;
  }
  auto d = [&](const nlohmann::json& v) { return v.get<double>(); };
  const auto& a = p["area_mm2"];
  std::fprintf(out, "physical       %s, clock %.2f ns (%.0f MHz, critical unit %s), %s\n",
               p["library"].get<std::string>().c_str(), d(p["clock_ns"]), d(p["clock_mhz"]),
               p["critical_unit"].get<std::string>().c_str(), p["source"].get<std::string>().c_str());
  std::fprintf(out, "area           %.3f mm^2 logic + %.3f mm^2 SRAM = %.3f mm^2\n", d(a["logic"]), d(a["sram"]),
               d(a["total"]));
  std::fprintf(out, "ray rate       %.3f Mrays/s per core, %.4f Mrays/s per mm^2 (%.2f cycles per ray)\n",
               d(p["mrays_per_s"]), d(p["mrays_per_s_per_mm2"]), d(p["cycles_per_ray"]));
  const auto& s = p["scaled"]["28nm"];
  std::fprintf(out,
               "scaled 28 nm   %.3f Mrays/s per core, %.3f Mrays/s per mm^2 (clock %.2f ns, %.3f mm^2: area "
               "x%.4f, delay x%.3f, Stillmaker & Baas 2017 interpolated between 32 and 20 nm)\n",
               d(s["mrays_per_s"]), d(s["mrays_per_s_per_mm2"]), d(s["clock_ns"]), d(s["area_mm2"]["total"]),
               d(s["area_factor"]), d(s["delay_factor"]));
  for (const auto& e : p["estimated_units"]) {
    std::fprintf(out, "estimated      %s: %s (not synthesized)\n", e["unit"].get<std::string>().c_str(),
                 e["method"].get<std::string>().c_str());
  }
}

std::vector<std::string> SynthParams(const CoreConfig& config) {
  std::vector<std::string> v;
  for (int i = 0; i < kParamCount; ++i) v.push_back(std::string(kCoreParams[i].sv_name) + "=" + std::to_string(config.value[i]));
  return v;
}

nlohmann::json SynthesizeCore(const CoreConfig& config, double period_ns, int jobs) {
  const std::string script = std::string(KDRT_SIM_SOURCE_DIR) + "/scripts/synth-core.sh";
  std::error_code ec;
  if (!fs::exists(script, ec)) throw InputError(script + ": not found (the synthesis flow of kdrt synth)");
  const fs::path core_path = PhysPath(config);
  const fs::path dir = core_path.parent_path();
  fs::create_directories(dir);
  // The script caches each unit under DIR/units; every configuration's
  // DIR/units is the one <phys dir>/units, so a unit with the same
  // parameters (most of them between two configurations) is synthesized once.
  const fs::path shared = fs::path(PhysDir()) / "units";
  fs::create_directories(shared);
  if (!fs::exists(dir / "units", ec)) fs::create_directory_symlink("../units", dir / "units");
  // What kdrt sim reads is the new result or nothing, never the old one.
  fs::remove(core_path, ec);
  std::string cmd = "bash " + Quote(script) + " --out " + Quote(dir.string());
  if (period_ns > 0) cmd += " --period " + Fixed(period_ns, 3);
  if (jobs > 0) cmd += " --jobs " + std::to_string(jobs);
  for (const std::string& kv : SynthParams(config)) cmd += " " + kv;
  // The script's progress goes to stderr: stdout is the table or the JSON.
  const int status = std::system((cmd + " 1>&2").c_str());
  const int rc = status == -1 ? -1 : WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (rc != 0) {
    fs::remove(core_path, ec);
    throw InputError("the synthesis of " + config.Key() + " failed (scripts/synth-core.sh exit status " +
                     std::to_string(rc) + "; its messages are above); no core.json was written (the units it " +
                     "finished stay cached in " + shared.string() + ")");
  }
  nlohmann::json core;
  try {
    // The same checks as a later read: a core.json that kdrt sim would refuse is not kept.
    if (!fs::exists(core_path, ec)) throw InputError(core_path.string() + ": scripts/synth-core.sh wrote no core.json");
    core = ReadCoreJson(config);
  } catch (...) {
    fs::remove(core_path, ec);
    throw;
  }
  if (core.is_null()) RequireSynthesisOfThisTree(config);  // the sources changed while it ran: throws
  return core;
}

void RequireSynthesisOfThisTree(const CoreConfig& config) {
  if (!HasSynthesisOfOtherSources(config) || !ReadCoreJson(config).is_null()) return;
  throw InputError(PhysPath(config) +
                   ": made from other sources than this tree's: rtl/*.sv or scripts/sram_model.txt changed while "
                   "it was synthesized (or since), so its figures are of the sources as they were when it started; "
                   "run 'kdrt synth' again (units whose RTL did not change stay cached)");
}

}  // namespace kdrt::sim
