// A FIFO in a power-of-two ring (no allocation per entry), for the queues the
// cycle models touch every cycle: the fast model's pipelines and job FIFO
// (bounded) and the memory model's outstanding requests (growing).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <vector>

namespace kdrt::sim {

template <typename T>
class Ring {
 public:
  // Room for at least `capacity` entries. A bounded ring never grows: its
  // bound is the caller's proof, and push() checks it all the same (throws
  // std::logic_error when full). An unbounded one doubles when full.
  Ring(size_t capacity, bool bounded) : bounded_(bounded) {
    size_t cap = 1;
    while (cap < capacity) cap <<= 1;
    buf_.resize(cap);
    mask_ = cap - 1;
  }
  bool empty() const { return head_ == tail_; }
  size_t size() const { return tail_ - head_; }
  const T& front() const { return buf_[head_ & mask_]; }
  // The entry i places behind the front (i < size()).
  const T& at(size_t i) const { return buf_[(head_ + i) & mask_]; }
  void pop() { ++head_; }
  void push(const T& v) {
    if (size() > mask_) Grow();
    buf_[tail_++ & mask_] = v;
  }

 private:
  // Doubles the ring, keeping the entries in order.
  void Grow() {
    if (bounded_) throw std::logic_error("ring overflow: more entries than its bound");
    std::vector<T> bigger(buf_.size() * 2);
    for (size_t i = head_; i < tail_; ++i) bigger[i - head_] = buf_[i & mask_];
    tail_ -= head_;
    head_ = 0;
    buf_.swap(bigger);
    mask_ = buf_.size() - 1;
  }

  std::vector<T> buf_;
  size_t mask_ = 0;  // buf_.size() - 1 (a power of two less one)
  bool bounded_;
  size_t head_ = 0, tail_ = 0;  // running counts: the entries are [head_, tail_)
};

}  // namespace kdrt::sim
