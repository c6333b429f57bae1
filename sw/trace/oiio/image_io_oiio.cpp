// The image module's OpenImageIO side (trace/image_io_module.h).
#include <OpenImageIO/imageio.h>

#include "trace/image_io_module.h"

namespace {

std::string WriteRgb8(const std::string& path, int width, int height, const std::vector<uint8_t>& pixels) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return "cannot write image: " + OIIO::geterror();
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("DateTime", "1970:01:01 00:00:00");  // deterministic bytes
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !out->close()) {
    return "cannot write image: " + out->geterror();
  }
  return "";
}

std::string WriteHits(const std::string& path, int width, int height, const std::vector<uint32_t>& pixels) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return "cannot write hit buffer: " + OIIO::geterror();
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"t", "prim", "u", "v"};
  spec.channelformats = {OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::UINT32, OIIO::TypeDesc::FLOAT,
                         OIIO::TypeDesc::FLOAT};
  spec.attribute("compression", "zip");
  // OpenImageIO stamps the write time unless told otherwise; a fixed value
  // keeps hit buffers byte-identical between runs (and between render and sim).
  spec.attribute("DateTime", "1970:01:01 00:00:00");
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UNKNOWN, pixels.data(), 4 * sizeof(uint32_t)) ||
      !out->close()) {
    return "cannot write hit buffer: " + out->geterror();
  }
  return "";
}

std::string ReadHits(const std::string& path, std::vector<uint32_t>* pixels, int* width, int* height) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return "cannot read hit buffer: " + OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  int channel[4] = {-1, -1, -1, -1};  // t, prim, u, v
  const char* const names[4] = {"t", "prim", "u", "v"};
  for (int c = 0; c < spec.nchannels; ++c) {
    for (int k = 0; k < 4; ++k) {
      if (spec.channelnames[c] == names[k]) channel[k] = c;
    }
  }
  for (int k = 0; k < 4; ++k) {
    if (channel[k] < 0) return "not a kdrt hit buffer (needs t, prim, u, v)";
  }
  const size_t n = static_cast<size_t>(spec.width) * spec.height;
  pixels->assign(4 * n, 0);
  // Each channel in its own type (prim is uint32, the others float), into its
  // slot of the pixel.
  for (int k = 0; k < 4; ++k) {
    const OIIO::TypeDesc type = k == 1 ? OIIO::TypeDesc::UINT32 : OIIO::TypeDesc::FLOAT;
    if (!in->read_image(0, 0, channel[k], channel[k] + 1, type, pixels->data() + k, 4 * sizeof(uint32_t))) {
      return "cannot read hit buffer: " + in->geterror();
    }
  }
  *width = spec.width;
  *height = spec.height;
  return "";
}

std::string Read8Bit(const std::string& path, std::vector<uint8_t>* pixels, int* width, int* height, int* channels) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return "cannot read image: " + OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  pixels->assign(static_cast<size_t>(spec.width) * spec.height * spec.nchannels, 0);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels->data())) {
    return "cannot read image: " + in->geterror();
  }
  *width = spec.width;
  *height = spec.height;
  *channels = spec.nchannels;
  return "";
}

const kdrt::image_io::Module kModule = {kdrt::image_io::kModuleVersion, WriteRgb8, WriteHits, ReadHits, Read8Bit};

}  // namespace

extern "C" const kdrt::image_io::Module* kdrt_image_io_module() { return &kModule; }
