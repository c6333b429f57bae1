// fp_add: pipelined (E, M) adder/subtracter, res = a + (sub_i ? -b : b).
//
// Bit-identical to kdrt::fp::Add/Sub (sw/fp/format.h): round to nearest
// even, subnormal operands read as zeros (DAZ), tiny results flushed to zero
// after rounding (FTZ), overflow to infinity, canonical NaN, exact zero sums
// +0 except (-0) + (-0) = -0.
//
// Interface: operands a_i, b_i and sub_i are sampled with valid_i when en_i is
// high; res_o/valid_o appear Latency = kdrt_fp_pkg::FpAddLatency (4) enabled
// cycles later. en_i low freezes the whole pipeline (all stage registers and
// valid bits hold), so a surrounding valid/ready pipeline can stall it. Data
// registers are not reset; only the valid bits are.
//
// Stages: 1 unpack, magnitude compare and swap, exponent difference;
//         2 alignment shift with sticky, significand add/subtract;
//         3 leading-zero count and normalising shift;
//         4 round, FTZ/overflow, pack.
`default_nettype none

module fp_add #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  input  logic         sub_i,
  output logic         valid_o,
  output logic [E+M:0] res_o
);

  /* verilator lint_off UNUSEDPARAM */
  localparam int unsigned Latency = kdrt_fp_pkg::FpAddLatency;
  /* verilator lint_on UNUSEDPARAM */
  localparam int unsigned ExpW = kdrt_fp_pkg::FpExpW;
  // Significand with three extra bits (guard, round, sticky) and a carry bit.
  localparam int unsigned SigW = M + 4;
  localparam int unsigned SumW = M + 5;
  localparam int unsigned ShW = $clog2(SigW + 1);
  localparam int unsigned LzW = $clog2(SumW + 1);
  localparam logic [E-1:0] ExpOnes = {E{1'b1}};

  // ---------------------------------------------------------------- stage 1
  logic         sa, sb;
  logic [E-1:0] ea, eb;
  logic [M-1:0] fa, fb;
  logic         a_zero, b_zero, a_inf, b_inf, a_nan, b_nan;
  logic         swap;

  assign sa = a_i[E+M];
  assign sb = b_i[E+M] ^ sub_i;
  assign ea = a_i[E+M-1:M];
  assign eb = b_i[E+M-1:M];
  assign fa = a_i[M-1:0];
  assign fb = b_i[M-1:0];
  assign a_zero = (ea == '0);  // DAZ
  assign b_zero = (eb == '0);
  assign a_inf = (ea == ExpOnes) && (fa == '0);
  assign b_inf = (eb == ExpOnes) && (fb == '0);
  assign a_nan = (ea == ExpOnes) && (fa != '0);
  assign b_nan = (eb == ExpOnes) && (fb != '0);
  // Zeros compare as magnitude 0 whatever their (subnormal) fraction.
  assign swap = (b_zero ? '0 : {eb, fb}) > (a_zero ? '0 : {ea, fa});

  logic         s1_sx_d, s1_sy_d;
  logic [E-1:0] s1_ex_d;
  logic [M:0]   s1_mx_d, s1_my_d;
  logic [ShW-1:0] s1_shift_d;
  logic         s1_nan_d, s1_inf_d, s1_inf_sign_d;
  logic [E-1:0] diff;

  assign s1_sx_d = swap ? sb : sa;
  assign s1_sy_d = swap ? sa : sb;
  assign s1_ex_d = swap ? eb : ea;
  assign s1_mx_d = swap ? (b_zero ? '0 : {1'b1, fb}) : (a_zero ? '0 : {1'b1, fa});
  assign s1_my_d = swap ? (a_zero ? '0 : {1'b1, fa}) : (b_zero ? '0 : {1'b1, fb});
  assign diff = swap ? eb - ea : ea - eb;
  // Shifting by SigW or more moves everything into the sticky bit.
  assign s1_shift_d = (32'(diff) >= SigW) ? ShW'(SigW) : ShW'(diff);
  assign s1_nan_d = a_nan || b_nan || (a_inf && b_inf && (sa != sb));
  assign s1_inf_d = a_inf || b_inf;
  assign s1_inf_sign_d = a_inf ? sa : sb;

  logic         s1_valid_q, s1_sx_q, s1_sy_q, s1_nan_q, s1_inf_q, s1_inf_sign_q;
  logic [E-1:0] s1_ex_q;
  logic [M:0]   s1_mx_q, s1_my_q;
  logic [ShW-1:0] s1_shift_q;

  // ---------------------------------------------------------------- stage 2
  logic [2*SigW-1:0] y_wide;
  logic [SigW-1:0]   y_aligned;
  logic [SumW-1:0]   s2_sum_d;

  assign y_wide = {s1_my_q, 3'b000, {SigW{1'b0}}} >> s1_shift_q;
  assign y_aligned = {y_wide[2*SigW-1:SigW+1], y_wide[SigW] | (|y_wide[SigW-1:0])};
  assign s2_sum_d = (s1_sx_q != s1_sy_q)
                  ? {1'b0, s1_mx_q, 3'b000} - {1'b0, y_aligned}
                  : {1'b0, s1_mx_q, 3'b000} + {1'b0, y_aligned};

  logic            s2_valid_q, s2_sx_q, s2_zero_sign_q, s2_nan_q, s2_inf_q, s2_inf_sign_q;
  logic [E-1:0]    s2_ex_q;
  logic [SumW-1:0] s2_sum_q;

  // ---------------------------------------------------------------- stage 3
  logic [LzW-1:0]  lz;
  logic [SumW-1:0] s3_norm_d;
  logic signed [ExpW-1:0] s3_exp_d;

  always_comb begin
    lz = LzW'(SumW);
    for (int i = 0; i < SumW; i++) begin
      if (s2_sum_q[i]) lz = LzW'(SumW - 1 - i);
    end
  end
  assign s3_norm_d = s2_sum_q << lz;
  // The sum's hidden-bit position is one above the operands' (carry bit).
  assign s3_exp_d = signed'(ExpW'(s2_ex_q)) + 1 - signed'(ExpW'(lz));

  logic            s3_valid_q, s3_sign_q, s3_zero_q, s3_nan_q, s3_inf_q;
  logic [SumW-1:0] s3_norm_q;
  logic signed [ExpW-1:0] s3_exp_q;

  // ---------------------------------------------------------------- stage 4
  logic [E+M:0] s4_res_d;
  logic         unused_hidden;

  assign unused_hidden = s3_norm_q[SumW-1];  // 1 unless the sum is zero

  fp_round #(
    .E   (E),
    .M   (M),
    .ExpW(ExpW)
  ) u_round (
    .sign_i  (s3_sign_q),
    .exp_i   (s3_exp_q),
    .mant_i  (s3_norm_q[SumW-2:4]),
    .guard_i (s3_norm_q[3]),
    .sticky_i(|s3_norm_q[2:0]),
    .nan_i   (s3_nan_q),
    .inf_i   (s3_inf_q),
    .zero_i  (s3_zero_q),
    .res_o   (s4_res_d)
  );

  logic         s4_valid_q;
  logic [E+M:0] s4_res_q;

  // --------------------------------------------------------------- registers
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_valid_q <= 1'b0;
      s2_valid_q <= 1'b0;
      s3_valid_q <= 1'b0;
      s4_valid_q <= 1'b0;
    end else if (en_i) begin
      s1_valid_q <= valid_i;
      s2_valid_q <= s1_valid_q;
      s3_valid_q <= s2_valid_q;
      s4_valid_q <= s3_valid_q;
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      s1_sx_q        <= s1_sx_d;
      s1_sy_q        <= s1_sy_d;
      s1_ex_q        <= s1_ex_d;
      s1_mx_q        <= s1_mx_d;
      s1_my_q        <= s1_my_d;
      s1_shift_q     <= s1_shift_d;
      s1_nan_q       <= s1_nan_d;
      s1_inf_q       <= s1_inf_d;
      s1_inf_sign_q  <= s1_inf_sign_d;

      s2_sx_q        <= s1_sx_q;
      // An exact zero sum is -0 only when both addends are negative.
      s2_zero_sign_q <= s1_sx_q & s1_sy_q;
      s2_ex_q        <= s1_ex_q;
      s2_sum_q       <= s2_sum_d;
      s2_nan_q       <= s1_nan_q;
      s2_inf_q       <= s1_inf_q;
      s2_inf_sign_q  <= s1_inf_sign_q;

      s3_zero_q      <= (s2_sum_q == '0);
      s3_sign_q      <= s2_inf_q ? s2_inf_sign_q
                      : (s2_sum_q == '0) ? s2_zero_sign_q : s2_sx_q;
      s3_norm_q      <= s3_norm_d;
      s3_exp_q       <= s3_exp_d;
      s3_nan_q       <= s2_nan_q;
      s3_inf_q       <= s2_inf_q;

      s4_res_q       <= s4_res_d;
    end
  end

  assign valid_o = s4_valid_q;
  assign res_o   = s4_res_q;

endmodule

`default_nettype wire
