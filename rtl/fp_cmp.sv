// fp_cmp: (E, M) comparisons and min/max.
//
// Bit-identical to kdrt::fp::Lt/Le/Eq/Min/Max (sw/fp/format.h):
//   lt_o, le_o, eq_o: IEEE 754 (false when either operand is NaN, -0 == +0,
//                     subnormal operands read as zeros);
//   min_o, max_o:     canonical NaN if either operand is NaN; otherwise the
//                     smaller/larger operand with subnormals flushed to a zero
//                     of the same sign; min(-0, +0) = -0, max(-0, +0) = +0.
//
// Stages = 0: purely combinational (valid_o = valid_i, en_i unused).
// Stages = 1: one register stage; outputs appear Latency = 1 enabled cycle
// later, en_i low holds it. Only the valid bit is reset.
`default_nettype none

module fp_cmp #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23,
  parameter int unsigned Stages = 1
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [E+M:0] a_i,
  input  logic [E+M:0] b_i,
  output logic         valid_o,
  output logic         lt_o,
  output logic         le_o,
  output logic         eq_o,
  output logic [E+M:0] min_o,
  output logic [E+M:0] max_o
);

  /* verilator lint_off UNUSEDPARAM */
  localparam int unsigned Latency = Stages;
  /* verilator lint_on UNUSEDPARAM */
  localparam logic [E-1:0] ExpOnes = {E{1'b1}};
  localparam logic [E+M:0] CanonicalNaN = {1'b0, ExpOnes, 1'b1, {(M-1){1'b0}}};

  logic         sa, sb, a_nan, b_nan, any_nan;
  logic [E+M:0] ac, bc;      // operands with subnormals flushed
  logic [E+M-1:0] mag_a, mag_b;
  logic         mag_lt, mag_gt, same, lt, eq;
  logic         lt_d, le_d, eq_d;
  logic [E+M:0] min_d, max_d;

  assign sa = a_i[E+M];
  assign sb = b_i[E+M];
  assign a_nan = (a_i[E+M-1:M] == ExpOnes) && (a_i[M-1:0] != '0);
  assign b_nan = (b_i[E+M-1:M] == ExpOnes) && (b_i[M-1:0] != '0);
  assign any_nan = a_nan || b_nan;
  assign ac = (a_i[E+M-1:M] == '0) ? {sa, {(E+M){1'b0}}} : a_i;
  assign bc = (b_i[E+M-1:M] == '0) ? {sb, {(E+M){1'b0}}} : b_i;
  assign mag_a = ac[E+M-1:0];
  assign mag_b = bc[E+M-1:0];
  assign mag_lt = mag_a < mag_b;
  assign mag_gt = mag_a > mag_b;
  // Equal values: identical encodings, or two zeros of any signs.
  assign same = (ac == bc) || ((mag_a == '0) && (mag_b == '0));

  always_comb begin
    unique case ({sa, sb})
      2'b00:   lt = mag_lt;
      2'b11:   lt = mag_gt;
      2'b10:   lt = !same;  // negative < positive unless both are zeros
      default: lt = 1'b0;
    endcase
  end
  assign eq = same;

  assign lt_d  = !any_nan && lt;
  assign eq_d  = !any_nan && eq;
  assign le_d  = !any_nan && (lt || eq);
  // On equality the encodings differ at most in the sign of a zero: OR takes
  // -0 for min, AND takes +0 for max.
  assign min_d = any_nan ? CanonicalNaN : lt ? ac : eq ? (ac | bc) : bc;
  assign max_d = any_nan ? CanonicalNaN : lt ? bc : eq ? (ac & bc) : ac;

  if (Stages == 0) begin : g_comb
    logic unused_clk;
    assign unused_clk = clk_i ^ rst_ni ^ en_i;
    assign valid_o = valid_i;
    assign lt_o    = lt_d;
    assign le_o    = le_d;
    assign eq_o    = eq_d;
    assign min_o   = min_d;
    assign max_o   = max_d;
  end else begin : g_reg
    logic         valid_q, lt_q, le_q, eq_q;
    logic [E+M:0] min_q, max_q;

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        valid_q <= 1'b0;
      end else if (en_i) begin
        valid_q <= valid_i;
      end
    end

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        lt_q  <= lt_d;
        le_q  <= le_d;
        eq_q  <= eq_d;
        min_q <= min_d;
        max_q <= max_d;
      end
    end

    assign valid_o = valid_q;
    assign lt_o    = lt_q;
    assign le_o    = le_q;
    assign eq_o    = eq_q;
    assign min_o   = min_q;
    assign max_o   = max_q;
  end

endmodule

`default_nettype wire
