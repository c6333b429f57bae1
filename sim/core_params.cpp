#include "sim/core_params.h"

#include <algorithm>

#include "common/error.h"
#include "trace/tracer.h"

namespace kdrt::sim {
namespace {

bool IsPowerOfTwo(int v) { return v > 0 && (v & (v - 1)) == 0; }

// The option's first long name, for messages ("--threads,--core-threads" -> "--threads"),
// or what the parameter is when no option sets it alone (E, M, TravE, TravM,
// ImgE, ImgM).
std::string FlagName(const CoreParam& p) {
  const std::string flag = p.flag;
  return flag.empty() ? std::string(p.what) : flag.substr(0, flag.find(','));
}

void CheckOverride(const CoreParam& p, int value) {
  const std::string flag = FlagName(p) + " " + std::to_string(value);
  if (value < p.min || value > p.max) {
    throw InputError(flag + ": must lie in " + std::to_string(p.min) + ".." + std::to_string(p.max));
  }
  if (p.power_of_two && !IsPowerOfTwo(value)) {
    throw InputError(flag + ": must be a power of two (a cache's sets and ways are indexed by key bits)");
  }
}

// The scene's need for a parameter under its rule (0: no need).
int Required(SceneRule rule, const SceneRequirements& req) {
  switch (rule) {
    case SceneRule::kTreeDepth: return req.stack_depth;
    case SceneRule::kNodeIndexBits: return req.node_idx_bits;
    case SceneRule::kTriIndexBits: return req.tri_idx_bits;
    case SceneRule::kAddressBits: return req.addr_bits;
    default: return 0;
  }
}

// Why the scene needs that much, for the error message.
std::string Reason(const CoreParam& p, const SceneRequirements& req) {
  const std::string need = std::to_string(Required(p.rule, req));
  switch (p.rule) {
    case SceneRule::kTreeDepth:
      return "the scene's kd-tree is " + need + " levels deep and needs " + FlagName(p) + " >= " + need +
             " (--allow-overflow runs it anyway)";
    case SceneRule::kNodeIndexBits: return "the scene's kd-tree needs " + need + " bits";
    case SceneRule::kTriIndexBits: return "the scene needs " + need + " bits";
    case SceneRule::kAddressBits:
      return "the scene's memory image of " + std::to_string(req.image_bytes) + " bytes needs " + need + " bits";
    default: return "";
  }
}

void CheckCacheWays(const CoreConfig& c) {
  for (const Param lines : {kNodeCacheLines, kListCacheLines, kTriCacheLines}) {
    if (c[kCacheWays] > c[lines]) {
      throw InputError("--cache-ways " + std::to_string(c[kCacheWays]) + ": more ways than the " +
                       std::to_string(c[lines]) + " " + kCoreParams[lines].what + " (a set cannot be larger)");
    }
  }
}

}  // namespace

int BitsFor(uint64_t max_value) {
  int bits = 1;
  while (bits < 64 && (max_value >> bits) != 0) ++bits;
  return bits;
}

std::string CoreConfig::Key() const {
  std::string key;
  for (int i = 0; i < kParamCount; ++i) key += kCoreParams[i].key + std::to_string(value[i]);
  return key;
}

nlohmann::json CoreConfig::Json() const {
  nlohmann::json j = {{"key", Key()}};
  for (int i = 0; i < kParamCount; ++i) j[kCoreParams[i].sv_name] = value[i];
  return j;
}

std::vector<std::string> CoreConfig::VerilatorDefines() const {
  std::vector<std::string> g;
  for (int i = 0; i < kParamCount; ++i) g.push_back("-G" + std::string(kCoreParams[i].sv_name) + "=" + std::to_string(value[i]));
  return g;
}

CoreConfig DefaultConfig(fp::Format format) {
  CoreConfig c;
  for (int i = 0; i < kParamCount; ++i) c.value[i] = kCoreParams[i].default_value;
  c[kE] = c[kTravE] = c[kImgE] = format.e;
  c[kM] = c[kTravM] = c[kImgM] = format.m;
  return c;
}

bool HasPrebuiltModel(fp::Format format) {
  const std::vector<fp::Format> presets = fp::Presets();
  return std::find(presets.begin(), presets.end(), format) != presets.end();
}

nlohmann::json SceneRequirements::Json() const {
  return {{"stack_depth", stack_depth},     {"node_idx_bits", node_idx_bits}, {"tri_idx_bits", tri_idx_bits},
          {"addr_bits", addr_bits},         {"image_bytes", image_bytes},     {"node_bytes", node_bytes},
          {"list_bytes", list_bytes},       {"tri_bytes", tri_bytes}};
}

SceneRequirements DeriveRequirements(const ImageView& image) {
  const img::Header& h = image.header();
  SceneRequirements r;
  r.stack_depth = std::max<int>(1, static_cast<int>(h.max_depth));
  r.node_idx_bits = BitsFor(h.node_count > 0 ? image.layout().IndexOfPosition(h.node_count - 1) : 0);
  const uint64_t max_tri_index = std::max<uint64_t>(h.tri_count, h.list_count);
  r.tri_idx_bits = BitsFor(max_tri_index > 0 ? max_tri_index - 1 : 0);
  r.image_bytes = image.size();
  r.addr_bits = BitsFor(r.image_bytes > 0 ? r.image_bytes - 1 : 0);
  r.node_bytes = image.layout().NodeSectionBytes(h.node_count);
  r.list_bytes = uint64_t{h.list_count} * img::kListEntryBytes;
  r.tri_bytes = image.layout().TriangleSectionBytes(h.tri_count);
  return r;
}

void CheckRtlTravFormat(const fp::Format& trav) {
  if (trav.e > kCoreParams[kTravE].max || trav.m > kCoreParams[kTravM].max) {
    throw InputError("--trav-format " + trav.Name() + ": the RTL traverses in at most e" +
                     std::to_string(kCoreParams[kTravE].max) + "m" + std::to_string(kCoreParams[kTravM].max) +
                     " (fp32); kdrt render --trav-format takes wider ones");
  }
}

void OverrideTravFormat(const fp::Format& format, const fp::Format& trav, ConfigOverrides* ov) {
  CheckRtlTravFormat(trav);
  if (trav == format) return;
  ov->value[kTravE] = trav.e;
  ov->value[kTravM] = trav.m;
}

void OverrideImageFormat(const fp::Format& format, const fp::Format& image, ConfigOverrides* ov) {
  CheckImageFormat(format, image);
  if (image == format) return;
  ov->value[kImgE] = image.e;
  ov->value[kImgM] = image.m;
}

void CheckConfigCovers(const CoreConfig& c, const SceneRequirements& req, uint64_t mem_size, bool allow_overflow) {
  CheckImageFormat(c.Format(), c.ImageFormat());
  for (int i = 0; i < kParamCount; ++i) {
    const CoreParam& p = kCoreParams[i];
    if (c.value[i] >= Required(p.rule, req)) continue;
    if (p.rule == SceneRule::kTreeDepth && allow_overflow) continue;
    throw InputError(std::string(p.what) + " " + std::to_string(c.value[i]) + " is too small: " + Reason(p, req));
  }
  CheckCacheWays(c);
  if (mem_size > (uint64_t{1} << c[kAddrWidth])) {
    throw InputError("--mem-size " + std::to_string(mem_size) + " exceeds what " + std::to_string(c[kAddrWidth]) +
                     " address bits reach");
  }
  if (mem_size < req.image_bytes) {
    throw InputError("the modelled memory of " + std::to_string(mem_size) + " bytes is too small: the scene's " +
                     "memory image needs " + std::to_string(req.image_bytes) + " bytes");
  }
}

CoreConfig ConfigWithoutScene(fp::Format format, const ConfigOverrides& ov) {
  CoreConfig c = DefaultConfig(format);
  for (int i = 0; i < kParamCount; ++i) {
    if (!ov.Has(i)) continue;
    CheckOverride(kCoreParams[i], ov.value[i]);
    c.value[i] = ov.value[i];
  }
  CheckImageFormat(c.Format(), c.ImageFormat());
  CheckCacheWays(c);
  return c;
}

ConfigChoice ChooseConfig(fp::Format format, const SceneRequirements& req, const ConfigOverrides& ov,
                          uint64_t mem_size, bool allow_overflow) {
  for (int i = 0; i < kParamCount; ++i) {
    if (ov.Has(i)) CheckOverride(kCoreParams[i], ov.value[i]);
  }
  auto apply = [&](CoreConfig c) {
    for (int i = 0; i < kParamCount; ++i) {
      if (ov.Has(i)) c.value[i] = ov.value[i];
    }
    return c;
  };
  auto mem_size_of = [&](const CoreConfig& c) { return mem_size ? mem_size : uint64_t{1} << c[kAddrWidth]; };

  ConfigChoice choice;
  const CoreConfig def = DefaultConfig(format);
  bool default_fits = HasPrebuiltModel(format) && apply(def) == def;
  if (default_fits) {
    try {
      CheckConfigCovers(def, req, mem_size_of(def), allow_overflow);
    } catch (const InputError&) {
      default_fits = false;
    }
  }
  if (default_fits) {
    choice.config = def;
    choice.prebuilt = true;
  } else {
    CoreConfig derived = def;
    for (int i = 0; i < kParamCount; ++i) {
      const int need = Required(kCoreParams[i].rule, req);
      if (need) derived.value[i] = need;
    }
    // The memory the user asks for must be addressable too.
    derived[kAddrWidth] = std::max({derived[kAddrWidth], mem_size ? BitsFor(mem_size - 1) : 0, 12});
    choice.config = apply(derived);
  }
  choice.mem_size = mem_size_of(choice.config);
  CheckConfigCovers(choice.config, req, choice.mem_size, allow_overflow);
  return choice;
}

}  // namespace kdrt::sim
