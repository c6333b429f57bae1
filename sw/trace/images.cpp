#include "trace/images.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "trace/image_io_module.h"

namespace kdrt {

std::vector<float> ShadeEyeLight(const Scene& scene, const std::vector<Ray>& rays, const std::vector<Hit>& hits) {
  std::vector<float> rgb(3 * hits.size());
  for (size_t i = 0; i < hits.size(); ++i) {
    glm::vec3 c = scene.background;
    if (hits[i].IsHit() && hits[i].prim < scene.triangles.size()) {
      const Triangle& t = scene.triangles[hits[i].prim];
      const glm::vec3 n = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
      const float len_n = glm::length(n), len_d = glm::length(rays[i].d);
      const float cosine = len_n > 0 && len_d > 0 ? std::fabs(glm::dot(n, rays[i].d)) / (len_n * len_d) : 1.0f;
      glm::vec3 surface(1.0f);
      if (hits[i].prim < scene.material.size() && scene.material[hits[i].prim] < scene.colors.size()) {
        surface = scene.colors[scene.material[hits[i].prim]];
      }
      c = surface * cosine;
    }
    for (int k = 0; k < 3; ++k) rgb[3 * i + k] = c[k];
  }
  return rgb;
}

void WriteRgbImage(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  std::vector<uint8_t> pixels(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) {
    pixels[i] = static_cast<uint8_t>(std::lround(std::clamp(rgb[i], 0.0f, 1.0f) * 255.0f));
  }
  const std::string error = image_io::Get().write_rgb8(path, width, height, pixels);
  if (!error.empty()) throw InputError(path, 0, error);
}

void WriteHitBuffer(const std::string& path, int width, int height, const std::vector<Hit>& hits) {
  std::vector<uint32_t> pixels(4 * hits.size());
  for (size_t i = 0; i < hits.size(); ++i) {
    std::memcpy(&pixels[4 * i + 0], &hits[i].t, 4);
    pixels[4 * i + 1] = hits[i].prim;
    std::memcpy(&pixels[4 * i + 2], &hits[i].u, 4);
    std::memcpy(&pixels[4 * i + 3], &hits[i].v, 4);
  }
  const std::string error = image_io::Get().write_hits(path, width, height, pixels);
  if (!error.empty()) throw InputError(path, 0, error);
}

std::vector<Hit> ReadHitBuffer(const std::string& path, int* width, int* height) {
  std::vector<uint32_t> pixels;
  const std::string error = image_io::Get().read_hits(path, &pixels, width, height);
  if (!error.empty()) throw InputError(path, 0, error);
  std::vector<Hit> hits(pixels.size() / 4);
  for (size_t i = 0; i < hits.size(); ++i) {
    std::memcpy(&hits[i].t, &pixels[4 * i + 0], 4);
    hits[i].prim = pixels[4 * i + 1];
    std::memcpy(&hits[i].u, &pixels[4 * i + 2], 4);
    std::memcpy(&hits[i].v, &pixels[4 * i + 3], 4);
  }
  return hits;
}

std::vector<uint8_t> ReadImage8(const std::string& path, int* width, int* height, int* channels) {
  std::vector<uint8_t> pixels;
  const std::string error = image_io::Get().read_8bit(path, &pixels, width, height, channels);
  if (!error.empty()) throw InputError(path, 0, error);
  return pixels;
}

}  // namespace kdrt
