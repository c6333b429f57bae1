// The per-format loaders behind LoadScene (scene.cpp picks one by extension).
// Each returns the triangles in file order and throws InputError.
#pragma once

#include <string>

#include "scene/scene.h"

namespace kdrt {

Scene LoadNff(const std::string& path, const LoadOptions& options);
Scene LoadObj(const std::string& path);
Scene LoadWithAssimp(const std::string& path, bool is_ply);  // PLY or OFF

}  // namespace kdrt
