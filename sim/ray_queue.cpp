#include "sim/ray_queue.h"

#include <algorithm>

#include "common/error.h"

namespace kdrt::sim {

RayQueue::RayQueue(size_t count, int cores, size_t chunk, const std::vector<uint32_t>* order)
    : count_(count), chunk_(chunk > 0 ? chunk : 1), cur_(cores, 0), end_(cores, 0),
      order_(order && !order->empty() ? order : nullptr) {}

bool RayQueue::Take(int core, size_t* id) {
  if (cur_[core] >= end_[core]) {
    if (next_ >= count_) return false;
    cur_[core] = next_;
    end_[core] = std::min(count_, next_ + chunk_);
    next_ = end_[core];
  }
  const size_t pos = cur_[core]++;
  *id = order_ ? (*order_)[pos] : pos;
  return true;
}

namespace {

// x's bits spread to the even bit positions.
uint64_t SpreadBits(uint32_t x) {
  uint64_t v = x;
  v = (v | v << 16) & 0x0000FFFF0000FFFFull;
  v = (v | v << 8) & 0x00FF00FF00FF00FFull;
  v = (v | v << 4) & 0x0F0F0F0F0F0F0F0Full;
  v = (v | v << 2) & 0x3333333333333333ull;
  v = (v | v << 1) & 0x5555555555555555ull;
  return v;
}

}  // namespace

int MortonStreams(const std::string& name) {
  if (name == "linear") return 0;
  if (name == "morton") return 1;
  const std::string prefix = "morton:";
  if (name.compare(0, prefix.size(), prefix) == 0) {
    const std::string k = name.substr(prefix.size());
    if (!k.empty() && k.size() <= 3 && std::all_of(k.begin(), k.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      const int streams = std::stoi(k);
      if (streams >= 1 && streams <= 256) return streams;
    }
    throw InputError("--ray-order " + name + ": the streams K of morton:K must be a number from 1 to 256");
  }
  throw InputError("--ray-order " + name + ": expected linear, morton or morton:K (K streams, 1 to 256)");
}

std::vector<uint32_t> InterleaveStreams(const std::vector<uint32_t>& order, int streams) {
  if (streams <= 1) return order;
  const size_t n = order.size(), run = (n + streams - 1) / streams;
  std::vector<uint32_t> out;
  out.reserve(n);
  for (size_t i = 0; i < run; ++i) {
    for (size_t s = 0; s < static_cast<size_t>(streams); ++s) {
      if (s * run + i < n) out.push_back(order[s * run + i]);
    }
  }
  return out;
}

std::vector<uint32_t> IssueOrder(const std::string& name, uint32_t width, size_t count) {
  const int streams = MortonStreams(name);
  if (streams == 0) return {};
  if (width == 0 || count % width != 0) {
    throw InputError("--ray-order " + name + ": the rays must be whole rows of a frame (" + std::to_string(count) +
                     " rays, width " + std::to_string(width) + ")");
  }
  std::vector<uint32_t> pixel(count);  // ray i is pixel i of the frame
  for (size_t i = 0; i < count; ++i) pixel[i] = static_cast<uint32_t>(i);
  return InterleaveStreams(PixelIssueOrder(pixel, width), streams);
}

std::vector<uint32_t> PixelIssueOrder(const std::vector<uint32_t>& pixel, uint32_t width) {
  if (width == 0) throw InputError("--ray-order morton: a pass's rays need the frame's width");
  std::vector<std::pair<uint64_t, uint32_t>> keyed(pixel.size());
  for (size_t i = 0; i < pixel.size(); ++i) {
    const uint32_t x = pixel[i] % width, y = pixel[i] / width;
    keyed[i] = {SpreadBits(x) | SpreadBits(y) << 1, static_cast<uint32_t>(i)};
  }
  std::sort(keyed.begin(), keyed.end());  // ties (one pixel's rays) by list position
  std::vector<uint32_t> order(pixel.size());
  for (size_t i = 0; i < pixel.size(); ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace kdrt::sim
