// The core's memory: a cycle-based model of a read-only memory with a fixed
// latency and a bandwidth limit, holding the kdrt memory image at address 0.
//
// Plain C++ on purpose (no Verilator or SystemC types): the Verilator harness
// calls it once per clock cycle, and a SystemC memory module can wrap the
// very same object.
//
// Timing. A request accepted in cycle c is answered no earlier than cycle
// c + latency. Responses leave in request order, at most one 16-byte beat per
// cycle (the width of the response port), and each one spends 16 bytes from a
// token bucket that refills by `bytes_per_cycle` every cycle (fractions are
// kept), so on average no more than bytes_per_cycle bytes leave per cycle.
// Requests are always accepted: any number may be outstanding.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/ring.h"

namespace kdrt::sim {

inline constexpr uint32_t kBeatBytes = 16;

// A request the hardware should never make (outside the memory, misaligned):
// a harness error, not bad user input.
class MemoryError : public std::runtime_error {
 public:
  explicit MemoryError(const std::string& what) : std::runtime_error(what) {}
};

struct MemoryConfig {
  uint64_t size_bytes = uint64_t{1} << 28;  // the modelled memory
  uint32_t latency = 20;                    // cycles from request to response
  double bytes_per_cycle = 16.0;            // token-bucket refill rate
};

// The bandwidth a run gets: the memory answers at most one beat a cycle (one
// port, behind the core or the L2), so a refill rate above kBeatBytes runs
// as kBeatBytes.
inline double PortBytesPerCycle(const MemoryConfig& c) {
  return c.bytes_per_cycle < kBeatBytes ? c.bytes_per_cycle : double{kBeatBytes};
}

struct MemoryResponse {
  uint16_t tag = 0;
  uint64_t addr = 0;
  uint8_t data[kBeatBytes] = {};
};

// What the core harness needs of a memory: the model below, or a SystemC
// module wrapping it (sim/sc_top.cpp).
class MemoryPort {
 public:
  virtual ~MemoryPort() = default;
  virtual void Request(uint64_t addr, uint16_t tag, uint64_t cycle) = 0;
  virtual bool Respond(uint64_t cycle, MemoryResponse* out) = 0;
  virtual size_t outstanding() const = 0;
};

class MemoryModel : public MemoryPort {
 public:
  // Throws std::invalid_argument on a zero size, a latency of 0 or a
  // bandwidth that is not positive and finite.
  explicit MemoryModel(const MemoryConfig& config);

  // Places `bytes` at address 0; the rest of the memory reads as zero.
  // Throws MemoryError if the image does not fit.
  void LoadImage(const std::vector<uint8_t>& bytes);
  // Throws LoadImage's MemoryError if an image of `bytes` would not fit.
  void CheckFits(uint64_t bytes) const;

  // A read of the 16 bytes at `addr` (16-byte aligned), accepted in cycle
  // `cycle`. Throws MemoryError outside the memory or when misaligned.
  void Request(uint64_t addr, uint16_t tag, uint64_t cycle) override {
    CheckRequest(addr, cycle);
    queue_.push(Pending{cycle + config_.latency, addr, tag});
    ++requests_;
    if (queue_.size() > max_outstanding_) max_outstanding_ = queue_.size();
  }
  // Request()'s check alone: throws MemoryError for a read outside the memory
  // or not 16-byte aligned (a cache in front of the memory checks with it).
  void CheckRequest(uint64_t addr, uint64_t cycle) const {
    if (addr % kBeatBytes != 0 || addr >= config_.size_bytes || config_.size_bytes - addr < kBeatBytes) {
      ThrowBadRequest(addr, cycle);
    }
  }

  // Advances to cycle `cycle` (call once per cycle, increasing) and returns
  // true with the beat to drive on the response port this cycle, if any.
  // (Inline: the fast model asks every cycle a beat may be due.)
  bool Respond(uint64_t cycle, MemoryResponse* out) override {
    const uint64_t elapsed = started_ ? cycle - last_cycle_ : 1;
    started_ = true;
    last_cycle_ = cycle;
    tokens_ = std::min(max_tokens_, tokens_ + config_.bytes_per_cycle * static_cast<double>(elapsed));
    if (queue_.empty() || queue_.front().ready_cycle > cycle || tokens_ < kBeatBytes) return false;
    const Pending p = queue_.front();
    queue_.pop();
    tokens_ -= kBeatBytes;
    bytes_read_ += kBeatBytes;
    out->tag = p.tag;
    out->addr = p.addr;
    CopyBeat(p.addr, out->data);
    return true;
  }

  const MemoryConfig& config() const { return config_; }
  uint64_t bytes_read() const { return bytes_read_; }
  uint64_t requests() const { return requests_; }
  size_t outstanding() const override { return queue_.size(); }
  uint64_t max_outstanding() const { return max_outstanding_; }
  // The first cycle in which Respond() can return a beat (UINT64_MAX when
  // nothing is outstanding): the fast model skips the cycles before it.
  uint64_t next_ready_cycle() const { return queue_.empty() ? UINT64_MAX : queue_.front().ready_cycle; }

 private:
  struct Pending {
    uint64_t ready_cycle;
    uint64_t addr;
    uint16_t tag;
  };
  [[noreturn]] void ThrowBadRequest(uint64_t addr, uint64_t cycle) const;
  // The image's bytes at addr (zeros beyond it) into a beat.
  void CopyBeat(uint64_t addr, uint8_t* data) const {
    std::memset(data, 0, kBeatBytes);
    if (addr < image_.size()) {
      std::memcpy(data, image_.data() + addr, std::min<uint64_t>(kBeatBytes, image_.size() - addr));
    }
  }

  MemoryConfig config_;
  std::vector<uint8_t> image_;
  Ring<Pending> queue_{64, /*bounded=*/false};  // request order; ready cycles never decrease
  double tokens_ = 0;
  double max_tokens_ = 0;
  uint64_t last_cycle_ = 0;
  bool started_ = false;
  uint64_t bytes_read_ = 0;
  uint64_t requests_ = 0;
  uint64_t max_outstanding_ = 0;
};

}  // namespace kdrt::sim
