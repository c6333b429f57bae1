#include "setup/shaded_frame.h"

#include "trace/rays_file.h"

namespace kdrt {

ShadedFrame TraceShadedFrame(const Scene& scene, const ShadingOptions& options, const std::vector<Ray>& primary,
                             const std::vector<Hit>& primary_hits, const nlohmann::json& primary_stats,
                             const PassTracer& trace) {
  const FrameShader shader(scene, options);
  ShadedFrame frame;
  RayPass first{"primary", Query::kClosest, primary, {}, {}};
  frame.passes.push_back(TracedPass{std::move(first), primary_hits, primary_stats});
  std::vector<RayPass> secondary = shader.SecondaryPasses(primary, primary_hits);
  std::vector<std::vector<Hit>> hits;
  for (RayPass& pass : secondary) {
    TracedPass traced;
    if (!pass.rays.empty()) traced.hits = trace(pass, &traced.stats);
    hits.push_back(traced.hits);
    traced.pass = std::move(pass);
    frame.passes.push_back(std::move(traced));
  }
  std::vector<RayPass> passes;
  for (size_t k = 1; k < frame.passes.size(); ++k) passes.push_back(frame.passes[k].pass);
  frame.rgb = shader.Shade(primary, primary_hits, passes, hits);
  return frame;
}

void AddRayPassFiles(OutputSet& outputs, const std::string& dir, const std::vector<TracedPass>& passes) {
  outputs.AddDirectory(dir, "primary.rays", [&](const std::string& tmp) {
    for (const TracedPass& p : passes) {
      // An empty pass (no hits to shade) has no file: a ray file holds at least one ray.
      if (!p.pass.rays.empty()) WriteRaysFile(tmp + "/" + p.pass.name + ".rays", p.pass.rays, p.pass.query);
    }
  });
}

nlohmann::json PassesJson(const std::vector<TracedPass>& passes) {
  nlohmann::json out = nlohmann::json::array();
  for (const TracedPass& p : passes) {
    uint64_t hits = 0;
    for (const Hit& h : p.hits) hits += h.IsHit();
    out.push_back({{"name", p.pass.name},
                   {"query", p.pass.query == Query::kAny ? "any" : "closest"},
                   {"rays", p.pass.rays.size()},
                   {"hits", hits},
                   {"stats", p.stats}});
  }
  return out;
}

}  // namespace kdrt
