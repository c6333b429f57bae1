// Precision requirements derived from the scene (docs/precision.md): how
// many exponent bits E and mantissa bits M a number format needs so that the
// scene, as the hardware reads it (the memory image), and the rays a command
// traces survive the conversion to the format and the datapath's arithmetic.
//
// Every criterion checks a set of items (vertices, triangles, split planes,
// rays) and gives each item the number of bits it needs; a format with fewer
// bits breaks that item. The exponent criteria depend on E only (magnitudes:
// overflow and flush to zero), the mantissa criteria on M only (rounding with
// an unbounded exponent), so the requirement is a pair (E_min, M_min) and a
// format meets it iff e >= E_min and m >= M_min; counts never grow with more
// bits.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/ray.h"
#include "fp/format.h"
#include "trace/memory_image.h"

namespace kdrt {

struct PrecisionCriterion {
  std::string name;    // JSON key, e.g. "vertex_collapse"
  bool exponent;       // needs exponent bits (else mantissa bits)
  std::string items;   // what is counted: "vertices", "triangles", ...
  std::string breaks;  // what happens to a failing item, for messages
  // A property of the stored scene (vertices, splits), decided by the image's
  // format; the others are decided by the datapath's arithmetic. The two
  // differ when the image is narrower than the datapath (--image-format).
  bool storage = false;
  uint64_t checked = 0;
  // needing[b]: items that need exactly b bits (b = 0: nothing to check).
  std::vector<uint64_t> needing = std::vector<uint64_t>(64, 0);

  void Add(int bits) {
    ++checked;
    ++needing[static_cast<size_t>(bits)];
  }
  int MinBits() const;                // no item needs more
  uint64_t Failing(int bits) const;  // items that need more than `bits`
};

struct PrecisionRequirement {
  std::vector<PrecisionCriterion> criteria;
  uint64_t rays = 0;       // rays analysed (0: the image criteria alone)
  uint64_t hit_tests = 0;  // of those, rays with a hit in fp64
  int min_exponent_bits = 2;
  int min_mantissa_bits = 1;
  // The same over the storage criteria alone: the narrowest image a datapath
  // that meets the rest may read.
  int min_image_exponent_bits = 2;
  int min_image_mantissa_bits = 1;

  std::string MinimalFormat() const;       // "eXmY"
  std::string MinimalImageFormat() const;  // "eXmY"
  bool Meets(const fp::Format& f) const { return f.e >= min_exponent_bits && f.m >= min_mantissa_bits; }
  // "" when `f` meets the requirement, else "<f> cannot represent this scene:
  // <n of N items break, per criterion> (minimal format eXmY)". With `image`
  // (the format of a narrower image than the datapath's `f`) the storage
  // criteria are checked against `image`, the others against `f`.
  std::string Shortfall(const fp::Format& f) const { return Shortfall(f, f); }
  std::string Shortfall(const fp::Format& f, const fp::Format& image) const;
  // {"min_exponent_bits", "min_mantissa_bits", "minimal_format",
  //  "min_image_exponent_bits", "min_image_mantissa_bits",
  //  "minimal_image_format", "rays", "hit_tests", "criteria": {name: {...}}}
  nlohmann::json Json() const;
};

// Analyses the image and, when `rays` is not empty, the rays (traced once in
// fp64 to find the triangle each ray hits). `threads` as in TraceOptions.
PrecisionRequirement AnalyzePrecision(const ImageView& image, const std::vector<Ray>& rays, int threads = 0);

// The fraction of x rounded to m bits (round to nearest even, unbounded
// exponent range; m >= 23 returns x): how a soft format with m mantissa bits
// loads an fp32 value, ignoring overflow and flush to zero.
float RoundMantissa(float x, int m);

// Whether three points are collinear (or coincide), exactly for points whose
// coordinate differences are exact in double (coordinates within 29
// binades of each other): the triangle has no area.
bool Collinear(const double a[3], const double b[3], const double c[3]);

}  // namespace kdrt
