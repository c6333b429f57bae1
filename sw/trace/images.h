// Images and hit buffers written by `kdrt render` and `kdrt sim`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/ray.h"
#include "scene/scene.h"

namespace kdrt {

// Eye-light shading: |cos| between the geometric normal and the ray, times
// the triangle's NFF surface colour; misses get the background colour.
// Returns width*height RGB floats, row 0 at the top.
std::vector<float> ShadeEyeLight(const Scene& scene, const std::vector<Ray>& rays, const std::vector<Hit>& hits);

// 8-bit RGB, values clamped to [0,1], no gamma (format from the extension:
// .png, .ppm, .exr, ...). Writes straight to `path`: wrap in an OutputSet.
void WriteRgbImage(const std::string& path, int width, int height, const std::vector<float>& rgb);

// EXR hit buffer: channels t (float32, +inf on a miss), prim (uint32,
// 0xFFFFFFFF on a miss), u, v (float32).
void WriteHitBuffer(const std::string& path, int width, int height, const std::vector<Hit>& hits);
std::vector<Hit> ReadHitBuffer(const std::string& path, int* width, int* height);

// Any image OpenImageIO reads, every channel as 8 bits, interleaved.
std::vector<uint8_t> ReadImage8(const std::string& path, int* width, int* height, int* channels);

}  // namespace kdrt
