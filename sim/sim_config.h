// What a simulated core is built with, and what a scene needs of it.
//
// Verilator fixes every rt_core parameter at build time, so each CoreConfig
// is its own executable. `kdrt sim` derives the scene's needs from its memory
// image, uses the prebuilt model of the format when that covers them, and
// otherwise builds (once) a model sized for the scene.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "fp/format.h"
#include "trace/memory_image.h"

namespace kdrt::sim {

struct CoreConfig {
  int e = 8, m = 23;
  int threads = 16;
  int stack_depth = 32;
  int node_idx_width = 24;
  int tri_idx_width = 24;
  int addr_width = 28;
  int node_cache_lines = 64;
  int list_cache_lines = 64;
  int tri_cache_lines = 64;

  // A file-name-safe identifier, e.g. e8m23-t16-s32-n24-i24-a28-c64.64.64.
  std::string Key() const;
  nlohmann::json Json() const;
  bool operator==(const CoreConfig& o) const { return Key() == o.Key(); }
};

// The configuration of the prebuilt model of a format (built by `make build`).
CoreConfig DefaultConfig(fp::Format format);
// Whether `format` has a prebuilt model (the four presets).
bool HasPrebuiltModel(fp::Format format);

// The smallest parameters that run a scene without a stack overflow and
// without truncating an index or an address.
struct SceneRequirements {
  int stack_depth = 1;     // header.max_depth (a push happens at most once per level), >= 1
  int node_idx_bits = 1;   // to hold node_count - 1
  int tri_idx_bits = 1;    // to hold triangle ids and list entry indices
  int addr_bits = 1;       // to address every byte of the image
  uint64_t image_bytes = 0;
  uint64_t node_bytes = 0;  // the cache footprint of each section
  uint64_t list_bytes = 0;
  uint64_t tri_bytes = 0;
  nlohmann::json Json() const;
};
SceneRequirements DeriveRequirements(const ImageView& image);

// Number of bits to represent every value in 0..max_value (at least 1).
int BitsFor(uint64_t max_value);

// Overrides from the command line; 0 means "not given".
struct ConfigOverrides {
  int threads = 0;
  int stack_depth = 0;
  int node_idx_width = 0;
  int tri_idx_width = 0;
  int addr_width = 0;
  int node_cache_lines = 0;
  int list_cache_lines = 0;
  int tri_cache_lines = 0;
  uint64_t mem_size = 0;  // bytes of modelled memory; 0: 2^addr_width
  bool allow_overflow = false;  // accept a stack smaller than the tree needs
};

struct ConfigChoice {
  CoreConfig config;
  bool prebuilt = false;  // the format's default model
  uint64_t mem_size = 0;  // resolved modelled memory in bytes
};

// The prebuilt model when it covers the scene and no override asks for
// something else; otherwise the scene's requirements with the overrides on
// top. Throws InputError, naming the scene's requirement, when an override is
// too small for the scene or out of range.
ConfigChoice ChooseConfig(fp::Format format, const SceneRequirements& req, const ConfigOverrides& ov);

// Throws InputError unless `config` can run a scene with `req` (the model's
// own check, so a model started by hand refuses too).
void CheckConfigCovers(const CoreConfig& config, const SceneRequirements& req, uint64_t mem_size,
                       bool allow_overflow);

}  // namespace kdrt::sim
