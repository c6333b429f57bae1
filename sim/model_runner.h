// The `kdrt sim` front end's side of a model executable: where the model of a
// configuration lives, building it once when it is missing, and running it on
// a memory image and a ray set that the front end has already built.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/ray.h"
#include "sim/core_params.h"
#include "sim/run_options.h"

namespace kdrt::sim {

struct ModelLocation {
  std::string path;    // the executable
  std::string target;  // its CMake target
  bool built = false;  // it exists and is newer than every source it is built from
  bool stale = false;  // it exists, but a source (rtl/, sim/, sw/) changed since
  // A scene-sized model compiled without optimisation, because the
  // environment has KDRT_QUICK_MODELS set (the tests do: they run a few
  // hundred rays on a model they build, so its compile time is their cost).
  bool quick = false;
};
ModelLocation LocateModel(const ConfigChoice& choice);

// Whether KDRT_QUICK_MODELS asks for quick builds (set, not empty, not "0").
bool QuickModels();

// Builds the model with CMake in the build tree this program belongs to
// (a few minutes; progress and the log path on stderr). A lock keeps
// concurrent runs from building at the same time. Throws on failure, with the
// end of the build log.
void BuildModel(const ConfigChoice& choice, const ModelLocation& location);

struct ModelRun {
  int exit_code = 0;         // the model's: 0, 1 (bad input), 3 (mismatch, timeout)
  std::vector<Hit> hits;     // by ray, when exit_code == 0
  nlohmann::json report;     // ReportJson of the run, when exit_code == 0
};

// Hands the image and the rays to the model through files in a temporary
// directory, runs it with `run` (waveform to `trace_path`, if set), and reads
// back its hit records and report. The model's messages go to stderr as they
// come.
// `query`: closest-hit or any-hit (shadow) rays, for every ray of the set.
ModelRun RunModel(const ModelLocation& location, const CoreConfig& config, const std::vector<uint8_t>& image,
                  const std::vector<Ray>& rays, const RunOptions& run, const std::string& trace_path,
                  Query query = Query::kClosest);

// The fast cycle model (sim/fast_model.h) on the same image and rays, with
// `config`'s parameters and `run`'s memory: the same report as a model run
// ("cycle_model": "fast", and a note of what it does not model); its hits are
// the reference's.
ModelRun RunFast(const CoreConfig& config, const std::vector<uint8_t>& image, const std::vector<Ray>& rays,
                 const RunOptions& run, Query query = Query::kClosest);

// The memory image the RTL core of `format` reads: the fp32 image packed in
// the format's width (docs/memory-image.md, "Packed formats"); fp32's is the
// fp32 image itself.
std::vector<uint8_t> CoreImage(const std::vector<uint8_t>& fp32_image, fp::Format format);

// The whole way for a caller without options: what the image requires, the
// model of `format` that covers it (built when missing), and its run on the
// image of its format (CoreImage of the fp32 `image`). `trav`: a core whose
// traversal datapath is that wider format (rt_core TravE, TravM).
// `image_format`: a core reading that narrower image (rt_core ImgE, ImgM).
// `core`: the core parameters set by the caller (`kdrt sim`'s --threads,
// --cache-mshrs, ...); the others are the defaults or what the scene needs.
ModelRun Simulate(const std::vector<uint8_t>& image, const std::vector<Ray>& rays, fp::Format format,
                  RunOptions run, Query query = Query::kClosest, std::optional<fp::Format> trav = std::nullopt,
                  std::optional<fp::Format> image_format = std::nullopt, const ConfigOverrides& core = {});

}  // namespace kdrt::sim
