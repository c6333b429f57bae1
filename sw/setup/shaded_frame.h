// A shaded frame traced pass by pass (trace/shading.h): the primary rays'
// hits are given, each secondary pass is traced by the caller's tracer (the
// reference model in kdrt render, the RTL core in kdrt sim), and the image is
// shaded from all the hit records.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/ray.h"
#include "scene/scene.h"
#include "trace/output_file.h"
#include "trace/shading.h"

namespace kdrt {

struct TracedPass {
  RayPass pass;
  std::vector<Hit> hits;
  nlohmann::json stats;  // what the tracer reported for the pass (null if it had no rays)
};

struct ShadedFrame {
  std::vector<TracedPass> passes;  // primary first, then FrameShader::SecondaryPasses' order
  std::vector<float> rgb;
};

// Traces one pass and returns its hit records (one per ray, in order),
// filling `stats` with its report.
using PassTracer = std::function<std::vector<Hit>(const RayPass& pass, nlohmann::json* stats)>;

ShadedFrame TraceShadedFrame(const Scene& scene, const ShadingOptions& options, const std::vector<Ray>& primary,
                             const std::vector<Hit>& primary_hits, const nlohmann::json& primary_stats,
                             const PassTracer& trace);

// The frame's ray sets as ray files DIR/<pass>.rays (primary, shadow, ao,
// bounce; each with its query), queued on `outputs` as one directory.
void AddRayPassFiles(OutputSet& outputs, const std::string& dir, const std::vector<TracedPass>& passes);

// {"name", "query", "rays", "hits"} per pass, plus the tracer's stats.
nlohmann::json PassesJson(const std::vector<TracedPass>& passes);

}  // namespace kdrt
