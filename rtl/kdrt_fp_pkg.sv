// Shared constants of the (E, M) floating-point units (rtl/fp_*.sv).
// The format, rounding and exception policy are described in
// docs/number-formats.md and modelled bit for bit by sw/fp/format.h.
//
// A surrounding pipeline that keeps tags in a parallel delay line takes the
// depth of that line from here (each unit's localparam Latency equals these).
`default_nettype none

package kdrt_fp_pkg;

  // Width of the signed internal exponent: holds every biased exponent that
  // an add, mul or div of E <= 8 operands produces before the FTZ/overflow
  // check (-127 .. 509).
  localparam int unsigned FpExpW = 11;

  localparam int unsigned FpAddLatency     = 4;
  localparam int unsigned FpMulLatency     = 3;
  localparam int unsigned FpFromF32Latency = 1;
  // fp_div: one stage to unpack, M + 2 quotient-bit stages, one to round.
  localparam int unsigned FpDivExtraLatency = 4;
  // fp_div's Latency is M + FpDivExtraLatency (Yosys 0.23 has no functions
  // in packages, so there is no helper function).

endpackage

`default_nettype wire
