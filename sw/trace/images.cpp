#include "trace/images.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include "common/error.h"

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
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw InputError(path, 0, "cannot write image: " + OIIO::geterror());
  std::vector<unsigned char> pixels(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) {
    pixels[i] = static_cast<unsigned char>(std::lround(std::clamp(rgb[i], 0.0f, 1.0f) * 255.0f));
  }
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("DateTime", "1970:01:01 00:00:00");  // deterministic bytes
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !out->close()) {
    throw InputError(path, 0, "cannot write image: " + out->geterror());
  }
}

namespace {
// Per-pixel layout handed to OpenImageIO; channel names in this order.
struct HitPixel {
  float t;
  uint32_t prim;
  float u, v;
};
}  // namespace

void WriteHitBuffer(const std::string& path, int width, int height, const std::vector<Hit>& hits) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw InputError(path, 0, "cannot write hit buffer: " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"t", "prim", "u", "v"};
  spec.channelformats = {OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::UINT32, OIIO::TypeDesc::FLOAT,
                         OIIO::TypeDesc::FLOAT};
  spec.attribute("compression", "zip");
  // OpenImageIO stamps the write time unless told otherwise; a fixed value
  // keeps hit buffers byte-identical between runs (and between render and sim).
  spec.attribute("DateTime", "1970:01:01 00:00:00");
  std::vector<HitPixel> pixels(hits.size());
  for (size_t i = 0; i < hits.size(); ++i) pixels[i] = {hits[i].t, hits[i].prim, hits[i].u, hits[i].v};
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UNKNOWN, pixels.data(), sizeof(HitPixel)) ||
      !out->close()) {
    throw InputError(path, 0, "cannot write hit buffer: " + out->geterror());
  }
}

std::vector<Hit> ReadHitBuffer(const std::string& path, int* width, int* height) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path, 0, "cannot read hit buffer: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  int ct = -1, cp = -1, cu = -1, cv = -1;
  for (int c = 0; c < spec.nchannels; ++c) {
    const std::string& n = spec.channelnames[c];
    if (n == "t") ct = c;
    if (n == "prim") cp = c;
    if (n == "u") cu = c;
    if (n == "v") cv = c;
  }
  if (ct < 0 || cp < 0 || cu < 0 || cv < 0) throw InputError(path, 0, "not a kdrt hit buffer (needs t, prim, u, v)");
  const size_t n = static_cast<size_t>(spec.width) * spec.height;
  // Read every channel in its native type and pick the fields out.
  std::vector<Hit> hits(n);
  std::vector<float> fl(n);
  std::vector<uint32_t> ui(n);
  auto read_channel = [&](int c, OIIO::TypeDesc type, void* dst) {
    if (!in->read_image(0, 0, c, c + 1, type, dst)) throw InputError(path, 0, "cannot read hit buffer: " + in->geterror());
  };
  read_channel(ct, OIIO::TypeDesc::FLOAT, fl.data());
  for (size_t i = 0; i < n; ++i) hits[i].t = fl[i];
  read_channel(cu, OIIO::TypeDesc::FLOAT, fl.data());
  for (size_t i = 0; i < n; ++i) hits[i].u = fl[i];
  read_channel(cv, OIIO::TypeDesc::FLOAT, fl.data());
  for (size_t i = 0; i < n; ++i) hits[i].v = fl[i];
  read_channel(cp, OIIO::TypeDesc::UINT32, ui.data());
  for (size_t i = 0; i < n; ++i) hits[i].prim = ui[i];
  *width = spec.width;
  *height = spec.height;
  return hits;
}

}  // namespace kdrt
