#include "tools/core_config.h"

#include "common/error.h"
#include "sim/model_runner.h"
#include "trace/memory_image.h"
#include "trace/tracer.h"

namespace kdrt::cli {

void AddFormatOptions(CLI::App& cmd, CoreConfigArgs& args) {
  cmd.add_option("--format", args.format, "Number format of the core: " + fp::PresetNames() + " or eXmY")
      ->capture_default_str();
  cmd.add_option("--trav-format", args.trav_format,
                 "Number format of the core's traversal datapath (ray setup's 1/d, box clip, split distances), "
                 "at least --format's bits and at most fp32; cell intervals and stacks stay in --format "
                 "(kdrt render --trav-format)");
  cmd.add_option("--image-format", args.image_format,
                 "Number format of the memory image the core reads (splits and vertices), at most --format's "
                 "bits: stored narrower, widened exactly on load, computed in --format (kdrt render "
                 "--image-format); default: --format");
}

CoreFormats ResolveFormats(const CoreConfigArgs& args) {
  CoreFormats f;
  f.overrides = args.overrides;
  f.format = fp::ParseFormat(args.format);
  if (f.format.IsFp64()) {
    throw InputError("--format fp64: no RTL model computes in fp64 (it is the software reference: kdrt render "
                     "--format fp64)");
  }
  if (!args.trav_format.empty()) {
    // A core with a wider traversal datapath (rt_core TravE, TravM): its own
    // model, sized for the scene like any non-default parameter.
    const fp::Format trav = fp::ParseFormat(args.trav_format);
    CheckTravFormat(f.format, trav);
    sim::OverrideTravFormat(f.format, trav, &f.overrides);
  }
  // A core reading a narrower image (rt_core ImgE, ImgM): splits and
  // vertices stored in fewer bits, widened exactly on load.
  f.image_format = args.image_format.empty() ? f.format : fp::ParseFormat(args.image_format);
  sim::OverrideImageFormat(f.format, f.image_format, &f.overrides);
  return f;
}

SceneCore ChooseSceneCore(const CoreFormats& formats, const std::vector<uint8_t>& fp32_image, uint64_t mem_size,
                          bool allow_overflow) {
  SceneCore s;
  // The core reads the image of its own format, or of --image-format
  // (docs/memory-image.md).
  s.core_image = sim::CoreImage(fp32_image, formats.image_format);
  s.req = sim::DeriveRequirements(ImageView(s.core_image));
  s.choice = sim::ChooseConfig(formats.format, s.req, formats.overrides, mem_size, allow_overflow);
  return s;
}

}  // namespace kdrt::cli
