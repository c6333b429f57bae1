// A second-level cache shared by several cores in front of the memory model
// (kdrt sim --cores N; docs/simulator.md, "Several cores"). Plain C++ like
// the memory model: each core sees a MemoryPort (port(k)), the SystemC top
// wraps them.
//
// Timing. A core's request in cycle c that hits a line is answered in cycle
// c + latency. A miss asks the memory for every beat of its line (one memory
// request per 16-byte beat, inside the memory) unless the line is already
// being fetched, in which case it waits for that fill (misses to a line in
// flight merge, any number of them). When the last beat of a line arrives in
// cycle c, the line is installed (the set's least recently used way is
// replaced) and its waiting requests are answered from cycle c + 1. Each
// core's port returns at most one beat per cycle, oldest ready first.
// Requests are always accepted.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <queue>
#include <vector>

#include "sim/memory_model.h"

namespace kdrt::sim {

struct L2Config {
  uint32_t size_bytes = 256 * 1024;
  uint32_t ways = 8;
  uint32_t line_bytes = 64;  // a multiple of 16
  uint32_t latency = 10;     // cycles from request to response on a hit
};

struct L2Stats {
  uint64_t requests = 0;  // beats asked for by the cores
  uint64_t hits = 0;      // answered from a present line
  uint64_t merged = 0;    // misses that joined a line being fetched
  uint64_t line_fills = 0;
};

class SharedL2 {
 public:
  // Throws std::invalid_argument on a geometry that is not a whole number of
  // sets of whole lines, or a latency of 0.
  SharedL2(const L2Config& config, MemoryModel& memory, const std::vector<uint8_t>& image, int cores);
  ~SharedL2();

  MemoryPort& port(int core);
  const L2Stats& stats() const { return stats_; }
  const L2Config& config() const { return config_; }

  // What port(core) does, without the virtual call (the fast model's cores
  // call these directly).
  void Request(int core, uint64_t addr, uint16_t tag, uint64_t cycle);
  bool Respond(int core, uint64_t cycle, MemoryResponse* out);
  // Takes the memory's beat of `cycle` (once per cycle; later calls in the
  // same cycle do nothing) and installs lines. Respond() calls it; a caller
  // that skips cycles in which nothing can arrive calls it itself.
  void Advance(uint64_t cycle);
  // The first cycle in which Respond(core) can return a beat without a new
  // memory beat arriving first (UINT64_MAX: none queued for the core).
  uint64_t next_ready_cycle(int core) const { return out_[core].empty() ? UINT64_MAX : out_[core].top().ready; }

 private:
  class Port;
  struct Response {
    uint64_t ready;
    uint64_t seq;  // request order among equal ready cycles
    uint64_t addr;
    uint16_t tag;
    bool operator>(const Response& o) const { return ready != o.ready ? ready > o.ready : seq > o.seq; }
  };
  struct Waiter {
    int core;
    uint64_t addr;
    uint16_t tag;
  };
  struct Fill {
    uint32_t beats_left;
    std::vector<Waiter> waiters;
  };

  bool Lookup(uint64_t line);  // and makes it most recently used
  void Install(uint64_t line);
  void Answer(int core, uint64_t addr, uint16_t tag, uint64_t ready);

  L2Config config_;
  MemoryModel& memory_;
  const std::vector<uint8_t>& image_;
  uint32_t sets_ = 0;
  std::vector<uint64_t> tags_;      // sets_ x ways: line number + 1, 0 = empty
  std::vector<uint64_t> last_use_;  // sets_ x ways: LRU stamps
  uint64_t use_clock_ = 0;
  std::map<uint64_t, Fill> fills_;          // by line number
  std::vector<uint64_t> tag_line_;          // memory tag -> line number
  std::vector<uint16_t> free_tags_;
  std::vector<std::priority_queue<Response, std::vector<Response>, std::greater<Response>>> out_;
  std::vector<std::unique_ptr<Port>> ports_;
  uint64_t seq_ = 0;
  uint64_t advanced_ = 0;
  bool started_ = false;
  L2Stats stats_;
};

}  // namespace kdrt::sim
