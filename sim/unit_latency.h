// The pipeline latencies of the core's fixed-latency units, in enabled
// cycles from input to output: the one source of these numbers on the C++
// side. The fast model (sim/fast_model.cpp) times its pipelines with them,
// and each unit's Verilator bench (tests/rtl/) measures the RTL unit and
// fails when it differs, naming the unit. The floating-point latencies mirror
// rtl/kdrt_fp_pkg.sv, which the RTL units build their pipelines from.
#ifndef KDRT_SIM_UNIT_LATENCY_H_
#define KDRT_SIM_UNIT_LATENCY_H_

#include <algorithm>

#include "fp/format.h"

namespace kdrt::sim::latency {

// rtl/kdrt_fp_pkg.sv: FpAddLatency, FpMulLatency, FpFromF32Latency,
// FpDivExtraLatency (fp_div takes M + FpDivExtraLatency).
inline constexpr unsigned kFpAdd = 4;
inline constexpr unsigned kFpMul = 3;
inline constexpr unsigned kFpFromF32 = 1;
inline constexpr unsigned kFpDivExtra = 4;
inline unsigned FpDiv(fp::Format f) { return static_cast<unsigned>(f.m) + kFpDivExtra; }

// A traversal format wider than the core's rounds the cell ends outwards
// into the core's format: one fp_round_out stage (FpFromF32Latency).
inline unsigned Widening(fp::Format f, fp::Format trav) { return f != trav ? kFpFromF32 : 0; }

// rt_ray_setup: frame 2, load 1, compare 1, divide M + 4; a wider
// traversal's reciprocals (frame 2, load 1, divide TravM + 4) may take longer.
inline unsigned RaySetup(fp::Format f, fp::Format trav) {
  const unsigned test = 4 + FpDiv(f);
  return f == trav ? test : std::max(test, 3 + FpDiv(trav));
}

// rt_clip_unit: from_f32, add, mul and a 3-stage chain.
inline unsigned Clip(fp::Format f, fp::Format trav) {
  return kFpFromF32 + kFpAdd + kFpMul + 3 + Widening(f, trav);
}

// rt_trav_unit: from_f32, add, mul.
inline unsigned Trav(fp::Format f, fp::Format trav) {
  return kFpFromF32 + kFpAdd + kFpMul + Widening(f, trav);
}

// rt_isect_unit (docs/isect-unit.md): 34 + M with the fp latencies above.
inline unsigned Isect(fp::Format f) { return 30 + FpDiv(f); }

}  // namespace kdrt::sim::latency

#endif  // KDRT_SIM_UNIT_LATENCY_H_
