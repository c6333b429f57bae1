// The core configuration options `kdrt sim` and `kdrt synth` share, and the
// one way from them (and a scene) to the rt_core parameters that run: the
// model key a simulation reports is the one a synthesis is stored under.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "fp/format.h"
#include "sim/core_params.h"

namespace kdrt::cli {

struct CoreConfigArgs {
  std::string format = "fp32";
  std::string trav_format;   // empty: --format
  std::string image_format;  // empty: --format
  sim::ConfigOverrides overrides;
};

// --format, --trav-format, --image-format.
void AddFormatOptions(CLI::App& cmd, CoreConfigArgs& args);

// The formats, checked (fp64 and formats the RTL has not are refused), with
// --trav-format and --image-format turned into overrides of TravE, TravM,
// ImgE, ImgM.
struct CoreFormats {
  fp::Format format;
  fp::Format image_format;
  sim::ConfigOverrides overrides;
};
CoreFormats ResolveFormats(const CoreConfigArgs& args);

// What a scene's memory image needs of the core and the configuration that
// runs it (sim::ChooseConfig): the prebuilt model of the format when it
// covers the scene and nothing else is asked for, else a scene-sized one.
// `fp32_image`: the scene's image (PrepareScene); the core reads it in
// image_format.
struct SceneCore {
  std::vector<uint8_t> core_image;
  sim::SceneRequirements req;
  sim::ConfigChoice choice;
};
SceneCore ChooseSceneCore(const CoreFormats& formats, const std::vector<uint8_t>& fp32_image, uint64_t mem_size,
                          bool allow_overflow);

}  // namespace kdrt::cli
