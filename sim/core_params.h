// What a simulated core is built with, and what a scene needs of it.
//
// Verilator fixes every rt_core parameter at build time, so each CoreConfig
// is its own executable. `kdrt sim` derives the scene's needs from its memory
// image, uses the prebuilt model of the format when that covers them, and
// otherwise builds (once) a model sized for the scene. Every parameter is a
// row of sim/core_params.def; nothing here names one parameter by hand except
// the scene rules.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fp/format.h"
#include "trace/memory_image.h"

namespace kdrt::sim {

// How `kdrt sim` sizes a parameter when it builds a model for a scene.
enum class SceneRule {
  kFormatE,        // the format's exponent bits
  kFormatM,        // the format's mantissa bits
  kFixed,          // the default, whatever the scene
  kTreeDepth,      // the kd-tree's depth (a push happens at most once per level)
  kNodeIndexBits,  // bits to hold node_count - 1
  kTriIndexBits,   // bits to hold triangle ids and list entry indices
  kAddressBits,    // bits to address every byte of the image (at least 12)
};

struct CoreParam {
  const char* sv_name;
  const char* key;
  const char* flag;
  int default_value;
  SceneRule rule;
  int min, max;
  bool power_of_two;
  const char* what;
};

enum Param {
#define KDRT_CORE_PARAM(name, ...) k##name,
#include "sim/core_params.def"
#undef KDRT_CORE_PARAM
  kParamCount
};

inline constexpr CoreParam kCoreParams[kParamCount] = {
#define KDRT_CORE_PARAM(name, key, flag, def, rule, lo, hi, pow2, what) \
  {#name, key, flag, def, SceneRule::rule, lo, hi, pow2, what},
#include "sim/core_params.def"
#undef KDRT_CORE_PARAM
};

struct CoreConfig {
  std::array<int, kParamCount> value{};

  int operator[](Param p) const { return value[p]; }
  int& operator[](Param p) { return value[p]; }
  fp::Format Format() const { return fp::Format{value[kE], value[kM]}; }
  // The traversal's format: Format() or a wider one (rt_core TravE, TravM).
  fp::Format TravFormat() const { return fp::Format{value[kTravE], value[kTravM]}; }
  // The memory image's format: Format() or a narrower one (rt_core ImgE, ImgM).
  fp::Format ImageFormat() const { return fp::Format{value[kImgE], value[kImgM]}; }
  // A file-name-safe identifier, e.g. e8m23v8.23p8.23-t32-s32-n24-i24-a28-c256.64.128-r16-g4-w4-l1-f0.
  std::string Key() const;
  nlohmann::json Json() const;
  // Verilator's -G<Name>=<value> for every parameter.
  std::vector<std::string> VerilatorDefines() const;
  bool operator==(const CoreConfig& o) const { return value == o.value; }
};

// The configuration of the prebuilt model of a format (built by `make build`).
CoreConfig DefaultConfig(fp::Format format);
// Whether `format` has a prebuilt model (the presets).
bool HasPrebuiltModel(fp::Format format);

// The smallest parameters that run a scene without a stack overflow and
// without truncating an index or an address.
struct SceneRequirements {
  int stack_depth = 1;
  int node_idx_bits = 1;
  int tri_idx_bits = 1;
  int addr_bits = 1;
  uint64_t image_bytes = 0;
  uint64_t node_bytes = 0;  // the cache footprint of each section
  uint64_t list_bytes = 0;
  uint64_t tri_bytes = 0;
  nlohmann::json Json() const;
};
SceneRequirements DeriveRequirements(const ImageView& image);

// Number of bits to represent every value in 0..max_value (at least 1).
int BitsFor(uint64_t max_value);

// Parameters the user asked for on the command line.
struct ConfigOverrides {
  // Not given on the command line (a value no parameter can take: ListStream
  // may be overridden with 0).
  static constexpr int kUnset = std::numeric_limits<int>::min();
  ConfigOverrides() { value.fill(kUnset); }
  bool Has(int i) const { return value[i] != kUnset; }
  std::array<int, kParamCount> value;
};

struct ConfigChoice {
  CoreConfig config;
  bool prebuilt = false;  // the format's default model
  uint64_t mem_size = 0;  // resolved modelled memory in bytes
};

// The prebuilt model when it covers the scene and no override asks for
// something else; otherwise the scene's requirements with the overrides on
// top. `mem_size` is the modelled memory the user asked for (0: 2^AddrWidth);
// `allow_overflow` accepts a stack smaller than the tree needs. Throws
// InputError, naming the scene's requirement, when an override is too small
// for the scene or out of range.
ConfigChoice ChooseConfig(fp::Format format, const SceneRequirements& req, const ConfigOverrides& ov,
                          uint64_t mem_size, bool allow_overflow);

// Without a scene (kdrt synth with no SCENE): rt_core's defaults of the
// format with the overrides on top, checked as ChooseConfig checks them. A
// scene may need other widths (ChooseConfig sizes them for it), so this is
// the configuration `kdrt sim` runs only when the scene fits these values and
// either no override is given or the overrides name every scene-sized one.
CoreConfig ConfigWithoutScene(fp::Format format, const ConfigOverrides& ov);

// Throws InputError unless the RTL can traverse in `trav` (rt_core TravE,
// TravM: at most fp32; kdrt render --trav-format takes wider ones).
void CheckRtlTravFormat(const fp::Format& trav);
// Sets `ov`'s TravE, TravM for a core of `format` whose traversal is `trav`
// (nothing when they are the same: the format's own model), after
// CheckRtlTravFormat. The caller checks that trav holds format (CheckTravFormat).
void OverrideTravFormat(const fp::Format& format, const fp::Format& trav, ConfigOverrides* ov);
// Sets `ov`'s ImgE, ImgM for a core of `format` reading an image of `image`
// (nothing when they are the same), after CheckImageFormat (trace/tracer.h).
void OverrideImageFormat(const fp::Format& format, const fp::Format& image, ConfigOverrides* ov);

// Throws InputError unless `config` can run a scene with `req` (the model's
// own check, so a model started by hand refuses too).
void CheckConfigCovers(const CoreConfig& config, const SceneRequirements& req, uint64_t mem_size,
                       bool allow_overflow);

}  // namespace kdrt::sim
