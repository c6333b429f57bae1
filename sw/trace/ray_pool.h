// The worker pool every batch tracer shares (the kd-tree tracer and the
// other structures of sw/structures): rays are handed out in chunks from a
// shared counter and every ray's result goes to its own slot, so the output
// never depends on the thread count.
#pragma once

#include <cstddef>
#include <functional>

namespace kdrt {

// Hands out the next chunk [*begin, *end); false when the rays are used up.
using NextChunk = std::function<bool(size_t* begin, size_t* end)>;

// Runs `body` once on each of min(threads, rays / 256 + 1) threads (0: all
// hardware threads), the calling thread included; each body sets up its
// per-thread state (rounding mode, scratch) and then takes chunks until none
// is left. `progress` prints a line on stderr every half second.
void RunRayThreads(size_t rays, int threads, bool progress, const std::function<void(const NextChunk&)>& body);

}  // namespace kdrt
