// Rays, hits and per-ray work counters shared by the reference tracer, the
// ray files and the simulator.
#pragma once

#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

namespace kdrt {

inline constexpr uint32_t kNoPrim = 0xFFFFFFFFu;

struct Ray {
  glm::vec3 o;
  glm::vec3 d;
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();
};

// A hit record; a miss has t = +inf, prim = kNoPrim, u = v = 0.
// u and v are the barycentric weights of v1 and v2 (Embree's convention):
// p = (1 - u - v) v0 + u v1 + v v2.
struct Hit {
  float t = std::numeric_limits<float>::infinity();
  uint32_t prim = kNoPrim;
  float u = 0.0f;
  float v = 0.0f;
  bool IsHit() const { return prim != kNoPrim; }
};

// What a ray asks for. kAny is a shadow or occlusion query: the ray ends
// after the first leaf (in traversal order) that gives it a hit, and returns
// that leaf's closest hit, so it answers "is anything in [tmin, tmax]?" and
// the record is still one definite hit, the same for the model and the RTL.
enum class Query : uint8_t { kClosest, kAny };

struct RayCounters {
  uint32_t nodes = 0;      // inner and leaf nodes fetched (an empty leaf only as the root:
                           // any other is marked in its parent and not fetched)
  uint32_t leaves = 0;     // leaf nodes fetched
  uint32_t empty_skipped = 0;  // empty leaves passed without a fetch (marked in their parent)
  uint32_t tri_tests = 0;  // ray/triangle tests
  uint32_t overflows = 0;  // rays ended by a push onto a full stack (TraceOptions::stack_depth)
  RayCounters& operator+=(const RayCounters& o) {
    nodes += o.nodes;
    leaves += o.leaves;
    empty_skipped += o.empty_skipped;
    tri_tests += o.tri_tests;
    overflows += o.overflows;
    return *this;
  }
};

}  // namespace kdrt
