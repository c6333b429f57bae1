// A small harness for the Verilator benches of the (E, M) units (rtl/fp_*.sv).
// It streams vectors through a unit with random bubbles (valid_i low) and
// random stalls (en_i low), checks the latency, that a stalled pipeline holds
// its outputs, that results come out in order and that every result equals
// the C++ model (sw/fp/format.h). The first mismatch is reported with the
// operands and both results. Clock and reset: sim/sim_ctrl.h.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fp/format.h"
#include "sim/sim_ctrl.h"
#include "sim/unit_latency.h"
#include "tests/fp/fp_vectors.h"

namespace kdrt::fp::bench {

// The latencies the fast model assumes (sim/unit_latency.h); the benches
// measure each unit's and compare.
namespace kdrt_fp_latency {
inline constexpr unsigned kAdd = sim::latency::kFpAdd;
inline constexpr unsigned kMul = sim::latency::kFpMul;
inline constexpr unsigned kFromF32 = sim::latency::kFpFromF32;
inline unsigned Div(Format f) { return sim::latency::FpDiv(f); }
}  // namespace kdrt_fp_latency

struct Vec {
  uint32_t a = 0;
  uint32_t b = 0;
  bool sub = false;
};

// Outputs of one result (unused slots stay 0).
using Out = std::array<uint32_t, 5>;

// Produces vectors one by one; returns false when exhausted.
using Source = std::function<bool(Vec&)>;

// Every pair of the format when it has at most 8 bits, else all pairs of the
// corner values followed by `random_pairs` random pairs.
inline Source PairSource(Format f, uint64_t random_pairs, uint64_t seed) {
  struct State {
    std::vector<uint32_t> corners;
    test::Rng rng;
    uint64_t i = 0;
  };
  auto st = std::make_shared<State>(State{test::CornerValues(f), test::Rng(seed)});
  const bool exhaustive = f.Width() <= 8;
  const uint64_t n_all = uint64_t{1} << (2 * f.Width());
  const uint64_t n_corner = st->corners.size() * st->corners.size();
  return [=](Vec& v) {
    const uint64_t i = st->i++;
    if (exhaustive) {
      if (i >= n_all) return false;
      v = {static_cast<uint32_t>(i >> f.Width()),
           static_cast<uint32_t>(i & ((uint64_t{1} << f.Width()) - 1)), false};
      return true;
    }
    if (i < n_corner) {
      v = {st->corners[i / st->corners.size()], st->corners[i % st->corners.size()], false};
      return true;
    }
    if (i >= n_corner + random_pairs) return false;
    const auto [a, b] = test::RandomPair(f, st->rng, st->corners);
    v = {a, b, false};
    return true;
  };
}

inline uint64_t RandomCount() { return test::RandomPairCount(); }

inline std::string ToString(const Vec& v) {
  return "a=" + test::Hex(v.a) + " b=" + test::Hex(v.b) + (v.sub ? " sub=1" : "");
}

inline std::string ToString(const Out& o, int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += (i ? " " : "") + test::Hex(o[i]);
  return s;
}

// Runs one verilated unit. `drive` sets the operand inputs from a vector,
// `read` gets the outputs, `model` gives the expected outputs; `n_out` is how
// many slots of Out are meaningful (for printing).
template <class Dut>
bool RunUnit(const char* unit, Format f, unsigned latency, Source next,
             const std::function<void(Dut&, const Vec&)>& drive,
             const std::function<Out(const Dut&)>& read,
             const std::function<Out(const Vec&)>& model, int n_out, uint64_t seed) {
  sim::SimCtrl<Dut> sim;
  Dut& dut = sim.top();
  const std::string what = std::string(unit) + " " + f.Name();
  auto tick = [&sim] { sim.Step(); };
  dut.en_i = 1;
  dut.valid_i = 0;
  sim.Reset();

  // Latency: one valid input, count enabled cycles until it comes out.
  dut.valid_i = 1;
  drive(dut, Vec{});
  tick();
  dut.valid_i = 0;
  unsigned cycles = 1;
  while (!dut.valid_o && cycles < 200) {
    tick();
    ++cycles;
  }
  if (cycles != latency) {
    std::printf("FAIL %s: latency %u, documented %u\n", what.c_str(), cycles, latency);
    return false;
  }
  for (unsigned i = 0; i < latency + 1; ++i) tick();  // drain
  if (dut.valid_o) {
    std::printf("FAIL %s: valid_o stays high after the pipeline drained\n", what.c_str());
    return false;
  }

  test::Rng rng(seed);
  std::deque<std::pair<Vec, Out>> expected;
  uint64_t issued = 0, checked = 0;
  bool have = false, exhausted = false;
  Vec v;
  for (;;) {
    if (!have && !exhausted) {
      have = next(v);
      exhausted = !have;
    }
    if (!have && expected.empty()) break;
    const bool en = rng.Below(8) != 0;
    const bool offer = have && rng.Below(8) != 0;
    dut.en_i = en;
    dut.valid_i = offer;
    if (offer) drive(dut, v);
    const bool valid_before = dut.valid_o;
    const Out out_before = read(dut);
    tick();
    if (!en) {  // stalled: nothing taken, nothing may change
      if (dut.valid_o != valid_before || read(dut) != out_before) {
        std::printf("FAIL %s: outputs changed while en_i was low\n", what.c_str());
        return false;
      }
      continue;
    }
    if (offer) {
      expected.emplace_back(v, model(v));
      ++issued;
      have = false;
    }
    if (dut.valid_o) {
      if (expected.empty()) {
        std::printf("FAIL %s: a result with no vector in flight\n", what.c_str());
        return false;
      }
      const auto [vec, want] = expected.front();
      expected.pop_front();
      const Out got = read(dut);
      if (got != want) {
        std::printf("FAIL %s: first mismatch at vector %llu: %s: rtl %s, model %s\n",
                    what.c_str(), static_cast<unsigned long long>(checked),
                    ToString(vec).c_str(), ToString(got, n_out).c_str(),
                    ToString(want, n_out).c_str());
        return false;
      }
      ++checked;
    }
    if (expected.size() > latency) {
      std::printf("FAIL %s: %zu vectors in flight but the latency is %u\n", what.c_str(),
                  expected.size(), latency);
      return false;
    }
  }
  std::printf("PASS %s: %llu vectors, latency %u\n", what.c_str(),
              static_cast<unsigned long long>(checked), latency);
  return issued == checked;
}

}  // namespace kdrt::fp::bench
