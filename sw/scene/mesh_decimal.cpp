#include "scene/mesh_decimal.h"

#include <cmath>
#include <cstdint>

#include "scene/text_fields.h"

namespace kdrt {

namespace {

bool IsDigit(char c) { return c >= '0' && c <= '9'; }

// assimp's fast_atof_table: 10^-k as double literals.
constexpr double kTenToMinus[16] = {0.0,   1e-1,  1e-2,  1e-3,  1e-4,  1e-5,  1e-6,  1e-7,
                                    1e-8,  1e-9,  1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15};

// assimp reads at most this many fraction digits and ignores the rest.
constexpr int kFractionDigits = 15;

// The whole part is read into a uint64_t, as in assimp. Where it would
// overflow, assimp returned garbage; kdrt takes the correctly rounded value.
constexpr uint64_t kMaxBeforeDigit = (UINT64_MAX - 9) / 10;

}  // namespace

template <typename Real>
bool ParseAssimpDecimal(std::string_view field, Real* value) {
  double exact;
  if (!ParseDouble(field, &exact)) return false;
  if (!std::isfinite(exact)) {  // "nan", "inf": the caller rejects them
    *value = static_cast<Real>(exact);
    return true;
  }
  // The syntax is known good from here on: [+-] digits [. digits] [e [+-] digits].
  const char* c = field.data();
  const char* const end = c + field.size();
  const bool negative = *c == '-';
  if (*c == '-' || *c == '+') ++c;

  // The three steps of assimp's fast_atoreal_move<Real>, each rounded as
  // there: the whole part to Real, the first 15 fraction digits scaled in
  // double then rounded to Real and added in Real, the exponent as a
  // multiplication by pow(Real(10), Real(e)).
  uint64_t whole = 0;
  for (; c < end && IsDigit(*c); ++c) {
    if (whole > kMaxBeforeDigit) {
      *value = static_cast<Real>(exact);
      return true;
    }
    whole = whole * 10 + (*c - '0');
  }
  Real f = static_cast<Real>(whole);
  if (c < end && *c == '.') ++c;
  uint64_t fraction = 0;
  int fraction_digits = 0;
  for (; c < end && IsDigit(*c); ++c) {
    if (fraction_digits < kFractionDigits) {
      fraction = fraction * 10 + (*c - '0');
      ++fraction_digits;
    }
  }
  if (fraction_digits > 0) {
    f += static_cast<Real>(static_cast<double>(fraction) * kTenToMinus[fraction_digits]);
  }
  if (c < end && (*c == 'e' || *c == 'E')) {
    ++c;
    const bool exp_negative = *c == '-';
    if (*c == '-' || *c == '+') ++c;
    uint64_t e = 0;
    // Saturates: any exponent this large makes pow() infinite anyway (and
    // 0e50 NaN, as in assimp, which the caller then rejects).
    for (; c < end && IsDigit(*c); ++c) {
      if (e < 1000000) e = e * 10 + (*c - '0');
    }
    Real exponent = static_cast<Real>(e);
    if (exp_negative) exponent = -exponent;
    f *= std::pow(static_cast<Real>(10), exponent);
  }
  *value = negative ? -f : f;
  return true;
}

template bool ParseAssimpDecimal<float>(std::string_view field, float* value);
template bool ParseAssimpDecimal<double>(std::string_view field, double* value);

}  // namespace kdrt
