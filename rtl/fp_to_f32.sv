// fp_to_f32: exact widening of an (E, M) value to binary32 bits, as
// kdrt::fp::ToFloat (sw/fp/format.h): zeros (and subnormal encodings, read as
// zeros) keep their sign, infinities stay infinities, any NaN becomes
// 0x7FC00000. Combinational.
`default_nettype none

module fp_to_f32 #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23
) (
  input  logic [E+M:0] a_i,
  output logic [31:0]  f32_o
);

  localparam int unsigned Bias = (1 << (E - 1)) - 1;
  localparam logic [E-1:0] ExpOnes = {E{1'b1}};

  logic         sign;
  logic [E-1:0] exp;
  logic [M-1:0] frac;
  logic [7:0]   exp32;
  logic [22:0]  frac32;

  assign sign = a_i[E+M];
  assign exp = a_i[E+M-1:M];
  assign frac = a_i[M-1:0];
  // Rebias: exp - Bias + 127, in range because E <= 8.
  assign exp32 = 8'(32'(exp) + 32'd127 - 32'(Bias));
  assign frac32 = 23'(frac) << (23 - M);

  always_comb begin
    if (exp == '0) begin
      f32_o = {sign, 31'd0};
    end else if (exp == ExpOnes) begin
      f32_o = (frac == '0) ? {sign, 8'hFF, 23'd0} : 32'h7FC0_0000;
    end else begin
      f32_o = {sign, exp32, frac32};
    end
  end

endmodule

`default_nettype wire
