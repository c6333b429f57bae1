// The precision check of `kdrt render` and `kdrt sim`: the scene's
// requirement (trace/precision.h) against the chosen format, before anything
// is traced, so that a format too small for the scene never fails silently.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/ray.h"
#include "fp/format.h"
#include "trace/memory_image.h"
#include "trace/precision.h"

namespace kdrt {

struct PrecisionCheck {
  PrecisionRequirement requirement;
  std::vector<std::string> warnings;  // the JSON "warnings" array (empty when the format suffices)
};

// Prints each warning on stderr as "kdrt: warning: <text>"; with `strict`
// throws InputError(<text>) instead (the caller then writes nothing).
// `rays_name` (e.g. "shadow", for a shaded frame's passes) is named in the
// text when given. `image_format`, when given, is the format of the image the
// datapath reads (at most `format`'s bits: --image-format; `format` itself
// changes nothing): the storage criteria are checked against it.
PrecisionCheck CheckPrecision(const ImageView& image, const std::vector<Ray>& rays, const fp::Format& format,
                              bool strict, int threads, const std::string& rays_name = "",
                              std::optional<fp::Format> image_format = std::nullopt);

}  // namespace kdrt
