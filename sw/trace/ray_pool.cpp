#include "trace/ray_pool.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

namespace kdrt {

void RunRayThreads(size_t rays, int threads, bool progress, const std::function<void(const NextChunk&)>& body) {
  threads = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::max(1, std::min<int>(threads, static_cast<int>(rays / 256 + 1)));
  constexpr size_t kChunk = 256;
  std::atomic<size_t> next{0};
  std::atomic<size_t> done{0};
  // A chunk counts as done when the next one is asked for (or none is left).
  auto worker = [&]() {
    size_t taken = 0;
    const NextChunk next_chunk = [&](size_t* begin, size_t* end) {
      if (taken > 0) done.fetch_add(taken);
      taken = 0;
      *begin = next.fetch_add(kChunk);
      if (*begin >= rays) return false;
      *end = std::min(rays, *begin + kChunk);
      taken = *end - *begin;
      return true;
    };
    body(next_chunk);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  if (progress) {
    std::atomic<bool> finished{false};
    std::thread progress_thread([&]() {
      while (!finished.load()) {
        std::fprintf(stderr, "\r  traced %zu / %zu rays", done.load(), rays);
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
      }
      std::fprintf(stderr, "\r  traced %zu / %zu rays\n", rays, rays);
    });
    worker();
    for (std::thread& t : pool) t.join();
    finished = true;
    progress_thread.join();
  } else {
    worker();
    for (std::thread& t : pool) t.join();
  }
}

}  // namespace kdrt
