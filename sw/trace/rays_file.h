// Ray files (--rays): little-endian, 8-byte magic "KDRTRAYS", uint32
// version = 1, uint32 count, then count x 8 float32
// (ox oy oz dx dy dz tmin tmax).
#pragma once

#include <string>
#include <vector>

#include "common/ray.h"

namespace kdrt {

// Throws InputError naming the file and the offending ray: bad magic, wrong
// version, size not matching the count, NaN/Inf origin or direction, zero
// direction, NaN or negative tmin, NaN tmax, tmax < tmin.
std::vector<Ray> ReadRaysFile(const std::string& path);

// Writes atomically (temporary file, then rename).
void WriteRaysFile(const std::string& path, const std::vector<Ray>& rays);

}  // namespace kdrt
