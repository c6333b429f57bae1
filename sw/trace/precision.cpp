#include "trace/precision.h"

#include <algorithm>

#include "trace/precision_criteria.h"
#include "trace/tracer.h"

namespace kdrt {

int PrecisionCriterion::MinBits() const {
  for (size_t b = needing.size(); b-- > 0;) {
    if (needing[b] > 0) return static_cast<int>(b);
  }
  return 0;
}

uint64_t PrecisionCriterion::Failing(int bits) const {
  uint64_t n = 0;
  for (size_t b = static_cast<size_t>(std::max(bits + 1, 0)); b < needing.size(); ++b) n += needing[b];
  return n;
}

std::string PrecisionRequirement::MinimalFormat() const {
  return "e" + std::to_string(min_exponent_bits) + "m" + std::to_string(min_mantissa_bits);
}

std::string PrecisionRequirement::MinimalImageFormat() const {
  return "e" + std::to_string(min_image_exponent_bits) + "m" + std::to_string(min_image_mantissa_bits);
}

std::string PrecisionRequirement::Shortfall(const fp::Format& f, const fp::Format& image) const {
  std::string what;
  for (const PrecisionCriterion& c : criteria) {
    const fp::Format& by = c.storage ? image : f;
    const uint64_t n = c.Failing(c.exponent ? by.e : by.m);
    if (n == 0) continue;
    what += (what.empty() ? "" : "; ") + std::to_string(n) + " of " + std::to_string(c.checked) + " " + c.items +
            " " + c.breaks;
  }
  if (what.empty()) return "";
  if (image == f) {
    return f.Name() + " cannot represent this scene: " + what + " (minimal format " + MinimalFormat() + ")";
  }
  return f.Name() + " with its image in " + image.Name() + " cannot represent this scene: " + what +
         " (minimal format " + MinimalFormat() + ", minimal image format " + MinimalImageFormat() + ")";
}

nlohmann::json PrecisionRequirement::Json() const {
  nlohmann::json crit = nlohmann::json::object();
  for (const PrecisionCriterion& c : criteria) {
    nlohmann::json needing = nlohmann::json::object();
    for (size_t b = 1; b < c.needing.size(); ++b) {
      if (c.needing[b] > 0) needing[std::to_string(b)] = c.needing[b];
    }
    nlohmann::json failing = nlohmann::json::object();
    for (const fp::Format& f : fp::Presets()) failing[f.Name()] = c.Failing(c.exponent ? f.e : f.m);
    crit[c.name] = {{"bits", c.exponent ? "exponent" : "mantissa"},
                    {"items", c.items},
                    {"checked", c.checked},
                    {"min_bits", c.MinBits()},
                    {"items_needing_bits", needing},
                    {"failing", failing}};
  }
  return {{"min_exponent_bits", min_exponent_bits},
          {"min_mantissa_bits", min_mantissa_bits},
          {"minimal_format", MinimalFormat()},
          {"min_image_exponent_bits", min_image_exponent_bits},
          {"min_image_mantissa_bits", min_image_mantissa_bits},
          {"minimal_image_format", MinimalImageFormat()},
          {"rays", rays},
          {"hit_tests", hit_tests},
          {"criteria", crit}};
}

PrecisionRequirement AnalyzePrecision(const ImageView& image, const std::vector<Ray>& rays, int threads) {
  PrecisionRequirement req;
  precision::AddImageExponentCriteria(image, &req.criteria);
  if (!rays.empty()) {
    // The hit each ray should have: the triangle whose test the format must
    // be able to compute. fp64 is the reference; its own rounding is far
    // below anything a soft format resolves.
    TraceOptions o;
    o.format = fp::kFp64;
    o.threads = threads;
    const std::vector<Hit> hits = TraceRays(image, rays, o);
    precision::AddRayExponentCriteria(image, rays, hits, &req.criteria);
    precision::AddRayMantissaCriteria(image, rays, hits, threads, &req.criteria);
    req.rays = rays.size();
    for (const Hit& h : hits) req.hit_tests += h.IsHit();
  }
  precision::AddMantissaCriteria(image, threads, &req.criteria);
  for (const PrecisionCriterion& c : req.criteria) {
    int& min_bits = c.exponent ? req.min_exponent_bits : req.min_mantissa_bits;
    min_bits = std::max(min_bits, c.MinBits());
    if (!c.storage) continue;
    int& image_bits = c.exponent ? req.min_image_exponent_bits : req.min_image_mantissa_bits;
    image_bits = std::max(image_bits, c.MinBits());
  }
  return req;
}

}  // namespace kdrt
