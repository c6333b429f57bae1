#include "setup/precision_check.h"

#include <cstdio>

#include "common/error.h"

namespace kdrt {

PrecisionCheck CheckPrecision(const ImageView& image, const std::vector<Ray>& rays, const fp::Format& format,
                              bool strict, int threads, const std::string& rays_name,
                              std::optional<fp::Format> image_format) {
  PrecisionCheck check;
  check.requirement = AnalyzePrecision(image, rays, threads);
  std::string shortfall = check.requirement.Shortfall(format, image_format.value_or(format));
  if (shortfall.empty()) return check;
  if (!rays_name.empty()) shortfall += " (" + rays_name + " rays)";
  if (strict) throw InputError(shortfall + " (--strict)");
  std::fprintf(stderr, "kdrt: warning: %s\n", shortfall.c_str());
  check.warnings.push_back(shortfall);
  return check;
}

}  // namespace kdrt
