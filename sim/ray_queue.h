// The rays of a run handed out to one or several cores (kdrt sim --cores N
// shares one queue between all cores, docs/simulator.md "Several cores").
// Plain C++: the RTL harness and the fast model take rays from it the same
// way, so both give each core the same rays in the same cycles.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace kdrt::sim {

// Hands out ray ids (indices in the ray list) in issue order, a chunk of
// consecutive positions at a time: a core takes its chunk's rays one by one
// and then the next free chunk. The issue order is the list's, or `order`
// (position -> ray id, a permutation of the ids; it must outlive the queue).
class RayQueue {
 public:
  RayQueue(size_t count, int cores, size_t chunk, const std::vector<uint32_t>* order = nullptr);
  bool Take(int core, size_t* id);
  // Nothing is left for `core` (its chunk is used up and no chunk is free).
  bool Exhausted(int core) const { return cur_[core] >= end_[core] && next_ >= count_; }
  size_t count() const { return count_; }
  size_t returned() const { return returned_; }
  void Returned() { ++returned_; }

 private:
  size_t count_, chunk_, next_ = 0, returned_ = 0;
  std::vector<size_t> cur_, end_;
  const std::vector<uint32_t>* order_;
};

// The issue orders of `kdrt sim --ray-order` (docs/simulator.md, "Ray
// order"): "linear" (the ray list's order: a camera's rays row by row) gives
// an empty vector; "morton" takes the rays as a row-major frame `width`
// pixels wide and issues them along the Z-order curve over (x, y), so the
// rays in flight together are neighbours in 2D (tiles of 2x2, 4x4, ...).
// Throws InputError for another name, a width of 0 or a count that is not
// whole rows.
// "morton:K" (K from 1 to 256; "morton" is "morton:1") cuts the Z-order
// into K runs of consecutive rays (the frame's K regions along the curve)
// and issues one ray of each in turn (InterleaveStreams), so the rays in
// flight come from K regions at once: where regions alternate between
// traversal-heavy and test-heavy work, both units then have work
// (docs/simulator.md, "Ray order"), at the cost of K working sets in the
// caches.
std::vector<uint32_t> IssueOrder(const std::string& name, uint32_t width, size_t count);

// The streams of an order name: 0 for "linear", K for "morton" (1) and
// "morton:K"; throws InputError for anything else.
int MortonStreams(const std::string& name);

// `order` cut into `streams` runs of ceil(n / streams) positions (the last
// shorter), then position i of run 0, of run 1, ..., of the last run, and
// i + 1 of each: a permutation of `order`; `streams` <= 1 returns it as is.
std::vector<uint32_t> InterleaveStreams(const std::vector<uint32_t>& order, int streams);

// The order of a secondary pass's rays (`kdrt sim --shade`) under
// --ray-order morton: by the Z-order of the pixel each ray comes from
// (`pixel[i]`: ray i's row-major pixel in a frame `width` wide), the rays of
// one pixel in their list order. Position -> ray index; throws InputError for
// a width of 0.
std::vector<uint32_t> PixelIssueOrder(const std::vector<uint32_t>& pixel, uint32_t width);

}  // namespace kdrt::sim
