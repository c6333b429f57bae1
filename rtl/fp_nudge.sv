// fp_nudge: moves a positive finite (E, M) value K encodings up and down, as
// kdrt::fp::NudgeUp/NudgeDown (sw/fp/format.h): the conservative interval
// ends of the traversal. up_o saturates at +inf; down_o is +0 where it would
// leave the normal range. Zeros, negatives and infinities pass unchanged, a
// NaN becomes the canonical NaN. Combinational: an adder on the encoding.
`default_nettype none

module fp_nudge #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23,
  parameter int unsigned K = 4
) (
  input  logic [E+M:0] a_i,
  output logic [E+M:0] up_o,
  output logic [E+M:0] down_o
);

  localparam logic [E-1:0] ExpOnes = {E{1'b1}};
  localparam logic [E+M:0] Inf = {1'b0, ExpOnes, {M{1'b0}}};
  localparam logic [E+M:0] CanonicalNaN = {1'b0, ExpOnes, 1'b1, {(M-1){1'b0}}};
  localparam logic [E+M:0] MinNormal = (E+M+1)'(1) << M;

  logic [E-1:0] exp;
  logic         nan, positive_finite;
  logic [E+M:0] up, down;

  assign exp = a_i[E+M-1:M];
  assign nan = exp == ExpOnes && a_i[M-1:0] != '0;
  assign positive_finite = !a_i[E+M] && exp != '0 && exp != ExpOnes;
  assign up = a_i + (E+M+1)'(K);
  assign down = a_i - (E+M+1)'(K);

  always_comb begin
    if (nan) begin
      up_o = CanonicalNaN;
      down_o = CanonicalNaN;
    end else if (positive_finite) begin
      // Positive encodings are ordered like their values, and the largest
      // finite one plus K cannot carry past the sign bit.
      up_o = (up >= Inf) ? Inf : up;
      down_o = (a_i < MinNormal + (E+M+1)'(K)) ? '0 : down;
    end else begin
      up_o = a_i;
      down_o = a_i;
    end
  end

endmodule

`default_nettype wire
