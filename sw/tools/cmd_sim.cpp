// kdrt sim: the cycle simulator front end, and kdrt compare.
//
// Verilator fixes the core's parameters at build time, so the simulator is a
// family of executables (sim/sim_main.cpp), one per configuration. This
// front end derives what the scene needs, picks the prebuilt model of the
// format when it covers that, otherwise builds a scene-sized model once (kept
// under <build>/sim-models/<key>/), and then runs the model with the very
// same arguments.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "fp/format.h"
#include "sim/sim_args.h"
#include "sim/sim_config.h"
#include "tools/commands.h"
#include "tools/scene_setup.h"
#include "trace/images.h"

namespace kdrt::cli {
namespace {

namespace fs = std::filesystem;

#ifdef KDRT_SIM_BUILD_DIR
const char* const kBuildDir = KDRT_SIM_BUILD_DIR;
#else
const char* const kBuildDir = "";
#endif

// The arguments after the `sim` subcommand, exactly as given.
std::vector<std::string> SimArguments() {
  std::ifstream f("/proc/self/cmdline", std::ios::binary);
  std::vector<std::string> all;
  std::string arg;
  while (std::getline(f, arg, '\0')) all.push_back(arg);
  for (size_t i = 1; i < all.size(); ++i) {
    if (all[i] == "sim") return std::vector<std::string>(all.begin() + i + 1, all.end());
  }
  throw std::runtime_error("cannot find the sim arguments in /proc/self/cmdline");
}

struct ModelLocation {
  std::string path;
  std::string target;
};

ModelLocation Locate(const sim::ConfigChoice& choice, fp::Format format) {
  if (choice.prebuilt) {
    return {std::string(kBuildDir) + "/bin/kdrt-sim-" + format.Name(), "kdrt-sim-" + format.Name()};
  }
  const std::string key = choice.config.Key();
  return {std::string(kBuildDir) + "/sim-models/" + key + "/kdrt-sim", "kdrt-sim-model-" + key};
}

#if defined(KDRT_SIM_MODELS) && defined(KDRT_CMAKE_COMMAND)
std::string ModelListLine(const sim::CoreConfig& c) {
  std::ostringstream s;
  s << c.Key() << " " << c.e << " " << c.m << " " << c.threads << " " << c.stack_depth << " " << c.node_idx_width
    << " " << c.tri_idx_width << " " << c.addr_width << " " << c.node_cache_lines << " " << c.list_cache_lines << " "
    << c.tri_cache_lines;
  return s.str();
}

std::string Tail(const std::string& path, size_t lines) {
  std::ifstream f(path);
  std::vector<std::string> all;
  std::string line;
  while (std::getline(f, line)) all.push_back(line);
  std::string out;
  for (size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) out += all[i] + "\n";
  return out;
}

#endif

// Builds the model with CMake in the build tree this `kdrt` belongs to; a
// lock file keeps concurrent `kdrt sim` runs from building at the same time.
void BuildModel(const sim::ConfigChoice& choice, const ModelLocation& loc) {
#if defined(KDRT_SIM_MODELS) && defined(KDRT_CMAKE_COMMAND)
  const fs::path models_dir = fs::path(kBuildDir) / "sim-models";
  fs::create_directories(models_dir);
  const std::string lock_path = (models_dir / ".lock").string();
  const int lock = open(lock_path.c_str(), O_CREAT | O_RDWR, 0644);
  if (lock < 0 || flock(lock, LOCK_EX) != 0) throw std::runtime_error("cannot lock " + lock_path);
  struct Unlock {
    int fd;
    ~Unlock() { close(fd); }
  } unlock{lock};
  if (fs::exists(loc.path)) return;  // another run built it meanwhile

  if (!choice.prebuilt) {
    const fs::path list = models_dir / "models.txt";
    const std::string line = ModelListLine(choice.config);
    bool listed = false;
    {
      std::ifstream in(list);
      std::string l;
      while (std::getline(in, l)) listed = listed || l == line;
    }
    if (!listed) {
      std::ofstream out(list, std::ios::app);
      out << line << "\n";
      if (!out) throw std::runtime_error("cannot write " + list.string());
    }
  }
  const std::string log = (models_dir / (choice.config.Key() + ".build.log")).string();
  std::fprintf(stderr,
               "kdrt sim: building the simulation model %s (Verilator, once; about 1-2 minutes on 2 cores)\n"
               "kdrt sim: log in %s\n",
               choice.config.Key().c_str(), log.c_str());
  const auto start = std::chrono::steady_clock::now();
  // Configure first: the new line in models.txt defines the target.
  const std::string cmake = std::string("'") + KDRT_CMAKE_COMMAND + "'";
  const std::string cmd = cmake + " '" + kBuildDir + "' > '" + log + "' 2>&1 && " + cmake + " --build '" +
                          kBuildDir + "' --target " + loc.target + " -j 2 >> '" + log + "' 2>&1";
  const int rc = std::system(cmd.c_str());
  if (rc != 0 || !fs::exists(loc.path)) {
    throw std::runtime_error("building the simulation model " + choice.config.Key() + " failed; the end of " + log +
                             ":\n" + Tail(log, 25));
  }
  std::fprintf(stderr, "kdrt sim: model built in %.0f s\n",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
#else
  (void)choice;
  (void)loc;
  throw InputError("kdrt sim: no simulation models in this build: Verilator was not found, or rtl/rt_core.sv did "
                   "not elaborate when CMake last configured (see its warning; re-run cmake)");
#endif
}

int RunSim(const sim::SimArgs& args) {
  sim::CheckSimArgs(args);
  const fp::Format format = fp::ParseFormat(args.format);
  // The model repeats this; here it only sizes the model.
  const PreparedScene p = PrepareScene(args.scene);
  const ImageView image(p.image);
  const sim::SceneRequirements req = sim::DeriveRequirements(image);
  const sim::ConfigChoice choice = sim::ChooseConfig(format, req, args.overrides);
  const ModelLocation loc = Locate(choice, format);
  const bool built = fs::exists(loc.path);
  if (args.which_model) {
    std::printf("scene needs    stack %d, node index %d bits, triangle index %d bits, address %d bits (%" PRIu64
                " bytes)\n",
                req.stack_depth, req.node_idx_bits, req.tri_idx_bits, req.addr_bits, req.image_bytes);
    std::printf("model          %s (%s)\n", choice.config.Key().c_str(), choice.prebuilt ? "prebuilt" : "scene-sized");
    std::printf("executable     %s (%s)\n", loc.path.c_str(), built ? "built" : "not built yet");
    return 0;
  }
  if (!built) BuildModel(choice, loc);

  std::vector<std::string> model_args = SimArguments();
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(loc.path.c_str()));
  for (std::string& a : model_args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // Models with SystemC linked in would print its banner on stdout.
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  std::fflush(stdout);
  std::fflush(stderr);
  execv(loc.path.c_str(), argv.data());
  throw std::runtime_error("cannot start " + loc.path + ": " + std::strerror(errno));
}

std::string HitText(const Hit& h) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "prim %" PRIu32 "%s, t %.9g (0x%08" PRIx32 "), u %.9g (0x%08" PRIx32
                "), v %.9g (0x%08" PRIx32 ")",
                h.prim, h.IsHit() ? "" : " (miss)", static_cast<double>(h.t), fp::BitsOf(h.t),
                static_cast<double>(h.u), fp::BitsOf(h.u), static_cast<double>(h.v), fp::BitsOf(h.v));
  return buf;
}

int RunCompare(const std::string& a_path, const std::string& b_path) {
  int aw = 0, ah = 0, bw = 0, bh = 0;
  const std::vector<Hit> a = ReadHitBuffer(a_path, &aw, &ah);
  const std::vector<Hit> b = ReadHitBuffer(b_path, &bw, &bh);
  if (aw != bw || ah != bh) {
    std::printf("different sizes: %s is %dx%d, %s is %dx%d\n", a_path.c_str(), aw, ah, b_path.c_str(), bw, bh);
    return 1;
  }
  size_t differ = 0, first = a.size();
  for (size_t i = 0; i < a.size(); ++i) {
    const bool same = a[i].prim == b[i].prim && fp::BitsOf(a[i].t) == fp::BitsOf(b[i].t) &&
                      fp::BitsOf(a[i].u) == fp::BitsOf(b[i].u) && fp::BitsOf(a[i].v) == fp::BitsOf(b[i].v);
    if (!same) {
      if (differ == 0) first = i;
      ++differ;
    }
  }
  if (differ == 0) {
    std::printf("identical (%dx%d hit records)\n", aw, ah);
    return 0;
  }
  std::printf("%zu of %zu hit records differ; the first at pixel (%zu, %zu):\n  %s: %s\n  %s: %s\n", differ,
              a.size(), first % aw, first / aw, a_path.c_str(), HitText(a[first]).c_str(), b_path.c_str(),
              HitText(b[first]).c_str());
  return 1;
}

struct CompareArgs {
  std::string a, b;
};

}  // namespace

Runner AddSimCommand(CLI::App& app) {
  auto args = std::make_shared<sim::SimArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sim", "Run the RTL core (Verilator) on a scene, checked ray by ray against the reference; report cycles");
  sim::AddSimOptions(*cmd, *args);

  auto cmp = std::make_shared<CompareArgs>();
  CLI::App* compare = app.add_subcommand(
      "compare", "Compare two EXR hit buffers bit for bit: prints 'identical' or the first differing pixel");
  compare->add_option("a", cmp->a, "First hit buffer (.exr)")->required();
  compare->add_option("b", cmp->b, "Second hit buffer (.exr)")->required();

  return [cmd, args, compare, cmp]() {
    if (cmd->parsed()) return RunSim(*args);
    if (compare->parsed()) return RunCompare(cmp->a, cmp->b);
    return -1;
  };
}

}  // namespace kdrt::cli
