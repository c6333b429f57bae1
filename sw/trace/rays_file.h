// Ray files (--rays): little-endian, 8-byte magic "KDRTRAYS", uint32
// version, uint32 count, in version 2 a uint32 query (0: closest hit, 1:
// any hit, as shadow rays), then count x 8 float32
// (ox oy oz dx dy dz tmin tmax). Version 1 (no query word) is read as
// closest-hit rays; files are written as version 2.
#pragma once

#include <string>
#include <vector>

#include "common/ray.h"

namespace kdrt {

// Throws InputError naming the file and the offending ray: bad magic, wrong
// version, size not matching the count, NaN/Inf origin or direction, zero
// direction, NaN or negative tmin, NaN tmax, tmax < tmin, unknown query.
// `query`, if given, receives the file's query.
std::vector<Ray> ReadRaysFile(const std::string& path, Query* query = nullptr);

// Writes atomically (temporary file, then rename).
void WriteRaysFile(const std::string& path, const std::vector<Ray>& rays, Query query = Query::kClosest);

}  // namespace kdrt
