// The structures side by side on one scene (`kdrt compare-accel`): each one
// built and traced on the same camera rays in one run, its work counted and
// its hit buffer checked against the SAH kd-tree's, in the spirit of
// Havran's Best Efficiency Scheme tables (docs/structures.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "setup/prepared_scene.h"
#include "structures/structure_tracer.h"

namespace kdrt {

struct AccelCompareOptions {
  std::vector<AccelKind> kinds = AllAccelKinds();
  SceneSpec spec;          // build options of the kd-trees and the structures (spec.scene unused)
  std::string res;         // camera resolution WxH ("" = the scene's, else 512x512)
  int threads = 1;         // 1: single-thread timings
  fp::Format format{8, 23};
  int repeat = 1;          // trace this many times, keep the fastest
  bool progress = false;   // one line per structure on stderr
};

struct AccelRow {
  AccelKind kind = AccelKind::kSah;
  double build_seconds = 0;
  uint64_t memory_bytes = 0;   // nodes/cells and reference lists (triangles not included)
  uint64_t nodes_built = 0;    // cells or nodes in the structure
  uint64_t references = 0;
  AccelTotals totals;          // work summed over the rays; seconds = the fastest trace
  bool mailbox = false;
  uint64_t mismatches = 0;     // hit records that differ from the SAH kd-tree's (a bug)
  uint64_t ties = 0;           // same t bits, another triangle (a tie at equal t)
  double time_ratio = 0;       // trace seconds / the scene's fastest
  std::string error;           // why the structure could not be built (then nothing else is set)
  double Mrays() const { return totals.seconds > 0 ? totals.rays / totals.seconds * 1e-6 : 0.0; }
};

struct AccelComparison {
  std::string scene;
  size_t triangles = 0;
  int width = 0, height = 0;
  std::vector<AccelRow> rows;  // in options.kinds order
};

// Throws InputError for a bad scene, resolution or options (a format other
// than fp32/fp64). A structure that cannot be built on the scene (a kd-tree
// too large for the memory image) gets a row with its error, not an
// exception, so the other rows survive.
AccelComparison CompareAccels(const std::string& scene, const AccelCompareOptions& options);

nlohmann::json AccelComparisonJson(const AccelComparison& c);

// Nodes, leaves and triangle tests per ray of a traced batch, and the tests
// the mailboxes saved (null for a structure without them); 0 for no rays.
// The "per_ray" object of kdrt render and of each compare-accel row.
nlohmann::json PerRayJson(const AccelTotals& totals, bool mailbox);

}  // namespace kdrt
