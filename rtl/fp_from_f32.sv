// fp_from_f32: converts IEEE binary32 bits (how the scene memory stores
// floats) to the (E, M) datapath format.
//
// Bit-identical to kdrt::fp::FromF32Bits (sw/fp/format.h): RNE, subnormal
// inputs read as zeros of the same sign (DAZ), tiny results flushed after
// rounding (FTZ), overflow to infinity, any NaN to the canonical NaN. For
// (E, M) = (8, 23) it only flushes subnormals and canonicalises NaNs.
//
// Interface: f32_i is sampled with valid_i when en_i is high; res_o/valid_o
// appear Latency = kdrt_fp_pkg::FpFromF32Latency (1) enabled cycle later.
// en_i low holds the register. Only the valid bit is reset.
`default_nettype none

module fp_from_f32 #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         en_i,
  input  logic         valid_i,
  input  logic [31:0]  f32_i,
  output logic         valid_o,
  output logic [E+M:0] res_o
);

  /* verilator lint_off UNUSEDPARAM */
  localparam int unsigned Latency = kdrt_fp_pkg::FpFromF32Latency;
  /* verilator lint_on UNUSEDPARAM */
  localparam int unsigned ExpW = kdrt_fp_pkg::FpExpW;
  localparam int unsigned Bias = (1 << (E - 1)) - 1;

  logic [7:0]  ef;
  logic [24:0] frac;  // the 23 fraction bits and two zeros, so M = 23 needs no rounding
  logic [E+M:0] res_d;

  assign ef   = f32_i[30:23];
  assign frac = {f32_i[22:0], 2'b00};

  fp_round #(
    .E   (E),
    .M   (M),
    .ExpW(ExpW)
  ) u_round (
    .sign_i  (f32_i[31]),
    .exp_i   (signed'(ExpW'(ef)) - 127 + signed'(ExpW'(Bias))),
    .mant_i  (frac[24:25-M]),
    .guard_i (frac[24-M]),
    .sticky_i(|frac[23-M:0]),
    .nan_i   ((ef == 8'hFF) && (f32_i[22:0] != '0)),
    .inf_i   ((ef == 8'hFF) && (f32_i[22:0] == '0)),
    .zero_i  (ef == '0),  // DAZ
    .res_o   (res_d)
  );

  logic         valid_q;
  logic [E+M:0] res_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= 1'b0;
    end else if (en_i) begin
      valid_q <= valid_i;
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      res_q <= res_d;
    end
  end

  assign valid_o = valid_q;
  assign res_o   = res_q;

endmodule

`default_nettype wire
