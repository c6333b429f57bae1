// fp_ldexp: a_i * 2^n_i in an (E, M) format, as kdrt::fp::Ldexp
// (sw/fp/format.h): exact, except that a result below the normal range is a
// signed zero (FTZ) and one above it an infinity; a subnormal input is a
// zero (DAZ), zeros and infinities pass, a NaN becomes the canonical NaN.
// Combinational: one adder on the exponent. The frame mapping of the ray
// setup and the hit distance's way back to world units use it in fp32
// (docs/dataflow.md, step 0).
`default_nettype none

module fp_ldexp #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23,
  // Width of the signed shift n_i.
  parameter int unsigned NW = 10
) (
  input  logic [E+M:0]        a_i,
  input  logic signed [NW-1:0] n_i,
  output logic [E+M:0]        y_o
);

  localparam int unsigned SW = (E > NW ? E : NW) + 2;  // signed sum, no overflow
  localparam logic [E-1:0] ExpOnes = {E{1'b1}};
  localparam logic [E+M:0] CanonicalNaN = {1'b0, ExpOnes, 1'b1, {(M-1){1'b0}}};

  logic         sign;
  logic [E-1:0] exp;
  logic [M-1:0] mant;
  logic signed [SW-1:0] sum;

  assign {sign, exp, mant} = a_i;
  assign sum = $signed({{(SW-E){1'b0}}, exp}) + SW'(n_i);

  always_comb begin
    if (exp == ExpOnes) begin
      y_o = (mant != '0) ? CanonicalNaN : a_i;
    end else if (exp == '0 || sum <= 0) begin
      y_o = {sign, {(E+M){1'b0}}};
    end else if (sum >= $signed({{(SW-E){1'b0}}, ExpOnes})) begin
      y_o = {sign, ExpOnes, {M{1'b0}}};
    end else begin
      y_o = {sign, sum[E-1:0], mant};
    end
  end

endmodule

`default_nettype wire
