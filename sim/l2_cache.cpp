#include "sim/l2_cache.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace kdrt::sim {

class SharedL2::Port : public MemoryPort {
 public:
  Port(SharedL2& l2, int core) : l2_(l2), core_(core) {}
  void Request(uint64_t addr, uint16_t tag, uint64_t cycle) override { l2_.Request(core_, addr, tag, cycle); }
  bool Respond(uint64_t cycle, MemoryResponse* out) override { return l2_.Respond(core_, cycle, out); }
  size_t outstanding() const override { return l2_.fills_.size() + l2_.out_[core_].size(); }

 private:
  SharedL2& l2_;
  int core_;
};

SharedL2::SharedL2(const L2Config& config, MemoryModel& memory, const std::vector<uint8_t>& image, int cores)
    : config_(config), memory_(memory), image_(image) {
  if (config.line_bytes == 0 || config.line_bytes % kBeatBytes != 0 || config.ways == 0 ||
      config.size_bytes % (config.line_bytes * config.ways) != 0 || config.size_bytes == 0) {
    throw std::invalid_argument("L2: size must be a whole number of sets of ways x lines of 16-byte beats");
  }
  if (config.latency == 0) throw std::invalid_argument("L2: latency must be at least 1 cycle");
  if (cores < 1) throw std::invalid_argument("L2: at least one core");
  sets_ = config.size_bytes / (config.line_bytes * config.ways);
  tags_.assign(static_cast<size_t>(sets_) * config.ways, 0);
  last_use_.assign(tags_.size(), 0);
  tag_line_.assign(65536, 0);
  for (uint32_t t = 65536; t-- > 0;) free_tags_.push_back(static_cast<uint16_t>(t));
  out_.resize(cores);
  for (int k = 0; k < cores; ++k) ports_.push_back(std::make_unique<Port>(*this, k));
}

SharedL2::~SharedL2() = default;

MemoryPort& SharedL2::port(int core) { return *ports_.at(core); }

bool SharedL2::Lookup(uint64_t line) {
  const size_t base = static_cast<size_t>(line % sets_) * config_.ways;
  for (uint32_t w = 0; w < config_.ways; ++w) {
    if (tags_[base + w] == line + 1) {
      last_use_[base + w] = ++use_clock_;
      return true;
    }
  }
  return false;
}

void SharedL2::Install(uint64_t line) {
  const size_t base = static_cast<size_t>(line % sets_) * config_.ways;
  size_t victim = base;
  for (uint32_t w = 0; w < config_.ways; ++w) {
    if (last_use_[base + w] < last_use_[victim]) victim = base + w;
  }
  tags_[victim] = line + 1;
  last_use_[victim] = ++use_clock_;
}

void SharedL2::Answer(int core, uint64_t addr, uint16_t tag, uint64_t ready) {
  out_[core].push(Response{ready, seq_++, addr, tag});
}

void SharedL2::Request(int core, uint64_t addr, uint16_t tag, uint64_t cycle) {
  try {
    memory_.CheckRequest(addr, cycle);
  } catch (const MemoryError& e) {
    throw MemoryError("core " + std::to_string(core) + " through the L2: " + e.what());
  }
  const uint64_t size = memory_.config().size_bytes;
  ++stats_.requests;
  const uint64_t line = addr / config_.line_bytes;
  if (Lookup(line)) {
    ++stats_.hits;
    Answer(core, addr, tag, cycle + config_.latency);
    return;
  }
  auto it = fills_.find(line);
  if (it != fills_.end()) {
    ++stats_.merged;
    it->second.waiters.push_back(Waiter{core, addr, tag});
    return;
  }
  Fill fill{0, {Waiter{core, addr, tag}}};
  const uint64_t first = line * config_.line_bytes;
  for (uint64_t a = first; a < first + config_.line_bytes && a < size && size - a >= kBeatBytes; a += kBeatBytes) {
    if (free_tags_.empty()) throw MemoryError("L2: more than 65536 memory reads outstanding");
    const uint16_t t = free_tags_.back();
    free_tags_.pop_back();
    tag_line_[t] = line;
    memory_.Request(a, t, cycle);
    ++fill.beats_left;
  }
  fills_.emplace(line, std::move(fill));
}

void SharedL2::Advance(uint64_t cycle) {
  if (started_ && cycle <= advanced_) return;
  started_ = true;
  advanced_ = cycle;
  MemoryResponse resp;
  if (!memory_.Respond(cycle, &resp)) return;
  const uint64_t line = tag_line_[resp.tag];
  free_tags_.push_back(resp.tag);
  auto it = fills_.find(line);
  if (it == fills_.end() || it->second.beats_left == 0) throw MemoryError("L2: a memory response nobody asked for");
  if (--it->second.beats_left > 0) return;
  Install(line);
  ++stats_.line_fills;
  for (const Waiter& w : it->second.waiters) Answer(w.core, w.addr, w.tag, cycle + 1);
  fills_.erase(it);
}

bool SharedL2::Respond(int core, uint64_t cycle, MemoryResponse* out) {
  Advance(cycle);
  auto& q = out_[core];
  if (q.empty() || q.top().ready > cycle) return false;
  const Response r = q.top();
  q.pop();
  out->tag = r.tag;
  out->addr = r.addr;
  std::memset(out->data, 0, kBeatBytes);
  if (r.addr < image_.size()) std::memcpy(out->data, image_.data() + r.addr, std::min<size_t>(kBeatBytes, image_.size() - r.addr));
  return true;
}

}  // namespace kdrt::sim
