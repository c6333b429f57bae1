// fp_round_out: a wide (WE, WM) interval end moved outwards into the narrow
// (E, M) format, as the model's WidenForTest (sw/trace/traversal.h): rounded
// to nearest (fp_from_f32, via the exact binary32 hub), one encoding further
// out if that rounding went inwards, then nudged out by K encodings
// (fp_nudge; Up: towards +inf, else towards 0, with fp_nudge's rules for
// zeros, negatives, infinities and NaNs). The result is an (E, M) value, so
// a traversal wider than the triangle test keeps its intervals and stack in
// the test's width. Requires WE <= 8 (the binary32 hub).
// Latency = kdrt_fp_pkg::FpFromF32Latency enabled cycles, like fp_from_f32.
`default_nettype none
// Unused outputs of fp_cmp and fp_nudge are left open on purpose.
/* verilator lint_off PINCONNECTEMPTY */

module fp_round_out #(
  parameter int unsigned E = 5,
  parameter int unsigned M = 10,
  parameter int unsigned WE = 8,
  parameter int unsigned WM = 23,
  parameter bit Up = 1'b1,
  parameter int unsigned K = 1  // kTestSlackUlps (sw/trace/traversal.h)
) (
  input  logic           clk_i,
  input  logic           rst_ni,
  input  logic           en_i,
  input  logic           valid_i,
  input  logic [WE+WM:0] a_i,
  output logic           valid_o,
  output logic [E+M:0]   res_o
);

  logic [31:0]    a_f32;
  logic [E+M:0]   nearest;
  logic [WE+WM:0] a_q, back;
  fp_to_f32 #(.E(WE), .M(WM)) u_hub (.a_i, .f32_o(a_f32));
  fp_from_f32 #(.E(E), .M(M)) u_round (
    .clk_i, .rst_ni, .en_i, .valid_i, .f32_i(a_f32), .valid_o, .res_o(nearest)
  );
  rt_delay #(.Width(WE + WM + 1), .Depth(kdrt_fp_pkg::FpFromF32Latency)) u_a (
    .clk_i, .en_i, .d_i(a_i), .q_o(a_q)
  );

  // Did rounding to nearest move the value inwards (below a for Up, above
  // it otherwise)?
  logic inwards;
  fp_widen #(.E(E), .M(M), .WE(WE), .WM(WM)) u_back (.a_i(nearest), .res_o(back));
  fp_cmp #(.E(WE), .M(WM), .Stages(0)) u_cmp (
    .clk_i, .rst_ni, .en_i, .valid_i(1'b1), .a_i(Up ? back : a_q), .b_i(Up ? a_q : back),
    .valid_o(), .lt_o(inwards), .le_o(), .eq_o(), .min_o(), .max_o()
  );

  // nudge(nudge(r, 1), K) == nudge(r, K + 1) under fp_nudge's rules (both
  // saturate at +inf and give +0 below the normal range), so both candidates
  // come from the rounded value in parallel with the comparison, and the
  // comparison only selects: one nudge on the path after the register.
  logic [E+M:0] k_up, k_down, k1_up, k1_down;
  fp_nudge #(.E(E), .M(M), .K(K)) u_slack (.a_i(nearest), .up_o(k_up), .down_o(k_down));
  fp_nudge #(.E(E), .M(M), .K(K + 1)) u_slack_step (.a_i(nearest), .up_o(k1_up), .down_o(k1_down));
  assign res_o = Up ? (inwards ? k1_up : k_up) : (inwards ? k1_down : k_down);

endmodule

`default_nettype wire
