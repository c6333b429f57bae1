// Verilator bench of rtl/rt_prio_enc.sv against the lowest set bit computed
// in C++: valid_o is whether any bit is set, idx_o the lowest set bit's index
// (0 when none). Every vector for N up to 5; for wider N every single bit,
// every pair of bits, and random vectors of densities from one bit in a
// hundred to all set. N = 1, 2, 3, 5 (not powers of two), 32 and 128, each
// in both descriptions of the encoder (Words = 1, the default under
// Verilator, and the tree, Words = 0, that synthesis takes).
#include <algorithm>
#include <cstdio>
#include <vector>

#include "Vrt_prio_enc_n1.h"
#include "Vrt_prio_enc_n128.h"
#include "Vrt_prio_enc_n128_tree.h"
#include "Vrt_prio_enc_n1_tree.h"
#include "Vrt_prio_enc_n2.h"
#include "Vrt_prio_enc_n2_tree.h"
#include "Vrt_prio_enc_n3.h"
#include "Vrt_prio_enc_n32.h"
#include "Vrt_prio_enc_n32_tree.h"
#include "Vrt_prio_enc_n3_tree.h"
#include "Vrt_prio_enc_n5.h"
#include "Vrt_prio_enc_n5_tree.h"
#include "sim/sim_ctrl.h"
#include "tests/rtl/isect_bench_util.h"

namespace kdrt::rtlbench {
namespace {

using sim::SimCtrl;

template <class Dut>
class Check {
 public:
  Check(unsigned n, const char* form) : n_(n), form_(form) {}
  // Applies `bits` (N of them) and compares; false (and a message) on a mismatch.
  bool operator()(const std::vector<bool>& bits) {
    Dut& dut = sim_.top();
    for (unsigned i = 0; i < n_; ++i) PutBits(dut.req_i, static_cast<int>(i), 1, bits[i]);
    sim_.Settle();
    unsigned lowest = 0;
    bool any = false;
    for (unsigned i = 0; i < n_ && !any; ++i) {
      if (bits[i]) {
        any = true;
        lowest = i;
      }
    }
    ++vectors_;
    if (dut.valid_o == any && dut.idx_o == lowest) return true;
    std::printf("rt_prio_enc N=%u %s: FAIL: req_i bits", n_, form_);
    for (unsigned i = 0; i < n_; ++i) {
      if (bits[i]) std::printf(" %u", i);
    }
    std::printf(": valid_o %u idx_o %u, expected %u %u\n", static_cast<unsigned>(dut.valid_o),
                static_cast<unsigned>(dut.idx_o), any, lowest);
    return false;
  }
  uint64_t vectors() const { return vectors_; }

 private:
  unsigned n_;
  const char* form_;
  SimCtrl<Dut> sim_;
  uint64_t vectors_ = 0;
};

template <class Dut>
bool Run(unsigned n, const char* form, uint64_t randoms) {
  Check<Dut> check(n, form);
  std::vector<bool> bits(n);
  if (n <= 5) {
    for (unsigned v = 0; v < (1u << n); ++v) {
      for (unsigned i = 0; i < n; ++i) bits[i] = (v >> i) & 1;
      if (!check(bits)) return false;
    }
  } else {
    for (unsigned a = 0; a < n; ++a) {
      for (unsigned b = a; b < n; ++b) {
        std::fill(bits.begin(), bits.end(), false);
        bits[a] = bits[b] = true;
        if (!check(bits)) return false;
      }
    }
    Rng rng(3 + n);
    const double densities[] = {0.01, 0.05, 0.2, 0.5, 0.9, 1.0};
    for (uint64_t k = 0; k < randoms; ++k) {
      const double p = densities[rng.Below(6)];
      for (unsigned i = 0; i < n; ++i) bits[i] = rng.Chance(p);
      if (!check(bits)) return false;
    }
  }
  std::printf("rt_prio_enc N=%u %s: PASS (%llu vectors)\n", n, form,
              static_cast<unsigned long long>(check.vectors()));
  return true;
}

}  // namespace
}  // namespace kdrt::rtlbench

int main(int argc, char** argv) {
  using namespace kdrt::rtlbench;
  Verilated::commandArgs(argc, argv);
  const uint64_t randoms = LongRun() ? 10000000 : 200000;
  // N must match the verilated parameters (tests/rtl/CMakeLists.txt).
  bool ok = Run<Vrt_prio_enc_n1>(1, "words", randoms);
  ok = Run<Vrt_prio_enc_n2>(2, "words", randoms) && ok;
  ok = Run<Vrt_prio_enc_n3>(3, "words", randoms) && ok;
  ok = Run<Vrt_prio_enc_n5>(5, "words", randoms) && ok;
  ok = Run<Vrt_prio_enc_n32>(32, "words", randoms) && ok;
  ok = Run<Vrt_prio_enc_n128>(128, "words", randoms) && ok;
  ok = Run<Vrt_prio_enc_n1_tree>(1, "tree", randoms) && ok;
  ok = Run<Vrt_prio_enc_n2_tree>(2, "tree", randoms) && ok;
  ok = Run<Vrt_prio_enc_n3_tree>(3, "tree", randoms) && ok;
  ok = Run<Vrt_prio_enc_n5_tree>(5, "tree", randoms) && ok;
  ok = Run<Vrt_prio_enc_n32_tree>(32, "tree", randoms) && ok;
  ok = Run<Vrt_prio_enc_n128_tree>(128, "tree", randoms) && ok;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
