// The rays of a run handed out to one or several cores (kdrt sim --cores N
// shares one queue between all cores, docs/simulator.md "Several cores").
// Plain C++: the RTL harness and the fast model take rays from it the same
// way, so both give each core the same rays in the same cycles.
#pragma once

#include <cstddef>
#include <vector>

namespace kdrt::sim {

// Hands out ray ids (indices in the ray list) in order, a chunk of
// consecutive rays at a time: a core takes its chunk's rays one by one and
// then the next free chunk.
class RayQueue {
 public:
  RayQueue(size_t count, int cores, size_t chunk);
  bool Take(int core, size_t* id);
  // Nothing is left for `core` (its chunk is used up and no chunk is free).
  bool Exhausted(int core) const { return cur_[core] >= end_[core] && next_ >= count_; }
  size_t count() const { return count_; }
  size_t returned() const { return returned_; }
  void Returned() { ++returned_; }

 private:
  size_t count_, chunk_, next_ = 0, returned_ = 0;
  std::vector<size_t> cur_, end_;
};

}  // namespace kdrt::sim
