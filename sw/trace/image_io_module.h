// The image file calls (OpenImageIO), kept in a module that is loaded the
// first time a program reads or writes an image: OpenImageIO brings about 250
// shared libraries whose symbol binding costs about a third of a second, which
// a process that never touches an image (kdrt --help, kdrt info, a model
// executable, most test processes) then does not pay.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kdrt::image_io {

// The module's functions. Each returns "" on success, else the message of
// what went wrong (the caller names the file).
struct Module {
  int version;
  std::string (*write_rgb8)(const std::string& path, int width, int height, const std::vector<uint8_t>& pixels);
  // Channels t, prim (uint32), u, v; `pixels` holds 4 x 32 bits per pixel in
  // that order.
  std::string (*write_hits)(const std::string& path, int width, int height, const std::vector<uint32_t>& pixels);
  // The same layout back; "not a kdrt hit buffer ..." when a channel is absent.
  std::string (*read_hits)(const std::string& path, std::vector<uint32_t>* pixels, int* width, int* height);
  // Every channel as 8 bits, interleaved.
  std::string (*read_8bit)(const std::string& path, std::vector<uint8_t>* pixels, int* width, int* height,
                           int* channels);
};

constexpr int kModuleVersion = 1;

// The loaded module (loads it on the first call; thread-safe). Throws
// std::runtime_error naming the module file when it cannot be loaded.
const Module& Get();

}  // namespace kdrt::image_io

// The module's one exported symbol.
extern "C" const kdrt::image_io::Module* kdrt_image_io_module();
