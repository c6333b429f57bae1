// The numbers `kdrt sim` reports (docs/simulator.md defines each one), as a
// table on stdout and as JSON.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "common/ray.h"
#include "sim/core_harness.h"
#include "sim/memory_model.h"
#include "sim/sim_config.h"

namespace kdrt::sim {

struct ReportInputs {
  std::string scene;
  std::string format;
  std::string loop;  // "verilator" or "systemc"
  int width = 0, height = 0;
  CoreConfig config;
  SceneRequirements requirements;
  MemoryConfig memory;
  RayCounters reference_totals;  // TraceRays over every ray
  const RunOutcome* run = nullptr;
  uint64_t rays = 0;
  uint64_t tree_nodes = 0;
  uint32_t tree_depth = 0;
  uint64_t triangles = 0;
};

nlohmann::json ReportJson(const ReportInputs& in);
// The same numbers as a table.
void PrintReport(const nlohmann::json& report, std::FILE* out);

}  // namespace kdrt::sim
