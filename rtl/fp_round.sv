// fp_round: combinational round-to-nearest-even and pack for the (E, M)
// units. Takes an unrounded finite result 1.mant_i * 2^(exp_i - bias) plus
// the guard bit and the sticky OR of everything below it, and applies the
// policy of docs/number-formats.md: RNE, then FTZ (biased exponent <= 0 after
// rounding -> signed zero: tininess after rounding) and overflow (-> signed
// infinity). nan_i, inf_i and zero_i override the finite result (canonical
// NaN, +-inf, +-0 with sign_i).
`default_nettype none

module fp_round #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23,
  parameter int unsigned ExpW = kdrt_fp_pkg::FpExpW
) (
  input  logic                   sign_i,
  input  logic signed [ExpW-1:0] exp_i,     // biased exponent of the hidden bit
  input  logic        [M-1:0]    mant_i,    // fraction bits after the hidden bit
  input  logic                   guard_i,   // first bit below mant_i[0]
  input  logic                   sticky_i,  // OR of all bits below guard_i
  input  logic                   nan_i,
  input  logic                   inf_i,
  input  logic                   zero_i,
  output logic        [E+M:0]    res_o
);

  localparam logic [E-1:0] ExpOnes = {E{1'b1}};

  logic                   round_up;
  logic        [M:0]      mant_inc;
  logic signed [ExpW-1:0] exp_rnd;

  assign round_up = guard_i & (sticky_i | mant_i[0]);
  assign mant_inc = {1'b0, mant_i} + {{M{1'b0}}, round_up};
  // A carry out of the fraction leaves it all zeros and bumps the exponent.
  assign exp_rnd  = exp_i + ExpW'(mant_inc[M]);

  always_comb begin
    if (nan_i) begin
      res_o = {1'b0, ExpOnes, 1'b1, {(M-1){1'b0}}};
    end else if (inf_i) begin
      res_o = {sign_i, ExpOnes, {M{1'b0}}};
    end else if (zero_i || exp_rnd <= 0) begin
      res_o = {sign_i, {(E+M){1'b0}}};
    end else if (exp_rnd >= ExpW'(signed'({1'b0, ExpOnes}))) begin
      res_o = {sign_i, ExpOnes, {M{1'b0}}};
    end else begin
      res_o = {sign_i, exp_rnd[E-1:0], mant_inc[M-1:0]};
    end
  end

endmodule

`default_nettype wire
