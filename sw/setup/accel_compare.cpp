#include "setup/accel_compare.h"

#include <algorithm>
#include <cstdio>

#include "common/error.h"
#include "setup/ray_set.h"
#include "trace/hit_compare.h"
#include "trace/memory_image.h"

namespace kdrt {
namespace {

// Counts the records that differ from the reference: ties (another triangle
// at the same t, within kTieUlps) apart from real mismatches.
void CompareHits(const std::vector<Hit>& reference, const std::vector<Hit>& hits, AccelRow* row) {
  for (size_t i = 0; i < hits.size(); ++i) {
    if (SameBits(reference[i], hits[i])) continue;
    ++(IsTie(reference[i], hits[i]) ? row->ties : row->mismatches);
  }
}

// Traces `repeat` times and keeps the fastest run's time (the work is the
// same every time).
template <class TraceFn>
std::vector<Hit> Timed(int repeat, AccelTotals* totals, TraceFn&& trace) {
  std::vector<Hit> hits;
  double fastest = 0;
  for (int k = 0; k < std::max(1, repeat); ++k) {
    hits = trace(totals);
    if (k == 0 || totals->seconds < fastest) fastest = totals->seconds;
  }
  totals->seconds = fastest;
  return hits;
}

// Builds one structure and traces the rays through it, filling the row's
// build and work figures.
std::vector<Hit> BuildAndTrace(AccelKind kind, const Scene& scene, const SceneSpec& spec, const PreparedScene& sah,
                               const StructureInput& input, const std::vector<Ray>& rays, const TraceOptions& to,
                               const AccelCompareOptions& options, AccelRow* row) {
  if (IsKdTree(kind)) {
    BuildOptions build = spec.build;
    build.method = SplitMethodOf(kind);
    const PreparedScene p = kind == AccelKind::kSah ? PreparedScene{} : PrepareScene(scene, build);
    const PreparedScene& tree = kind == AccelKind::kSah ? sah : p;
    const ImageView image(tree.image);
    row->build_seconds = tree.tree.stats.build_seconds;
    row->memory_bytes = uint64_t{image.header().node_count} * img::kNodeBytes +
                        uint64_t{image.header().list_count} * sizeof(uint32_t);
    row->nodes_built = tree.tree.stats.nodes;
    row->references = tree.tree.stats.references;
    return Timed(options.repeat, &row->totals, [&](AccelTotals* totals) {
      TraceStats ts;
      std::vector<Hit> h = TraceRays(image, rays, to, &ts);
      *totals = ToAccelTotals(ts);
      return h;
    });
  }
  const std::unique_ptr<Structure> s = BuildStructure(kind, input, spec.structure);
  row->build_seconds = s->stats().build_seconds;
  row->memory_bytes = s->stats().memory_bytes;
  row->nodes_built = s->stats().nodes;
  row->references = s->stats().references;
  row->mailbox = s->uses_mailbox();
  return Timed(options.repeat, &row->totals,
               [&](AccelTotals* totals) { return TraceStructureRays(*s, sah.frame, rays, to, totals); });
}

}  // namespace

AccelComparison CompareAccels(const std::string& scene_name, const AccelCompareOptions& options) {
  TraceOptions to;
  to.format = options.format;
  to.threads = options.threads;
  CheckStructureTraceOptions(to);
  CheckStructureOptions(options.spec.structure);
  SceneSpec spec = options.spec;
  spec.scene = scene_name;
  const Scene scene = LoadOrGenerate(spec);
  const RaySet ray_set = MakeRays(scene, "", "", options.res);

  AccelComparison c;
  c.scene = scene.source;
  c.triangles = scene.triangles.size();
  c.width = ray_set.width;
  c.height = ray_set.height;

  // The SAH kd-tree comes first: its image feeds the other structures and
  // its hits are the reference.
  BuildOptions sah_build = spec.build;
  sah_build.method = SplitMethod::kSah;
  const PreparedScene sah = PrepareScene(scene, sah_build);
  const ImageView sah_image(sah.image);
  const std::vector<Hit> reference = TraceRays(sah_image, ray_set.rays, to);
  const StructureInput input = MakeStructureInput(sah_image);

  for (AccelKind kind : options.kinds) {
    if (options.progress) std::fprintf(stderr, "  %s: %s...\n", c.scene.c_str(), AccelKindName(kind));
    AccelRow row;
    row.kind = kind;
    try {
      const std::vector<Hit> hits = BuildAndTrace(kind, scene, spec, sah, input, ray_set.rays, to, options, &row);
      CompareHits(reference, hits, &row);
    } catch (const InputError& e) {
      row = AccelRow{};
      row.kind = kind;
      row.error = e.what();
    }
    c.rows.push_back(row);
  }
  double fastest = 0;
  for (const AccelRow& r : c.rows) {
    if (r.error.empty() && r.totals.seconds > 0 && (fastest == 0 || r.totals.seconds < fastest)) {
      fastest = r.totals.seconds;
    }
  }
  for (AccelRow& r : c.rows) r.time_ratio = fastest > 0 ? r.totals.seconds / fastest : 0.0;
  return c;
}

nlohmann::json PerRayJson(const AccelTotals& t, bool mailbox) {
  const double n = std::max<double>(1.0, static_cast<double>(t.rays));
  return {{"nodes", t.nodes / n},
          {"leaves", t.leaves / n},
          {"tri_tests", t.tri_tests / n},
          {"mailbox_hits", mailbox ? nlohmann::json(t.mailbox_hits / n) : nlohmann::json(nullptr)}};
}

nlohmann::json AccelComparisonJson(const AccelComparison& c) {
  nlohmann::json rows = nlohmann::json::array();
  for (const AccelRow& r : c.rows) {
    if (!r.error.empty()) {
      rows.push_back({{"structure", AccelKindName(r.kind)}, {"error", r.error}});
      continue;
    }
    nlohmann::json j = {
        {"structure", AccelKindName(r.kind)},
        {"build_seconds", r.build_seconds},
        {"memory_bytes", r.memory_bytes},
        {"nodes", r.nodes_built},
        {"references", r.references},
        {"refs_per_triangle", c.triangles ? double(r.references) / c.triangles : 0.0},
        {"rays", r.totals.rays},
        {"hits", r.totals.hits},
        {"trace_seconds", r.totals.seconds},
        {"mrays_per_second", r.Mrays()},
        {"time_ratio_to_best", r.time_ratio},
        {"per_ray", PerRayJson(r.totals, r.mailbox)},
        {"mismatches", r.mismatches},
        {"ties", r.ties},
    };
    rows.push_back(j);
  }
  return {{"scene", c.scene}, {"triangles", c.triangles}, {"width", c.width}, {"height", c.height}, {"rows", rows}};
}

}  // namespace kdrt
