// fp_mul: pipelined (E, M) multiplier, res = a * b.
//
// Bit-identical to kdrt::fp::Mul (sw/fp/format.h): RNE, DAZ, FTZ after
// rounding, overflow to infinity, canonical NaN (NaN operand, 0 * inf).
//
// Interface: a_i, b_i are sampled with valid_i when en_i is high; res_o and
// valid_o appear Latency = kdrt_fp_pkg::FpMulLatency (3) enabled cycles
// later. en_i low freezes the whole pipeline. Only the valid bits are reset.
//
// Stages: 1 unpack, special cases, exponent sum;
//         2 (M+1) x (M+1) significand product;
//         3 one-bit normalisation, round, FTZ/overflow, pack.
`default_nettype none

module fp_mul #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  output logic         valid_o,
  output logic [E+M:0] res_o
);

  /* verilator lint_off UNUSEDPARAM */
  localparam int unsigned Latency = kdrt_fp_pkg::FpMulLatency;
  /* verilator lint_on UNUSEDPARAM */
  localparam int unsigned ExpW = kdrt_fp_pkg::FpExpW;
  localparam int unsigned ProdW = 2 * M + 2;
  localparam logic [E-1:0] ExpOnes = {E{1'b1}};
  localparam int unsigned Bias = (1 << (E - 1)) - 1;

  // ---------------------------------------------------------------- stage 1
  logic [E-1:0] ea, eb;
  logic [M-1:0] fa, fb;
  logic         a_zero, b_zero, a_inf, b_inf, a_nan, b_nan;

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

  logic         s1_valid_q, s1_sign_q, s1_nan_q, s1_inf_q, s1_zero_q;
  logic [M:0]   s1_ma_q, s1_mb_q;
  logic signed [ExpW-1:0] s1_exp_q;

  // ---------------------------------------------------------------- stage 2
  logic             s2_valid_q, s2_sign_q, s2_nan_q, s2_inf_q, s2_zero_q;
  logic [ProdW-1:0] s2_prod_q;
  logic signed [ExpW-1:0] s2_exp_q;

  // ---------------------------------------------------------------- stage 3
  // The product of two significands in [1, 2) lies in [1, 4).
  logic             top;
  logic [ProdW-1:0] norm;
  logic [E+M:0]     s3_res_d;
  logic             unused_hidden;

  assign top  = s2_prod_q[ProdW-1];
  assign norm = top ? s2_prod_q : {s2_prod_q[ProdW-2:0], 1'b0};
  assign unused_hidden = norm[ProdW-1];

  fp_round #(
    .E   (E),
    .M   (M),
    .ExpW(ExpW)
  ) u_round (
    .sign_i  (s2_sign_q),
    .exp_i   (s2_exp_q + ExpW'(top)),
    .mant_i  (norm[ProdW-2:M+1]),
    .guard_i (norm[M]),
    .sticky_i(|norm[M-1:0]),
    .nan_i   (s2_nan_q),
    .inf_i   (s2_inf_q),
    .zero_i  (s2_zero_q),
    .res_o   (s3_res_d)
  );

  logic         s3_valid_q;
  logic [E+M:0] s3_res_q;

  // --------------------------------------------------------------- registers
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_valid_q <= 1'b0;
      s2_valid_q <= 1'b0;
      s3_valid_q <= 1'b0;
    end else if (en_i) begin
      s1_valid_q <= valid_i;
      s2_valid_q <= s1_valid_q;
      s3_valid_q <= s2_valid_q;
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      s1_sign_q <= a_i[E+M] ^ b_i[E+M];
      s1_nan_q  <= a_nan || b_nan || (a_inf && b_zero) || (a_zero && b_inf);
      s1_inf_q  <= a_inf || b_inf;
      s1_zero_q <= a_zero || b_zero;
      s1_ma_q   <= {1'b1, fa};
      s1_mb_q   <= {1'b1, fb};
      s1_exp_q  <= signed'(ExpW'(ea)) + signed'(ExpW'(eb)) - signed'(ExpW'(Bias));

      s2_sign_q <= s1_sign_q;
      s2_nan_q  <= s1_nan_q;
      s2_inf_q  <= s1_inf_q;
      s2_zero_q <= s1_zero_q;
      s2_prod_q <= ProdW'(s1_ma_q) * ProdW'(s1_mb_q);
      s2_exp_q  <= s1_exp_q;

      s3_res_q  <= s3_res_d;
    end
  end

  assign valid_o = s3_valid_q;
  assign res_o   = s3_res_q;

endmodule

`default_nettype wire
