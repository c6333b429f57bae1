// kdrt: the command-line front end of the kd-tree ray tracing processor model.
#include <cstdio>
#include <exception>
#include <vector>

#include "common/error.h"
#include "tools/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"kdrt: a hardware kd-tree ray tracing processor model and its software reference"};
  app.require_subcommand(1);
  std::vector<kdrt::cli::Runner> runners = {
      kdrt::cli::AddRenderCommand(app),
      kdrt::cli::AddInfoCommand(app),
      kdrt::cli::AddGenCommand(app),
      kdrt::cli::AddRaysCommand(app),
      kdrt::cli::AddSimCommand(app),
      kdrt::cli::AddSynthCommand(app),
      kdrt::cli::AddCompareCommand(app),
      kdrt::cli::AddExtremesCommand(app),
      kdrt::cli::AddTradeCommand(app),
      kdrt::cli::AddSweepCommand(app),
      kdrt::cli::AddCompareAccelCommand(app),
  };
  try {
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      return app.exit(e);
    }
    for (const auto& run : runners) {
      const int rc = run();
      if (rc >= 0) return rc;
    }
  } catch (const kdrt::InputError& e) {
    std::fprintf(stderr, "kdrt: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kdrt: internal error: %s\n", e.what());
    return 2;
  }
  return 0;
}
