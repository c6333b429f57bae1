// kdrt sweep: design-space sweeps of kdrt sim, on a local pool or a Dask
// cluster. The driver is Python (scripts/kdrt_sweep.py, docs/sweep.md),
// because Dask is; this command hands it the arguments and this binary's
// own path, so every point runs the same kdrt.
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <string>
#include <vector>

#include "common/error.h"
#include "tools/commands.h"

namespace kdrt::cli {
namespace {

struct SweepArgs {
  std::string spec;
  std::string out;
  std::string scheduler;
  int jobs = 0;
};

// Debian's interpreter: python3-yaml and python3-distributed install there.
constexpr const char* kPython = "/usr/bin/python3";

int RunSweep(const SweepArgs& args) {
  char self[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) throw InputError("kdrt sweep: cannot find this program's own path");
  self[n] = '\0';
  const std::string script = std::string(KDRT_SOURCE_DIR) + "/scripts/kdrt_sweep.py";
  if (access(script.c_str(), R_OK) != 0) throw InputError(script + ": the sweep driver is missing");
  if (access(kPython, X_OK) != 0) {
    throw InputError("kdrt sweep needs /usr/bin/python3 with python3-yaml (scripts/install-deps.sh installs them)");
  }
  std::vector<std::string> a = {kPython, script, args.spec, "--kdrt", self};
  if (!args.out.empty()) a.insert(a.end(), {"--out", args.out});
  if (!args.scheduler.empty()) a.insert(a.end(), {"--scheduler", args.scheduler});
  if (args.jobs > 0) a.insert(a.end(), {"--jobs", std::to_string(args.jobs)});
  std::vector<char*> argv;
  for (std::string& s : a) argv.push_back(s.data());
  argv.push_back(nullptr);
  execv(kPython, argv.data());
  throw InputError(std::string("kdrt sweep: cannot run ") + kPython + ": " + std::strerror(errno));
}

}  // namespace

Runner AddSweepCommand(CLI::App& app) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Run kdrt sim over scenes x formats x parameters from a YAML spec, locally or on a Dask cluster; "
               "CSV, JSON and plots (docs/sweep.md)");
  cmd->add_option("spec", args->spec, "Sweep specification (YAML)")->required();
  cmd->add_option("-o,--out", args->out, "Output directory (default: <spec name>.sweep); points already there "
                                         "are not run again");
  cmd->add_option("--scheduler", args->scheduler, "Run the points on this Dask scheduler (tcp://HOST:PORT)");
  cmd->add_option("--jobs", args->jobs, "Local processes (default: the number of cores)");
  return [cmd, args]() { return cmd->parsed() ? RunSweep(*args) : -1; };
}

}  // namespace kdrt::cli
