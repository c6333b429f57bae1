// The fast cycle model of rt_core (kdrt sim --model fast|both; docs/simulator.md,
// "The fast model"): plain C++, no Verilator. It follows the same rays through
// the same memory image with the core's structure at the level of its
// registers and handshakes: threads and their states, the fixed-latency
// units (setup, clip, traversal, intersection), the round-robin arbiters, the
// node cache with its miss-only port, the list unit, the list and triangle
// caches (sets of lines with pseudo-LRU, miss registers, merging, the two response
// registers), the memory arbiter and the same MemoryModel. What a ray does
// (the nodes it fetches, the leaves and their tests) comes from the reference
// traversal, so the hits are the reference's by construction; the model only
// says how many cycles the core takes and why.
//
// Every performance event of rt_perf_events is counted as the RTL counts it
// (the backpressure and unit stalls are zero: the units and the harness are
// always ready). A StackDepth below the tree's depth (--allow-overflow) is
// modelled as the core does it: the push onto a full stack ends the ray.
#pragma once

#include <cstdint>
#include <vector>

#include "common/ray.h"
#include "sim/core_params.h"
#include "sim/memory_model.h"
#include "sim/run_result.h"
#include "trace/memory_image.h"

namespace kdrt::sim {

struct FastSpec {
  const ImageView* image = nullptr;  // the image the core reads (of ImageFormat())
  const std::vector<Ray>* rays = nullptr;
  Query query = Query::kClosest;
  CoreConfig config;
  MemoryConfig memory;
  uint64_t timeout = 1000000;  // cycles without a hit record
};

// The reference's hits are in result.hits; throws SimFailure on a timeout.
RunOutcome RunFastModel(const FastSpec& spec, RayCounters* reference_totals);

}  // namespace kdrt::sim
