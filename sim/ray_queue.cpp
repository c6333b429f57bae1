#include "sim/ray_queue.h"

#include <algorithm>

namespace kdrt::sim {

RayQueue::RayQueue(size_t count, int cores, size_t chunk)
    : count_(count), chunk_(chunk > 0 ? chunk : 1), cur_(cores, 0), end_(cores, 0) {}

bool RayQueue::Take(int core, size_t* id) {
  if (cur_[core] >= end_[core]) {
    if (next_ >= count_) return false;
    cur_[core] = next_;
    end_[core] = std::min(count_, next_ + chunk_);
    next_ = end_[core];
  }
  *id = cur_[core]++;
  return true;
}

}  // namespace kdrt::sim
