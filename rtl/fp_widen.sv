// fp_widen: exact widening of an (E, M) value to a wider (WE, WM) format
// (WE >= E, WM >= M), as the model's at.Load(ai.Store(x)) (Widen in
// sw/trace/traversal.h): zeros (and subnormal encodings, read as zeros) keep
// their sign, infinities stay infinities, any NaN becomes the wide format's
// canonical NaN. Every (E, M) value is a normal of the wide format, so no
// rounding is involved. Combinational: a rebias and a shift; a wire when the
// formats are the same (a unit whose traversal is its own format instantiates
// it all the same, and keeps exactly its one-format hardware).
`default_nettype none

module fp_widen #(
  parameter int unsigned E = 5,
  parameter int unsigned M = 10,
  parameter int unsigned WE = 8,
  parameter int unsigned WM = 23
) (
  input  logic [E+M:0]   a_i,
  output logic [WE+WM:0] res_o
);

  localparam int unsigned Bias = (1 << (E - 1)) - 1;
  localparam int unsigned WBias = (1 << (WE - 1)) - 1;
  localparam logic [E-1:0] ExpOnes = {E{1'b1}};

  if (WE == E && WM == M) begin : g_same
    assign res_o = a_i;
  end else begin : g_widen
    logic         sign;
    logic [E-1:0] exp;
    logic [M-1:0] frac;
    assign sign = a_i[E+M];
    assign exp = a_i[E+M-1:M];
    assign frac = a_i[M-1:0];

    always_comb begin
      if (exp == '0) begin
        res_o = {sign, {(WE + WM){1'b0}}};
      end else if (exp == ExpOnes) begin
        res_o = (frac == '0) ? {sign, {WE{1'b1}}, {WM{1'b0}}} : {1'b0, {WE{1'b1}}, 1'b1, {(WM-1){1'b0}}};
      end else begin
        // Rebias: exp - Bias + WBias, in range because WE >= E.
        res_o = {sign, WE'(32'(exp) + 32'(WBias) - 32'(Bias)), WM'(frac) << (WM - M)};
      end
    end
  end

endmodule

`default_nettype wire
