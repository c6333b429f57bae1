// Tracing batches of rays through a software structure (structure.h), in
// fp32 or fp64, on the worker pool the kd-tree tracer uses.
#pragma once

#include <cstdint>
#include <vector>

#include "structures/structure.h"
#include "trace/frame.h"
#include "trace/tracer.h"

namespace kdrt {

// Work and time of a batch, summed over its rays.
struct AccelTotals {
  uint64_t rays = 0;
  uint64_t hits = 0;
  uint64_t nodes = 0;
  uint64_t leaves = 0;
  uint64_t tri_tests = 0;
  uint64_t mailbox_hits = 0;
  double seconds = 0;  // wall-clock time of tracing alone
  void Add(const AccelCounters& c) {
    nodes += c.nodes;
    leaves += c.leaves;
    tri_tests += c.tri_tests;
    mailbox_hits += c.mailbox_hits;
  }
};

// The kd-tree tracer's totals in the same form (no mailbox).
AccelTotals ToAccelTotals(const TraceStats& stats);

// Throws InputError unless options.format is fp32 or fp64 and the test is
// the watertight one (the backends share nothing else with the datapath).
void CheckStructureTraceOptions(const TraceOptions& options);

// One ray (world coordinates); `scratch` holds the mailbox and receives the
// ray's counters.
Hit TraceStructureOne(const Structure& s, const Frame& frame, const Ray& ray, const TraceOptions& options,
                      TraceScratch& scratch);

std::vector<Hit> TraceStructureRays(const Structure& s, const Frame& frame, const std::vector<Ray>& rays,
                                    const TraceOptions& options, AccelTotals* totals = nullptr,
                                    std::vector<AccelCounters>* per_ray = nullptr);

}  // namespace kdrt
