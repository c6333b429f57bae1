#include "sim/model_runner.h"

#include "sim/fast_model.h"
#include "sim/ray_queue.h"
#include "sim/sim_report.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "common/text_file.h"
#include "trace/images.h"
#include "trace/rays_file.h"

namespace kdrt::sim {
namespace {

namespace fs = std::filesystem;

const char* const kBuildDir = KDRT_SIM_BUILD_DIR;
const char* const kSourceDir = KDRT_SIM_SOURCE_DIR;

// Whether the model at `path` is older than a source it is built from: the
// RTL, the harness and the reference code it links. A model built before an
// RTL change must not run silently (`cmake --build` of one target leaves the
// other models as they were).
bool OlderThanSources(const fs::path& path) {
  std::error_code ec;
  const auto built = fs::last_write_time(path, ec);
  if (ec) return true;
  for (const char* dir : {"rtl", "sim", "sw", "cmake"}) {
    for (fs::recursive_directory_iterator it(fs::path(kSourceDir) / dir, ec), end; !ec && it != end;
         it.increment(ec)) {
      if (it->is_regular_file(ec) && fs::last_write_time(it->path(), ec) > built) return true;
    }
  }
  return false;
}

// A directory that is removed with everything in it when it goes out of scope.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "kdrt-sim-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary directory in " + pattern);
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string File(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

int RunAndWait(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    // Models with SystemC linked in would print its banner on stdout.
    setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
    execv(argv[0], argv.data());
    std::fprintf(stderr, "kdrt: internal error: cannot start %s: %s\n", argv[0], std::strerror(errno));
    _exit(2);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
  }
  if (WIFSIGNALED(status)) {
    throw std::runtime_error(args[0] + " was killed by signal " + std::to_string(WTERMSIG(status)));
  }
  return WEXITSTATUS(status);
}

// The name of a scene-sized model's directory, its CMake target (after
// "kdrt-sim-model-") and its line in models.txt: the configuration's key,
// and ".quick" for a quick build (sim/CMakeLists.txt compiles those as one unit at -O1).
std::string ModelName(const ConfigChoice& choice, bool quick) {
  return choice.config.Key() + (quick ? ".quick" : "");
}

#if defined(KDRT_SIM_MODELS)
// Appends `line` to the list file unless it holds it already (callers hold
// the models directory's lock).
void AppendLineOnce(const fs::path& list, const std::string& line) {
  {
    std::ifstream in(list);
    std::string l;
    while (std::getline(in, l)) {
      if (l == line) return;
    }
  }
  std::ofstream out(list, std::ios::app);
  out << line << "\n";
  if (!out) throw std::runtime_error("cannot write " + list.string());
}
#endif

}  // namespace

bool QuickModels() {
  const char* v = std::getenv("KDRT_QUICK_MODELS");
  return v && *v && std::strcmp(v, "0") != 0;
}

ModelLocation LocateModel(const ConfigChoice& choice) {
  ModelLocation loc;
  // The build's profile training (sim/pgo_train.sh) runs the instrumented
  // model of a preset in place of the one being built.
  if (const char* binary = std::getenv("KDRT_SIM_MODEL_BINARY"); binary && *binary) {
    loc.path = binary;
    loc.target = "(KDRT_SIM_MODEL_BINARY)";
    loc.built = fs::exists(loc.path);
    if (!loc.built) throw InputError(loc.path, 0, "KDRT_SIM_MODEL_BINARY names no file");
    return loc;
  }
  if (choice.prebuilt) {
    const std::string name = "kdrt-sim-" + choice.config.Format().Name();
    loc = {std::string(kBuildDir) + "/bin/" + name, name};
  } else {
    // A quick build lives beside the optimised one, never in its place.
    loc.quick = QuickModels();
    const std::string name = ModelName(choice, loc.quick);
    loc.path = std::string(kBuildDir) + "/sim-models/" + name + "/kdrt-sim";
    loc.target = "kdrt-sim-model-" + name;
  }
  const bool exists = fs::exists(loc.path);
  loc.stale = exists && OlderThanSources(loc.path);
  loc.built = exists && !loc.stale;
  return loc;
}

void BuildModel(const ConfigChoice& choice, const ModelLocation& loc) {
#if defined(KDRT_SIM_MODELS)
  const fs::path models_dir = fs::path(kBuildDir) / "sim-models";
  fs::create_directories(models_dir);
  const std::string lock_path = (models_dir / ".lock").string();
  const int lock = open(lock_path.c_str(), O_CREAT | O_RDWR, 0644);
  if (lock < 0 || flock(lock, LOCK_EX) != 0) throw std::runtime_error("cannot lock " + lock_path);
  struct Unlock {
    int fd;
    ~Unlock() { close(fd); }
  } unlock{lock};
  if (fs::exists(loc.path) && !OlderThanSources(loc.path)) return;  // another run built it meanwhile

  if (choice.prebuilt) {
    // sim/CMakeLists.txt defines the target of a preset that `make build`
    // does not compile once it is listed here.
    AppendLineOnce(models_dir / "presets.txt", choice.config.Format().Name());
  } else {
    // The list sim/CMakeLists.txt defines a target per line of: the key and
    // Verilator's -G options.
    std::string line = ModelName(choice, loc.quick);
    for (const std::string& g : choice.config.VerilatorDefines()) line += " " + g;
    AppendLineOnce(models_dir / "models.txt", line);
  }
  const std::string log = (models_dir / (ModelName(choice, loc.quick) + ".build.log")).string();
  std::fprintf(stderr,
               "kdrt sim: %s the simulation model %s (Verilator, once; minutes: up to about 3 on 2 cores for a "
               "128-thread core, twice that for a preset compiled with its profile, KDRT_MODEL_PGO)%s\n"
               "kdrt sim: log in %s\n",
               loc.stale ? "sources changed since it was built: rebuilding" : "building", choice.config.Key().c_str(),
               loc.quick ? ", a quick build (KDRT_QUICK_MODELS: its C++ one unit at -O1 without waveforms, a fraction of the compile "
                           "time, slower to run)"
                         : "",
               log.c_str());
  const auto start = std::chrono::steady_clock::now();
  // Configure first: the new line in models.txt defines the target.
  const std::string cmake = std::string("'") + KDRT_CMAKE_COMMAND + "'";
  const std::string cmd = cmake + " '" + kBuildDir + "' > '" + log + "' 2>&1 && " + cmake + " --build '" +
                          kBuildDir + "' --target " + loc.target + " -j 2 >> '" + log + "' 2>&1";
  const int rc = std::system(cmd.c_str());
  if (rc != 0 || !fs::exists(loc.path)) {
    throw std::runtime_error("building the simulation model " + choice.config.Key() + " failed; the end of " + log +
                             ":\n" + LastLines(log, 25));
  }
  // A source the model does not depend on leaves the target as it was:
  // mark it current, so that it is not rebuilt again on every run.
  fs::last_write_time(loc.path, fs::file_time_type::clock::now());
  std::fprintf(stderr, "kdrt sim: model built in %.0f s\n",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
#else
  (void)choice;
  (void)loc;
  throw InputError("kdrt sim: no simulation models in this build: Verilator was not found, or rtl/rt_core.sv did "
                   "not elaborate when CMake last configured (see its warning; re-run cmake)");
#endif
}

ModelRun RunModel(const ModelLocation& loc, const CoreConfig& config, const std::vector<uint8_t>& image,
                  const std::vector<Ray>& rays, const RunOptions& run, const std::string& trace_path,
                  Query query) {
  TempDir dir;
  const std::string image_path = dir.File("image.bin"), rays_path = dir.File("rays.bin");
  const std::string hits_path = dir.File("hits.exr"), report_path = dir.File("report.json");
  {
    std::ofstream f(image_path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(image.data()), static_cast<std::streamsize>(image.size()));
    if (!f) throw std::runtime_error("cannot write " + image_path);
  }
  WriteRaysFile(rays_path, rays, query);

  std::vector<std::string> args = {loc.path,   "--expect-model", config.Key(), "--image",     image_path,
                                   "--rays",   rays_path,        "--hits-out", hits_path,     "--report-out",
                                   report_path};
  for (std::string& a : RunOptionArgs(run, trace_path)) args.push_back(std::move(a));
  ModelRun out;
  out.exit_code = RunAndWait(args);
  if (out.exit_code != 0) return out;
  int width = 0, height = 0;
  out.hits = ReadHitBuffer(hits_path, &width, &height);
  if (out.hits.size() != rays.size()) throw std::runtime_error("the model returned " + std::to_string(out.hits.size()) +
                                                               " hit records for " + std::to_string(rays.size()) + " rays");
  std::ifstream f(report_path);
  out.report = nlohmann::json::parse(f);
  return out;
}

ModelRun RunFast(const CoreConfig& config, const std::vector<uint8_t>& image, const std::vector<Ray>& rays,
                 const RunOptions& run, Query query) {
  const ImageView view(image);
  FastSpec spec;
  spec.image = &view;
  spec.rays = &rays;
  spec.query = query;
  spec.config = config;
  spec.memory.size_bytes = run.mem_size ? run.mem_size : uint64_t{1} << config[kAddrWidth];
  spec.memory.latency = run.mem_latency;
  spec.memory.bytes_per_cycle = run.mem_bw;
  spec.timeout = run.timeout;
  spec.progress = run.progress;
  const std::vector<uint32_t> order = IssueOrder(run.ray_order, run.frame_width, rays.size());
  spec.order = &order;
  ReportInputs ri;
  ri.loop = "fast";
  ri.config = config;
  ri.requirements = DeriveRequirements(view);
  ri.memory = spec.memory;
  ri.rays = rays.size();
  ri.query = query;
  ModelRun out;
  if (run.cores > 0) {
    // Several cores behind the shared L2, as the SystemC system model runs
    // them (RunSystemCCores).
    L2Config l2;
    l2.size_bytes = run.l2_kb * 1024u;
    l2.ways = run.l2_ways;
    l2.latency = run.l2_latency;
    FastReference ref;
    const SystemOutcome sys = RunFastCores(spec, run.cores, l2, run.ray_chunk, &ref);
    ri.reference_totals = ref.totals;
    SetWindowBound(ref.per_ray, &order, config[kThreads], run.cores, &ri);
    out.report = SystemReportJson(ri, sys, ref.per_ray);
    out.hits = std::move(ref.hits);
  } else {
    std::vector<RayCounters> per_ray;
    RunOutcome outcome = RunFastModel(spec, &ri.reference_totals, &per_ray);
    SetWindowBound(per_ray, &order, config[kThreads], run.cores, &ri);
    ri.run = &outcome;
    out.report = ReportJson(ri);
    out.hits = std::move(outcome.result.hits);
  }
  out.report["cycle_model"] = "fast";
  out.report["notes"] = {"fast cycle model (sim/fast_model.h): cycles and every performance event as the RTL "
                         "counts them (cycle-exact where tested: tests/sim/sim_cli_test.cpp); a stack overflow "
                         "ends the ray as in the RTL"};
  return out;
}

std::vector<uint8_t> CoreImage(const std::vector<uint8_t>& fp32_image, fp::Format format) {
  const img::ImageLayout layout = LayoutFor(format);
  if (layout.IsFp32()) return fp32_image;
  return RepackImage(ImageView(fp32_image), layout);
}

ModelRun Simulate(const std::vector<uint8_t>& fp32_image, const std::vector<Ray>& rays, fp::Format format,
                  RunOptions run, Query query, std::optional<fp::Format> trav,
                  std::optional<fp::Format> image_format, const ConfigOverrides& core) {
  const std::vector<uint8_t> image = CoreImage(fp32_image, image_format.value_or(format));
  const SceneRequirements req = DeriveRequirements(ImageView(image));
  ConfigOverrides ov = core;
  if (trav) OverrideTravFormat(format, *trav, &ov);
  if (image_format) OverrideImageFormat(format, *image_format, &ov);
  const ConfigChoice choice = ChooseConfig(format, req, ov, run.mem_size, run.allow_overflow);
  const ModelLocation loc = LocateModel(choice);
  if (!loc.built) BuildModel(choice, loc);
  run.mem_size = choice.mem_size;
  return RunModel(loc, choice.config, image, rays, run, "", query);
}

}  // namespace kdrt::sim
