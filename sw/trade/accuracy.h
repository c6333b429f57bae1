// Accuracy of a format's hits against the fp64 truth (`kdrt render --format
// fp64`): what `kdrt trade` reports per format.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/ray.h"
#include "fp/format.h"

namespace kdrt::trade {

struct Accuracy {
  uint64_t rays = 0;
  uint64_t hitmiss = 0;      // rays whose hit/miss differs from the truth
  uint64_t prim = 0;         // both hit, another triangle
  uint64_t common_hits = 0;  // both hit (the t errors are over these)
  double t_rel_p50 = 0, t_rel_p99 = 0, t_rel_max = 0;  // |t - t_truth| / |t_truth|
  double psnr_db = 0;        // of the 8-bit shaded image; +inf when identical
  double HitmissFraction() const { return rays ? static_cast<double>(hitmiss) / rays : 0.0; }
  double PrimFraction() const { return rays ? static_cast<double>(prim) / rays : 0.0; }
  // Rays that see another surface than the truth: hit/miss or triangle.
  double MismatchFraction() const { return rays ? static_cast<double>(hitmiss + prim) / rays : 0.0; }
};

// `rgb` and `truth_rgb` are the shaded images (images.h ShadeEyeLight) of
// `hits` and `truth`. The truth's t is fp64 rounded once to the record's
// float, so errors below about 6e-8 are not resolved.
Accuracy CompareWithTruth(const std::vector<Hit>& hits, const std::vector<Hit>& truth, const std::vector<float>& rgb,
                          const std::vector<float>& truth_rgb);

// PSNR in dB of two RGB float images after the 8-bit quantisation the PNG
// writer applies (clamp to [0,1], round to 0..255); +inf when equal.
double Psnr8(const std::vector<float>& a, const std::vector<float>& b);

// The closed-mesh watertightness set: `kdrt extremes --reduced` cases of the
// groups "unit" (sphere and cube at unit scale) and "dense" (a dense sphere
// seen from far), rays through every vertex and edge midpoint, all of which
// must hit.
struct Holes {
  uint64_t holes = 0;     // must-hit rays that missed
  uint64_t must_hit = 0;  // of this many
  std::string cases;      // the case names, comma-separated
};
Holes WatertightHoles(const fp::Format& format);

}  // namespace kdrt::trade
