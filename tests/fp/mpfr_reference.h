// An independent reference for the (E, M) arithmetic: MPFR computes the
// correctly rounded result at precision M+1 with MPFR's huge exponent range
// (no subnormals), then this file applies the FTZ/overflow rule and encodes
// it. Nothing here calls the model in sw/fp; decoding and encoding are
// written again from the format definition.
#pragma once

#include <mpfr.h>

#include <cstdint>
#include <string>

#include "fp/format.h"
#include "tests/fp/fp_vectors.h"

namespace kdrt::fp::test {

enum class Op { kAdd, kSub, kMul, kDiv, kMin, kMax, kLt, kLe, kEq };

inline const char* OpName(Op op) {
  switch (op) {
    case Op::kAdd: return "add";
    case Op::kSub: return "sub";
    case Op::kMul: return "mul";
    case Op::kDiv: return "div";
    case Op::kMin: return "min";
    case Op::kMax: return "max";
    case Op::kLt: return "lt";
    case Op::kLe: return "le";
    case Op::kEq: return "eq";
  }
  return "?";
}

inline bool IsPredicate(Op op) { return op == Op::kLt || op == Op::kLe || op == Op::kEq; }

class MpfrReference {
 public:
  explicit MpfrReference(Format f) : f_(f) {
    mpfr_inits2(64, a_, b_, r_, t_, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_prec(r_, f.m + 1);
  }
  ~MpfrReference() { mpfr_clears(a_, b_, r_, t_, static_cast<mpfr_ptr>(nullptr)); }
  MpfrReference(const MpfrReference&) = delete;
  MpfrReference& operator=(const MpfrReference&) = delete;

  // The encoded result (for predicates: 0 or 1).
  uint32_t Compute(Op op, uint32_t a, uint32_t b) {
    Decode(a, a_);
    Decode(b, b_);
    switch (op) {
      case Op::kAdd: mpfr_add(r_, a_, b_, MPFR_RNDN); return Encode(r_);
      case Op::kSub: mpfr_sub(r_, a_, b_, MPFR_RNDN); return Encode(r_);
      case Op::kMul: mpfr_mul(r_, a_, b_, MPFR_RNDN); return Encode(r_);
      case Op::kDiv: mpfr_div(r_, a_, b_, MPFR_RNDN); return Encode(r_);
      case Op::kMin:
      case Op::kMax:
        // MPFR's min/max return the other operand for one NaN (IEEE minNum);
        // our policy is NaN.
        if (mpfr_nan_p(a_) || mpfr_nan_p(b_)) return CanonicalNaN();
        if (op == Op::kMin) {
          mpfr_min(r_, a_, b_, MPFR_RNDN);  // min(-0, +0) = -0 in MPFR
        } else {
          mpfr_max(r_, a_, b_, MPFR_RNDN);
        }
        return Encode(r_);
      case Op::kLt: return mpfr_less_p(a_, b_) ? 1 : 0;
      case Op::kLe: return mpfr_lessequal_p(a_, b_) ? 1 : 0;
      case Op::kEq: return mpfr_equal_p(a_, b_) ? 1 : 0;
    }
    return 0;
  }

  // Rounds a double once to the format (for the conversion tests).
  uint32_t RoundDouble(double x) {
    mpfr_set_d(r_, x, MPFR_RNDN);
    return Encode(r_);
  }

 private:
  uint32_t CanonicalNaN() const {
    return ((1u << f_.e) - 1) << f_.m | 1u << (f_.m - 1);
  }

  void Decode(uint32_t x, mpfr_t out) const {
    const bool neg = (x >> (f_.e + f_.m)) & 1;
    const uint32_t exp = (x >> f_.m) & ((1u << f_.e) - 1);
    const uint32_t mant = x & ((1u << f_.m) - 1);
    if (exp == (1u << f_.e) - 1) {
      if (mant != 0) {
        mpfr_set_nan(out);
      } else {
        mpfr_set_inf(out, neg ? -1 : 1);
      }
    } else if (exp == 0) {
      mpfr_set_zero(out, neg ? -1 : 1);  // subnormals are zeros (DAZ)
    } else {
      const long bias = (1L << (f_.e - 1)) - 1;
      mpfr_set_ui_2exp(out, (1ul << f_.m) | mant, static_cast<long>(exp) - bias - f_.m,
                       MPFR_RNDN);  // exact: 64-bit precision
      if (neg) mpfr_neg(out, out, MPFR_RNDN);
    }
  }

  uint32_t Encode(mpfr_t x) {
    if (mpfr_nan_p(x)) return CanonicalNaN();
    const uint32_t sign = mpfr_signbit(x) ? 1u << (f_.e + f_.m) : 0u;
    const uint32_t exp_ones = (1u << f_.e) - 1;
    if (mpfr_inf_p(x)) return sign | exp_ones << f_.m;
    if (mpfr_zero_p(x)) return sign;
    const long bias = (1L << (f_.e - 1)) - 1;
    const long unbiased = mpfr_get_exp(x) - 1;  // x = 1.f * 2^unbiased
    if (unbiased < 1 - bias) return sign;                           // FTZ
    if (unbiased > bias) return sign | exp_ones << f_.m;           // overflow
    mpfr_abs(t_, x, MPFR_RNDN);
    mpfr_mul_2si(t_, t_, f_.m - unbiased, MPFR_RNDN);  // integer in [2^M, 2^(M+1))
    const uint32_t sig = static_cast<uint32_t>(mpfr_get_ui(t_, MPFR_RNDN));
    return sign | static_cast<uint32_t>(unbiased + bias) << f_.m | (sig & ((1u << f_.m) - 1));
  }

  Format f_;
  mpfr_t a_, b_, r_, t_;
};

}  // namespace kdrt::fp::test
