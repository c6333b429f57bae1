#include "sim/sim_config.h"

#include <algorithm>

#include "common/error.h"

namespace kdrt::sim {
namespace {

bool IsPowerOfTwo(int v) { return v > 0 && (v & (v - 1)) == 0; }

void CheckRange(const char* option, int value, int lo, int hi) {
  if (value < lo || value > hi) {
    throw InputError(std::string(option) + " " + std::to_string(value) + ": must lie in " + std::to_string(lo) +
                     ".." + std::to_string(hi));
  }
}

void CheckCacheLines(const char* option, int value) {
  CheckRange(option, value, 2, 65536);
  if (!IsPowerOfTwo(value)) {
    throw InputError(std::string(option) + " " + std::to_string(value) +
                     ": a direct-mapped cache needs a power of two lines");
  }
}

}  // namespace

int BitsFor(uint64_t max_value) {
  int bits = 1;
  while (bits < 64 && (max_value >> bits) != 0) ++bits;
  return bits;
}

std::string CoreConfig::Key() const {
  return "e" + std::to_string(e) + "m" + std::to_string(m) + "-t" + std::to_string(threads) + "-s" +
         std::to_string(stack_depth) + "-n" + std::to_string(node_idx_width) + "-i" + std::to_string(tri_idx_width) +
         "-a" + std::to_string(addr_width) + "-c" + std::to_string(node_cache_lines) + "." +
         std::to_string(list_cache_lines) + "." + std::to_string(tri_cache_lines);
}

nlohmann::json CoreConfig::Json() const {
  return {{"key", Key()},
          {"E", e},
          {"M", m},
          {"Threads", threads},
          {"StackDepth", stack_depth},
          {"NodeIdxWidth", node_idx_width},
          {"TriIdxWidth", tri_idx_width},
          {"AddrWidth", addr_width},
          {"NodeCacheLines", node_cache_lines},
          {"ListCacheLines", list_cache_lines},
          {"TriCacheLines", tri_cache_lines}};
}

CoreConfig DefaultConfig(fp::Format format) {
  CoreConfig c;
  c.e = format.e;
  c.m = format.m;
  return c;
}

bool HasPrebuiltModel(fp::Format format) {
  for (const fp::Format& p : fp::Presets()) {
    if (p == format) return true;
  }
  return false;
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
  r.node_idx_bits = BitsFor(h.node_count > 0 ? h.node_count - 1 : 0);
  const uint64_t max_tri_index = std::max<uint64_t>(h.tri_count, h.list_count);
  r.tri_idx_bits = BitsFor(max_tri_index > 0 ? max_tri_index - 1 : 0);
  r.image_bytes = image.size();
  r.addr_bits = BitsFor(r.image_bytes > 0 ? r.image_bytes - 1 : 0);
  r.node_bytes = uint64_t{h.node_count} * img::kNodeBytes;
  r.list_bytes = uint64_t{h.list_count} * img::kListEntryBytes;
  r.tri_bytes = uint64_t{h.tri_count} * img::kTriangleBytes;
  return r;
}

void CheckConfigCovers(const CoreConfig& c, const SceneRequirements& req, uint64_t mem_size, bool allow_overflow) {
  if (c.stack_depth < req.stack_depth && !allow_overflow) {
    throw InputError("stack depth " + std::to_string(c.stack_depth) + " is too small: the scene's kd-tree is " +
                     std::to_string(req.stack_depth) + " levels deep and needs --stack-depth >= " +
                     std::to_string(req.stack_depth) + " (--allow-overflow runs it anyway)");
  }
  if (c.node_idx_width < req.node_idx_bits) {
    throw InputError("node index width " + std::to_string(c.node_idx_width) + " is too small: the scene's " +
                     "kd-tree needs " + std::to_string(req.node_idx_bits) + " bits");
  }
  if (c.tri_idx_width < req.tri_idx_bits) {
    throw InputError("triangle index width " + std::to_string(c.tri_idx_width) + " is too small: the scene " +
                     "needs " + std::to_string(req.tri_idx_bits) + " bits");
  }
  if (c.addr_width < req.addr_bits) {
    throw InputError("address width " + std::to_string(c.addr_width) + " is too small: the scene's memory image of " +
                     std::to_string(req.image_bytes) + " bytes needs " + std::to_string(req.addr_bits) + " bits");
  }
  if (mem_size > (uint64_t{1} << c.addr_width)) {
    throw InputError("--mem-size " + std::to_string(mem_size) + " exceeds what " + std::to_string(c.addr_width) +
                     " address bits reach");
  }
  if (mem_size < req.image_bytes) {
    throw InputError("the modelled memory of " + std::to_string(mem_size) + " bytes is too small: the scene's " +
                     "memory image needs " + std::to_string(req.image_bytes) + " bytes");
  }
}

ConfigChoice ChooseConfig(fp::Format format, const SceneRequirements& req, const ConfigOverrides& ov) {
  if (ov.threads) CheckRange("--core-threads", ov.threads, 1, 256);
  if (ov.stack_depth) CheckRange("--stack-depth", ov.stack_depth, 1, 255);
  if (ov.node_idx_width) CheckRange("--node-idx-width", ov.node_idx_width, 1, 30);
  if (ov.tri_idx_width) CheckRange("--tri-idx-width", ov.tri_idx_width, 1, 30);
  if (ov.addr_width) CheckRange("--addr-width", ov.addr_width, 8, 32);
  if (ov.node_cache_lines) CheckCacheLines("--node-cache-lines", ov.node_cache_lines);
  if (ov.list_cache_lines) CheckCacheLines("--list-cache-lines", ov.list_cache_lines);
  if (ov.tri_cache_lines) CheckCacheLines("--tri-cache-lines", ov.tri_cache_lines);

  auto apply = [&](CoreConfig c) {
    if (ov.threads) c.threads = ov.threads;
    if (ov.stack_depth) c.stack_depth = ov.stack_depth;
    if (ov.node_idx_width) c.node_idx_width = ov.node_idx_width;
    if (ov.tri_idx_width) c.tri_idx_width = ov.tri_idx_width;
    if (ov.addr_width) c.addr_width = ov.addr_width;
    if (ov.node_cache_lines) c.node_cache_lines = ov.node_cache_lines;
    if (ov.list_cache_lines) c.list_cache_lines = ov.list_cache_lines;
    if (ov.tri_cache_lines) c.tri_cache_lines = ov.tri_cache_lines;
    return c;
  };
  auto mem_size_of = [&](const CoreConfig& c) {
    return ov.mem_size ? ov.mem_size : uint64_t{1} << c.addr_width;
  };

  ConfigChoice choice;
  const CoreConfig def = DefaultConfig(format);
  const CoreConfig def_with_overrides = apply(def);
  bool default_fits = HasPrebuiltModel(format) && def_with_overrides == def;
  if (default_fits) {
    try {
      CheckConfigCovers(def, req, mem_size_of(def), ov.allow_overflow);
    } catch (const InputError&) {
      default_fits = false;
    }
  }
  if (default_fits) {
    choice.config = def;
    choice.prebuilt = true;
  } else {
    CoreConfig derived = def;
    derived.stack_depth = req.stack_depth;
    derived.node_idx_width = req.node_idx_bits;
    derived.tri_idx_width = req.tri_idx_bits;
    // The memory the user asks for must be addressable too.
    derived.addr_width = std::max(req.addr_bits, ov.mem_size ? BitsFor(ov.mem_size - 1) : 0);
    derived.addr_width = std::max(derived.addr_width, 12);
    choice.config = apply(derived);
  }
  choice.mem_size = mem_size_of(choice.config);
  CheckConfigCovers(choice.config, req, choice.mem_size, ov.allow_overflow);
  return choice;
}

}  // namespace kdrt::sim
