// Subcommands of the `kdrt` tool. Each registers its options on a CLI11
// subcommand and returns the function that runs it.
#pragma once

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace kdrt::cli {

using Runner = std::function<int()>;

Runner AddRenderCommand(CLI::App& app);
Runner AddInfoCommand(CLI::App& app);
Runner AddGenCommand(CLI::App& app);
Runner AddRaysCommand(CLI::App& app);
Runner AddSimCommand(CLI::App& app);
Runner AddCompareCommand(CLI::App& app);
Runner AddExtremesCommand(CLI::App& app);
Runner AddTradeCommand(CLI::App& app);
Runner AddSweepCommand(CLI::App& app);
Runner AddCompareAccelCommand(CLI::App& app);
Runner AddSynthCommand(CLI::App& app);

}  // namespace kdrt::cli
