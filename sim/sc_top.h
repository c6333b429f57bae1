// The SystemC top (`kdrt sim --systemc`): an SC_MODULE owns the Verilated
// core and ticks it from an SC_METHOD on an sc_clock, and a memory SC_MODULE
// wraps the memory model. The core's pins are not wired through sc_signals
// (that costs several times the simulation speed); the core module calls the
// memory module through an sc_port / sc_interface, once per cycle, exactly
// as the plain Verilator loop calls the memory model, so both loops give the
// same cycles and the same hits.
#pragma once

#include "sim/core_harness.h"
#include "sim/l2_cache.h"

namespace kdrt::sim {

RunOutcome RunSystemC(const RunSpec& spec);

// Several cores (kdrt sim --cores N): N core modules, each its own Verilated
// rt_core and harness, take rays from one shared queue (RayQueue, chunks of
// `chunk` rays) and read through one shared L2 module (SharedL2) in front of
// the memory module. The waveform, if any, is core 0's.
SystemOutcome RunSystemCCores(const RunSpec& spec, int cores, const L2Config& l2, size_t chunk);

}  // namespace kdrt::sim
