// `kdrt trade`: for each number format, side by side, what it costs (area,
// cycles, work, memory) and what it loses (accuracy against the fp64 truth).
// docs/trade.md describes every column.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/ray.h"
#include "fp/format.h"
#include "setup/prepared_scene.h"
#include "setup/ray_set.h"
#include "trade/accuracy.h"
#include "trade/area.h"

namespace kdrt::trade {

struct TradeOptions {
  std::vector<fp::Format> formats;  // soft formats (not fp64: the truth is always traced)
  double target_mismatch = 1e-3;    // the recommendation's bound on MismatchFraction()
  bool sim = false;                 // run the RTL core
  uint64_t sim_rays = 0;            // simulate every k-th ray so that at most this many run; 0: all
  bool area = true;                 // false: no area columns (--no-area)
  AreaOptions area_options;
  int threads = 0;                  // of the software tracer
  std::function<void(const std::string&)> progress;  // phase messages; may be empty
};

struct SimNumbers {
  uint64_t rays = 0;  // simulated (a subsample when fewer than the trace's)
  double cycles_per_ray = 0;
  double efficiency = 0;
  double bytes_per_ray = 0;
  nlohmann::json cache_hit_rate;  // as in kdrt sim's JSON
  nlohmann::json model;           // the simulated configuration, as kdrt sim's "model" (key and parameters)
  double RaysPerCycle() const { return cycles_per_ray > 0 ? 1.0 / cycles_per_ray : 0.0; }
};

struct FormatResult {
  fp::Format format;
  std::string warning;  // the precision requirement's shortfall ("" when the format suffices)
  Accuracy accuracy;    // against the truth (all zero for the truth itself)
  Holes holes;
  double nodes = 0, leaves = 0, tri_tests = 0;  // per ray
  double trace_seconds = 0;
  std::optional<SimNumbers> sim;
  std::optional<Area> area;
  // kdrt sim's physical block (sim/phys.h) of the simulated configuration
  // when build/phys has its synthesis (kdrt synth); null otherwise.
  nlohmann::json physical;
  uint64_t memory_bytes = 0;
  std::vector<Hit> hits;
  std::vector<float> rgb;  // the shaded image
  // Rays per cycle per 1,000 cells: performance per area (needs sim and area).
  std::optional<double> RaysPerCyclePerKcell() const;
  // physical's Mrays/s per mm^2 on the cell library, and scaled to 28 nm
  // (nullopt without a synthesis of the simulated configuration).
  std::optional<double> MraysPerSPerMm2() const;
  std::optional<double> MraysPerSPerMm2At28nm() const;
};

struct TradeResult {
  std::string scene;
  uint64_t triangles = 0;
  int width = 0, height = 1;
  bool from_rays_file = false;
  uint64_t rays = 0;
  uint64_t sim_stride = 1;    // every sim_stride-th ray was simulated
  std::string minimal_format;  // the scene's, from the requirement analysis
  double target_mismatch = 0;
  std::string recommended;     // "" when no format meets the target
  FormatResult truth;          // fp64
  std::vector<FormatResult> formats;
  std::vector<std::string> notes;  // what is weaker than a user would assume (also on stderr)
};

// Throws InputError when a format has no RTL model but --sim or area needs one
// (E > 8, M > 23), or when the RTL run fails or differs from the reference.
TradeResult MeasureTrade(const PreparedScene& scene, const RaySet& rays, const TradeOptions& options);

// The smallest format (bits, then cells) with MismatchFraction() <= target and
// no holes; "" when none.
std::string Recommend(const std::vector<FormatResult>& formats, double target);

}  // namespace kdrt::trade
