// Writes a Scene as NFF: the `v` block (if the scene has a camera), `b`,
// an `f` line before the first triangle and whenever the colour changes,
// and every triangle as `p 3`. Floats use "%.9g", which reads back as the
// same float, so LoadScene(WriteNff(scene)) gives bit-identical triangles,
// colours and camera. Kd/Ks/shine/T/ior are not kept by Scene and are
// written as 1 0 0 0 1.
#pragma once

#include <string>

#include "scene/scene.h"

namespace kdrt {

// Writes to a temporary file next to `path` and renames it, so `path` is
// either the complete new file or untouched. Throws InputError on an I/O
// error or a scene that NFF cannot hold (NaN/Inf, bad material index).
void WriteNff(const Scene& scene, const std::string& path);

}  // namespace kdrt
