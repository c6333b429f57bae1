#include "trade/accuracy.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "setup/extreme_cases.h"
#include "setup/prepared_scene.h"
#include "trace/tracer.h"

namespace kdrt::trade {
namespace {

// Nearest-rank percentile of sorted values.
double Percentile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const size_t rank = static_cast<size_t>(std::ceil(q * sorted.size()));
  return sorted[std::min(sorted.size() - 1, rank > 0 ? rank - 1 : 0)];
}

uint8_t To8Bit(float x) { return static_cast<uint8_t>(std::lround(std::clamp(x, 0.0f, 1.0f) * 255.0f)); }

}  // namespace

double Psnr8(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double d = static_cast<double>(To8Bit(a[i])) - To8Bit(b[i]);
    sum += d * d;
  }
  if (sum == 0 || a.empty()) return std::numeric_limits<double>::infinity();
  const double mse = sum / a.size();
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

Accuracy CompareWithTruth(const std::vector<Hit>& hits, const std::vector<Hit>& truth, const std::vector<float>& rgb,
                          const std::vector<float>& truth_rgb) {
  Accuracy a;
  a.rays = hits.size();
  std::vector<double> rel;
  for (size_t i = 0; i < hits.size(); ++i) {
    const bool hit = hits[i].IsHit(), truth_hit = truth[i].IsHit();
    if (hit != truth_hit) {
      ++a.hitmiss;
      continue;
    }
    if (!hit) continue;
    ++a.common_hits;
    a.prim += hits[i].prim != truth[i].prim;
    const double t = hits[i].t, tt = truth[i].t;
    rel.push_back(tt != 0 ? std::fabs(t - tt) / std::fabs(tt) : std::fabs(t));
  }
  std::sort(rel.begin(), rel.end());
  a.t_rel_p50 = Percentile(rel, 0.50);
  a.t_rel_p99 = Percentile(rel, 0.99);
  a.t_rel_max = rel.empty() ? 0.0 : rel.back();
  a.psnr_db = Psnr8(rgb, truth_rgb);
  return a;
}

Holes WatertightHoles(const fp::Format& format) {
  // The cases are built once per process: trade asks for every format.
  static std::once_flag once;
  static std::vector<ExtremeCase> cases;
  static std::vector<PreparedScene> prepared;
  std::call_once(once, [] {
    for (ExtremeCase& c : MakeExtremeCases(/*reduced=*/true)) {
      if (c.group != "unit" && c.group != "dense") continue;
      prepared.push_back(PrepareScene(c.scene, BuildOptions{}));
      cases.push_back(std::move(c));
    }
  });
  Holes h;
  for (size_t k = 0; k < cases.size(); ++k) {
    TraceOptions to;
    to.format = format;
    const std::vector<Hit> hits = TraceRays(ImageView(prepared[k].image), cases[k].rays, to);
    for (size_t i = 0; i < hits.size(); ++i) {
      h.must_hit += cases[k].must_hit[i];
      h.holes += cases[k].must_hit[i] && !hits[i].IsHit();
    }
    h.cases += (h.cases.empty() ? "" : ", ") + cases[k].name;
  }
  return h;
}

}  // namespace kdrt::trade
