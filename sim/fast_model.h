// The fast cycle model of rt_core (kdrt sim --model fast|both; docs/simulator.md,
// "The fast model"): plain C++, no Verilator. It follows the same rays through
// the same memory image with the core's structure at the level of its
// registers and handshakes: threads and their states, the fixed-latency
// units (setup, clip, traversal, intersection), the round-robin arbiters, the
// node cache with its miss-only port, the list unit (with ListStream its
// line requests and rt_mem_system's line register; with ListPrefetch its
// prefetcher and the list cache's prefetch port), the list and triangle
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
#include "sim/l2_cache.h"
#include "sim/memory_model.h"
#include "sim/run_result.h"
#include "trace/memory_image.h"

namespace kdrt::sim {

struct FastSpec {
  const ImageView* image = nullptr;  // the image the core reads (of ImageFormat())
  const std::vector<Ray>* rays = nullptr;
  const std::vector<uint32_t>* order = nullptr;  // issue order (sim/ray_queue.h), or null: the list's
  Query query = Query::kClosest;
  CoreConfig config;
  MemoryConfig memory;
  uint64_t timeout = 1000000;  // cycles without a hit record
  bool progress = false;       // a progress line on stderr (rays returned, cycles, Mcycles/s)
};

// One core straight on the memory (the fast model of RunVerilator). The
// reference's hits are in result.hits, its counters in `reference_totals`
// and (when not null) each ray's in `reference_per_ray`; throws
// std::runtime_error on a timeout.
RunOutcome RunFastModel(const FastSpec& spec, RayCounters* reference_totals,
                        std::vector<RayCounters>* reference_per_ray = nullptr);

// What the reference traversal gave every ray of a run of several cores:
// the hits (the records the cores return), and each ray's counters (a
// core's bound is the sum over the rays it took).
struct FastReference {
  std::vector<Hit> hits;
  std::vector<uint8_t> overflow;  // by ray: its push met a full stack
  uint64_t overflows = 0;
  std::vector<RayCounters> per_ray;
  RayCounters totals;
};

// N cores sharing an L2 in front of the memory, rays from one shared queue
// `chunk` at a time: the fast model of RunSystemCCores (sim/sc_top.h), core
// by core in the order the SystemC kernel runs them, so each core takes the
// same rays in the same cycles as there. Each core's result has its rays'
// ids, hit and overflow counts; the hits themselves are in `reference`.
SystemOutcome RunFastCores(const FastSpec& spec, int cores, const L2Config& l2, size_t chunk,
                           FastReference* reference);

}  // namespace kdrt::sim
