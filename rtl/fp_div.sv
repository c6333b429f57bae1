// fp_div: fully pipelined (E, M) divider, res = a / b, correctly rounded.
// One result per enabled cycle; restoring division, one quotient bit per
// stage.
//
// Bit-identical to kdrt::fp::Div (sw/fp/format.h): RNE, DAZ, FTZ after
// rounding, overflow to infinity; x/0 = inf with the sign xor, 0/0 and
// inf/inf = canonical NaN, x/inf = signed zero.
//
// Interface: a_i, b_i are sampled with valid_i when en_i is high; res_o and
// valid_o appear Latency = M + kdrt_fp_pkg::FpDivExtraLatency (M + 4)
// enabled cycles later (fp32: 27, fp24: 20, bf16: 11, fp16: 14). en_i low
// freezes the whole pipeline. Only the valid bits are reset.
//
// Stages: 1 unpack, special cases, pre-normalisation (so the quotient of the
//           significands lies in [1, 2)), exponent difference;
//         2 .. M+3 one quotient bit each (compare, subtract, shift);
//         M+4 round (sticky = remainder non-zero), FTZ/overflow, pack.
`default_nettype none

module fp_div #(
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

  localparam int unsigned QBits = M + 2;  // hidden bit, M fraction bits, guard
  /* verilator lint_off UNUSEDPARAM */
  localparam int unsigned Latency = M + kdrt_fp_pkg::FpDivExtraLatency;
  /* verilator lint_on UNUSEDPARAM */
  localparam int unsigned ExpW = kdrt_fp_pkg::FpExpW;
  localparam int unsigned RemW = M + 2;   // remainder < 2 * divisor < 2^(M+2)
  localparam logic [E-1:0] ExpOnes = {E{1'b1}};
  localparam int unsigned Bias = (1 << (E - 1)) - 1;

  // ---------------------------------------------------------------- stage 1
  logic [E-1:0] ea, eb;
  logic [M-1:0] fa, fb;
  logic         a_zero, b_zero, a_inf, b_inf, a_nan, b_nan;
  logic         a_small;

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
  assign a_small = (fa < fb);  // then shift the dividend left by one

  // Per-stage state: index 0 is stage 1's output, index i the state after i
  // quotient bits.
  logic                   valid_q [QBits+1];
  logic                   sign_q  [QBits+1];
  logic                   nan_q   [QBits+1];
  logic                   inf_q   [QBits+1];
  logic                   zero_q  [QBits+1];
  logic signed [ExpW-1:0] exp_q   [QBits+1];
  logic [M:0]             dvs_q   [QBits+1];  // divisor significand
  logic [RemW-1:0]        rem_q   [QBits+1];
  logic [QBits-1:0]       quo_q   [QBits+1];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q[0] <= 1'b0;
    end else if (en_i) begin
      valid_q[0] <= valid_i;
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      sign_q[0] <= a_i[E+M] ^ b_i[E+M];
      nan_q[0]  <= a_nan || b_nan || (a_zero && b_zero) || (a_inf && b_inf);
      inf_q[0]  <= a_inf || b_zero;
      zero_q[0] <= a_zero || b_inf;
      exp_q[0]  <= signed'(ExpW'(ea)) - signed'(ExpW'(eb)) + signed'(ExpW'(Bias))
                 - signed'(ExpW'(a_small));
      dvs_q[0]  <= {1'b1, fb};
      rem_q[0]  <= a_small ? {1'b1, fa, 1'b0} : {1'b0, 1'b1, fa};
      quo_q[0]  <= '0;
    end
  end

  // --------------------------------------------------- stages 2 .. QBits+1
  for (genvar i = 0; i < QBits; i++) begin : g_step
    logic            ge;
    logic [RemW-1:0] diff;
    logic            unused_diff_msb;  // zero whenever ge: diff < divisor

    assign ge   = rem_q[i] >= RemW'(dvs_q[i]);
    assign diff = rem_q[i] - RemW'(dvs_q[i]);
    assign unused_diff_msb = diff[RemW-1];

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        valid_q[i+1] <= 1'b0;
      end else if (en_i) begin
        valid_q[i+1] <= valid_q[i];
      end
    end

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        sign_q[i+1] <= sign_q[i];
        nan_q[i+1]  <= nan_q[i];
        inf_q[i+1]  <= inf_q[i];
        zero_q[i+1] <= zero_q[i];
        exp_q[i+1]  <= exp_q[i];
        dvs_q[i+1]  <= dvs_q[i];
        // The partial remainder stays below twice the divisor, so the shift
        // loses nothing.
        rem_q[i+1]  <= {(ge ? diff[RemW-2:0] : rem_q[i][RemW-2:0]), 1'b0};
        quo_q[i+1]  <= {quo_q[i][QBits-2:0], ge};
      end
    end
  end

  // ---------------------------------------------------------- last stage
  logic [E+M:0] res_d;
  logic [M:0]   unused_dvs;
  logic         unused_hidden;

  assign unused_dvs    = dvs_q[QBits];
  assign unused_hidden = quo_q[QBits][QBits-1];  // always 1

  fp_round #(
    .E   (E),
    .M   (M),
    .ExpW(ExpW)
  ) u_round (
    .sign_i  (sign_q[QBits]),
    .exp_i   (exp_q[QBits]),
    .mant_i  (quo_q[QBits][M:1]),
    .guard_i (quo_q[QBits][0]),
    .sticky_i(rem_q[QBits] != '0),
    .nan_i   (nan_q[QBits]),
    .inf_i   (inf_q[QBits]),
    .zero_i  (zero_q[QBits]),
    .res_o   (res_d)
  );

  logic         valid_out_q;
  logic [E+M:0] res_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_out_q <= 1'b0;
    end else if (en_i) begin
      valid_out_q <= valid_q[QBits];
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      res_q <= res_d;
    end
  end

  assign valid_o = valid_out_q;
  assign res_o   = res_q;

endmodule

`default_nettype wire
