// Structural checks run before assimp reads a PLY or OFF file. assimp 5.2
// accepts broken files silently (missing face indices read as 0, OFF
// indices clamped) or hangs on a PLY header without end_header, so kdrt
// walks the file first and reports file:line itself. These checks accept
// every well-formed file; assimp still does the actual reading.
#pragma once

#include <string>

namespace kdrt {

// `bytes` is the whole file. Throw InputError on a malformed header,
// truncated or over-long element data, non-numeric values, NaN/Inf vertex
// coordinates, faces with fewer than 3 vertices or out-of-range indices.
void CheckPly(const std::string& path, const std::string& bytes);
void CheckOff(const std::string& path, const std::string& bytes);

}  // namespace kdrt
