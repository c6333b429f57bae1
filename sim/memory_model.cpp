#include "sim/memory_model.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace kdrt::sim {
namespace {

std::string Hex(uint64_t v) {
  std::ostringstream s;
  s << "0x" << std::hex << v;
  return s.str();
}

}  // namespace

MemoryModel::MemoryModel(const MemoryConfig& config) : config_(config) {
  if (config.size_bytes == 0) throw std::invalid_argument("memory model: size must be positive");
  if (config.latency == 0) throw std::invalid_argument("memory model: latency must be at least 1 cycle");
  if (!(config.bytes_per_cycle > 0) || !std::isfinite(config.bytes_per_cycle)) {
    throw std::invalid_argument("memory model: bandwidth must be a positive number of bytes per cycle");
  }
  // The bucket holds one beat plus one cycle's refill: the remainder left
  // after a beat is never lost (so a fractional rate averages exactly), and an
  // idle memory cannot save up more than about one extra beat.
  max_tokens_ = kBeatBytes + config.bytes_per_cycle;
  tokens_ = kBeatBytes;
}

void MemoryModel::CheckFits(uint64_t bytes) const {
  if (bytes > config_.size_bytes) {
    throw MemoryError("memory image of " + std::to_string(bytes) + " bytes does not fit the modelled memory of " +
                      std::to_string(config_.size_bytes) + " bytes");
  }
}

void MemoryModel::LoadImage(const std::vector<uint8_t>& bytes) {
  CheckFits(bytes.size());
  image_ = bytes;
}

void MemoryModel::ThrowBadRequest(uint64_t addr, uint64_t cycle) const {
  if (addr % kBeatBytes != 0) {
    throw MemoryError("memory request at " + Hex(addr) + " (cycle " + std::to_string(cycle) +
                      ") is not 16-byte aligned");
  }
  throw MemoryError("memory request at " + Hex(addr) + " (cycle " + std::to_string(cycle) +
                    ") lies outside the modelled memory of " + std::to_string(config_.size_bytes) + " bytes");
}

}  // namespace kdrt::sim
