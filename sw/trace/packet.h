// Coherent rays traced together (Wald 2001/2004): a packet of 4, 8 or 16
// rays walks the kd-tree as one, each inner node fetched once for all its
// active rays and its split distance computed for all of them in one vector
// operation. Every ray keeps its own interval, stack depth, in-plane count,
// best hit and counters, and is active at exactly the nodes of its own
// scalar walk, in the same order (a ray whose children order differs from
// the packet's at a node where both would push leaves the packet and is
// traced alone). So hits and per-ray counters are the scalar tracer's, bit
// for bit (tests/trace/packet_test.cpp).
//
// Packed: native fp32 in one format (trav_format unset or fp32) on an fp32
// image; every other format runs the scalar walk (PacketPlan says so).
#pragma once

#include <cstddef>
#include <string>

#include "common/ray.h"
#include "trace/memory_image.h"

namespace kdrt {

struct TraceOptions;

// --packets: "off" (0), "4", "8" or "16"; InputError otherwise.
int ParsePacketWidth(const std::string& text);

// The default width: the fastest one measured with kdrt_bench (docs/results.md,
// "The reference tracer against Embree").
inline constexpr int kDefaultPacketWidth = 8;

// How a batch is traced.
struct PacketPlan {
  int width = 0;           // 0: one ray at a time
  const char* isa = "";    // "sse2" or "avx2": the instructions the width runs on
  std::string why_scalar;  // width 0 although packets were asked for: why
};

// The plan for `options` on `image` (the width asked, the CPU's ISA, the format).
PacketPlan PlanPackets(const ImageView& image, const TraceOptions& options);

// The formats the packet path runs (the others run the scalar walk).
const char* PacketFormats();

// What packets did, beside the per-ray counters (those are each ray's own).
struct PacketCounts {
  uint64_t scalar_rays = 0;   // rays that left their packet and ran alone
  uint64_t node_fetches = 0;  // nodes fetched by packets: RayCounters::nodes / this = active lanes per fetch
  PacketCounts& operator+=(const PacketCounts& o) {
    scalar_rays += o.scalar_rays;
    node_fetches += o.node_fetches;
    return *this;
  }
};

// Traces rays[0..n) (n <= width) as one packet with the plan's width; the
// caller holds fp::ScopedFtzDaz. hits[i] and counters[i] (added to) are the
// scalar tracer's.
void TracePacket(const PacketPlan& plan, const ImageView& image, const Ray* rays, int n,
                 const TraceOptions& options, Hit* hits, RayCounters* counters, PacketCounts* counts);

}  // namespace kdrt
