// The cases of `kdrt extremes` (numerics at the extremes): scenes and
// ray sets that push the arithmetic to its limits, each with the rays that
// must hit (a miss among them is a hole: the ray was aimed through the
// interior of a closed mesh).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/ray.h"
#include "scene/scene.h"

namespace kdrt {

struct ExtremeCase {
  std::string name;   // e.g. "offset 1e5", unique, no spaces doubled
  std::string group;  // offset, scale, direction, axis, surface, grazing, dense, sliver, needle, degenerate, one-point
  Scene scene;
  std::vector<Ray> rays;
  std::vector<uint8_t> must_hit;  // per ray
};

// Every case; `reduced` keeps a representative subset with smaller meshes
// (what `make test` runs).
std::vector<ExtremeCase> MakeExtremeCases(bool reduced);

}  // namespace kdrt
