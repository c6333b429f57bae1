// Tracing batches of rays through a memory image in any number format.
// fp32 runs on native floats (FTZ/DAZ set for the duration), fp64 (the
// accuracy reference) on native doubles with IEEE gradual underflow, every
// other format on the bit-accurate soft-float model; all share one template.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "common/ray.h"
#include "fp/format.h"
#include "trace/intersect.h"
#include "trace/memory_image.h"
#include "trace/packet.h"

namespace kdrt {

IsectMethod ParseIsectMethod(const std::string& name);  // "watertight", "moller"
const char* IsectMethodName(IsectMethod m);

struct TraceOptions {
  fp::Format format{8, 23};
  // The traversal's own format (clip, split distances, cell intervals and
  // the stack), wider than `format` or equal; unset: `format`. The triangle
  // test always runs in `format`. The RTL core's TravE, TravM (kdrt sim
  // --trav-format, at most fp32).
  std::optional<fp::Format> trav_format;
  IsectMethod isect = IsectMethod::kWatertight;
  Query query = Query::kClosest;  // kAny: shadow rays (common/ray.h)
  int threads = 0;  // 0: all hardware threads; results do not depend on it
  // 0: a stack as deep as the tree; N: the core's StackDepth N (a push onto N
  // entries ends the ray, RayCounters::overflows; trace/traversal.h).
  int stack_depth = 0;
  bool progress = false;  // a progress line on stderr for long runs
  // Rays per packet (trace/packet.h): 0 one at a time, 4, 8 or 16; the
  // results are the same bits either way.
  int packets = kDefaultPacketWidth;
  // Rays in rows of this many (a camera's image, row by row): packets are
  // then tiles of 2x2 (4 rays), 4x2 (8) or 4x4 (16) neighbouring rays.
  // 0: packets of consecutive rays.
  int row_width = 0;
};

// The traversal format in effect.
fp::Format TravFormat(const TraceOptions& options);
// Throws InputError unless the traversal format holds every value of the
// test's format (at least its exponent and mantissa bits), as the traversal
// works on the test's ray widened exactly.
void CheckTravFormat(const fp::Format& format, const fp::Format& trav);
void CheckTravFormat(const TraceOptions& options);
// Throws InputError unless `format`, the datapath's, holds every value of the
// image's format `image` (a narrower image: splits and vertices stored in
// fewer bits, loaded exactly; --image-format).
void CheckImageFormat(const fp::Format& format, const fp::Format& image);

struct TraceStats {
  RayCounters totals;
  uint64_t rays = 0;
  uint64_t hits = 0;
  double seconds = 0;  // wall-clock time of tracing alone
  PacketPlan packets;     // how the rays were traced
  PacketCounts packet_counts;
};

// One ray; `path` (optional) receives the nodes fetched, in order.
Hit TraceOne(const ImageView& image, const Ray& ray, const TraceOptions& options,
             RayCounters* counters = nullptr, std::vector<uint32_t>* path = nullptr);

std::vector<Hit> TraceRays(const ImageView& image, const std::vector<Ray>& rays,
                           const TraceOptions& options, TraceStats* stats = nullptr,
                           std::vector<RayCounters>* per_ray = nullptr);

}  // namespace kdrt
