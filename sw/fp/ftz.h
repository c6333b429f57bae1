// RAII guard that sets flush-to-zero and denormals-are-zero (and round to
// nearest) in the SSE control register for the calling thread, and restores
// the previous state on exit. NativeF32Arith needs it: with it, native float
// arithmetic is bit-identical to SoftArith(kFp32). MXCSR is per thread, so
// every worker thread needs its own guard.
#pragma once

#if defined(__SSE__) || defined(_M_X64)
#include <xmmintrin.h>
#define KDRT_HAVE_MXCSR 1
#else
#define KDRT_HAVE_MXCSR 0
#endif

namespace kdrt::fp {

class ScopedFtzDaz {
 public:
#if KDRT_HAVE_MXCSR
  static constexpr unsigned kFtz = 0x8000u;          // MXCSR bit 15
  static constexpr unsigned kDaz = 0x0040u;          // MXCSR bit 6
  static constexpr unsigned kRoundingMask = 0x6000u;  // bits 13-14; 0 = nearest
  ScopedFtzDaz() : saved_(_mm_getcsr()) { _mm_setcsr((saved_ & ~kRoundingMask) | kFtz | kDaz); }
  ~ScopedFtzDaz() { _mm_setcsr(saved_); }
#else
  // Without SSE there is no portable FTZ/DAZ switch: NativeF32Arith is then
  // not bit-exact for tiny values (tests/fp/native_test.cpp would show it).
  ScopedFtzDaz() = default;
#endif
  ScopedFtzDaz(const ScopedFtzDaz&) = delete;
  ScopedFtzDaz& operator=(const ScopedFtzDaz&) = delete;

 private:
#if KDRT_HAVE_MXCSR
  unsigned saved_;
#endif
};

// The opposite guard for NativeF64Arith: IEEE default behaviour (gradual
// underflow, FTZ and DAZ off, round to nearest) for the calling thread, so
// the double-precision reference does not inherit a caller's FTZ/DAZ.
class ScopedIeeeDefault {
 public:
#if KDRT_HAVE_MXCSR
  ScopedIeeeDefault() : saved_(_mm_getcsr()) {
    _mm_setcsr(saved_ & ~(ScopedFtzDaz::kRoundingMask | ScopedFtzDaz::kFtz | ScopedFtzDaz::kDaz));
  }
  ~ScopedIeeeDefault() { _mm_setcsr(saved_); }
#else
  ScopedIeeeDefault() = default;
#endif
  ScopedIeeeDefault(const ScopedIeeeDefault&) = delete;
  ScopedIeeeDefault& operator=(const ScopedIeeeDefault&) = delete;

 private:
#if KDRT_HAVE_MXCSR
  unsigned saved_;
#endif
};

}  // namespace kdrt::fp
