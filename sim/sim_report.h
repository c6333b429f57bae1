// The numbers `kdrt sim` reports (docs/simulator.md defines each one), as a
// table on stdout and as JSON. The model executable writes the JSON of its
// run (ReportJson); the front end adds what it knows of the scene (AddScene)
// and prints it (PrintReport).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/ray.h"
#include "sim/core_params.h"
#include "sim/memory_model.h"
#include "sim/run_result.h"

namespace kdrt::sim {

struct ReportInputs {
  std::string loop;  // "verilator" or "systemc"
  CoreConfig config;
  SceneRequirements requirements;
  MemoryConfig memory;
  RayCounters reference_totals;  // TraceRays over every ray
  // WindowBoundCycles over the rays in issue order, `window_rays` at a time
  // (the rays in flight: threads x cores); 0: not reported.
  double window_bound_cycles = 0;
  uint64_t window_rays = 0;
  const RunOutcome* run = nullptr;
  uint64_t rays = 0;
  Query query = Query::kClosest;
};

nlohmann::json ReportJson(const ReportInputs& in);

// The per-core bound (one traversal step and one triangle test a cycle)
// taken `window` rays at a time: the sum over consecutive windows of rays in
// issue order (`order`, or the rays' own when null or empty) of max(nodes, tests),
// in cycles. Where the mix of nodes and tests changes across the frame, a
// core that holds a window's rays cannot overlap one unit's work on them
// with the other unit's on rays far ahead, so this is above the whole
// run's max(nodes, tests) (equal when `window` covers every ray). An
// estimate of what the rays in flight allow, not a bound: the rays in
// flight are not aligned to the windows, and a slow ray stays while later
// ones pass.
double WindowBoundCycles(const std::vector<RayCounters>& per_ray, const std::vector<uint32_t>* order,
                         uint64_t window);

// The report's window bound: the rays in flight (`threads` x `cores`, one
// core when `cores` is 0, as `kdrt sim --cores`) and WindowBoundCycles over
// them, into `in`. The one definition the RTL harness and the fast model share.
void SetWindowBound(const std::vector<RayCounters>& per_ray, const std::vector<uint32_t>* order, int threads,
                    int cores, ReportInputs* in);

// The report of several cores (kdrt sim --cores N): `in` describes the whole
// run (in.run unused); the unit, cache and thread figures are averages over
// the cores (counts summed, divided by N x cycles), cycles are the system's
// (the last core's), the bound is the per-core bound divided by N, and the
// memory figures are the memory's behind the L2. Adds "cores" (N),
// "per_core" (rays, cycles, cycles per ray, bound, efficiency, L2 reads per
// ray, utilisation, cache hit rates of each core) and "l2".
nlohmann::json SystemReportJson(const ReportInputs& in, const SystemOutcome& sys,
                                const std::vector<RayCounters>& per_ray);

// What only the front end knows: the scene, its tree and the image size.
struct SceneFacts {
  std::string scene;
  int width = 0, height = 0;
  uint64_t triangles = 0;
  uint64_t tree_nodes = 0;
  uint32_t tree_depth = 0;
};
void AddScene(const SceneFacts& facts, nlohmann::json* report);

// The same numbers as a table.
void PrintReport(const nlohmann::json& report, std::FILE* out);

// A shaded frame (kdrt sim --shade): `passes` as setup/shaded_frame.h's
// PassesJson, each pass's stats a ReportJson. The frame's totals: rays,
// cycles (the passes run one after another), cycles per ray, and the bound
// summed over the passes.
nlohmann::json FrameTotals(const nlohmann::json& passes);
// One line per pass and one for the frame.
// With "per_core" in the report: one line per core and the L2's.
void PrintCores(const nlohmann::json& report, std::FILE* out);
void PrintPasses(const nlohmann::json& passes, const nlohmann::json& totals, std::FILE* out);

}  // namespace kdrt::sim
