// rt_ray_setup: the per-ray precomputation, pipelined, one ray per cycle.
//
// Exactly the model's operations (sw/trace/intersect.h SetupRay,
// docs/dataflow.md section 1) in the (E, M) format:
//   o[i] = load(ray.o[i]); d[i] = load(ray.d[i]); inv_d[i] = 1 / d[i]
//   tmin = load(ray.tmin); tmax = load(ray.tmax)
//   kz = 0; if |d[kz]| < |d[1]|: kz = 1; if |d[kz]| < |d[2]|: kz = 2
//   kx = (kz + 1) mod 3; ky = (kx + 1) mod 3; if sign(d[kz]): swap(kx, ky)
//   sx = d[kx] / d[kz]; sy = d[ky] / d[kz]; sz = 1 / d[kz]
// The two comparisons of the kz rule are made as three in parallel:
// |d0| < |d1|, |d0| < |d2| and |d1| < |d2|; the second one the model makes is
// the second or the third, chosen by the first, so the outcome is the same.
// |x| clears the sign bit; the model's Abs also turns a NaN into the canonical
// NaN, which a comparison cannot tell apart (both compare false).
//
// Stages: 1 load (fp_from_f32); 2 the three comparisons, the reciprocals
// start; 3 the axis choice and operand select, the three divisions start;
// outputs after Latency = 2 + M + FpDivExtraLatency enabled cycles
// (fp32 29, fp24 22, bf16 13, fp16 16). Flow control as rt_isect_unit: a
// global stall with en = !out_valid_o || out_ready_i = in_ready_o.
`default_nettype none

module rt_ray_setup #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23,
  parameter int unsigned TagWidth = 8,
  localparam int unsigned W = E + M + 1
) (
  input  logic                clk_i,
  input  logic                rst_ni,

  input  logic                in_valid_i,
  output logic                in_ready_o,
  input  logic [TagWidth-1:0] in_tag_i,
  // fp32 words in the order of a KDRTRAYS record: o.x in [31:0], o.y, o.z,
  // d.x, d.y, d.z, tmin, tmax in [255:224].
  input  logic [255:0]        in_ray_i,

  output logic                out_valid_o,
  input  logic                out_ready_i,
  output logic [TagWidth-1:0] out_tag_o,
  output logic [3*W-1:0]      out_o_o,    // (E, M) format, x in [W-1:0]
  output logic [3*W-1:0]      out_d_o,
  output logic [3*W-1:0]      out_inv_o,  // 1 / d
  output logic [W-1:0]        out_tmin_o,
  output logic [W-1:0]        out_tmax_o,
  output logic [1:0]          out_kx_o,
  output logic [1:0]          out_ky_o,
  output logic [1:0]          out_kz_o,
  output logic [W-1:0]        out_sx_o,
  output logic [W-1:0]        out_sy_o,
  output logic [W-1:0]        out_sz_o
);

  // The fp units' own valid_o and unused comparison outputs stay open: one
  // valid chain serves the schedule.
  /* verilator lint_off PINCONNECTEMPTY */

  localparam int unsigned LConv = kdrt_fp_pkg::FpFromF32Latency;
  localparam int unsigned LDiv  = M + kdrt_fp_pkg::FpDivExtraLatency;
  localparam int unsigned LCmp  = 1;
  localparam int unsigned TCmp  = LConv;          // comparisons, 1 / d[i]
  localparam int unsigned TAxis = TCmp + LCmp;    // axis choice, the shear divisions
  localparam int unsigned Latency = TAxis + LDiv;

  localparam logic [W-1:0] One = {2'b00, {(E-1){1'b1}}, {M{1'b0}}};

  logic en;
  assign en = !out_valid_o || out_ready_i;
  assign in_ready_o = en;

  logic [Latency:1] vld_q;
  logic [Latency:0] vld;
  assign vld = {vld_q, in_valid_i};
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      vld_q <= '0;
    end else if (en) begin
      vld_q <= vld[Latency-1:0];
    end
  end
  assign out_valid_o = vld[Latency];

  // ------------------------------------------------ load
  // Words 0..2: o, 3..5: d, 6: tmin, 7: tmax.
  // Value arrays are flat vectors of W-bit words (word i at [W*i +: W]).
  logic [255:0] raw;
  logic [8*W-1:0] val;
  assign raw = in_ray_i;
  for (genvar j = 0; j < 8; j++) begin : g_load
    fp_from_f32 #(.E(E), .M(M)) u_load (
      .clk_i, .rst_ni, .en_i(en), .valid_i(vld[0]), .f32_i(raw[32*j +: 32]),
      .valid_o(), .res_o(val[W*j +: W])
    );
  end

  // ------------------------------------------------ 1 / d, comparisons
  logic [3*W-1:0] inv;
  logic [3*W-1:0] abs_d;
  for (genvar i = 0; i < 3; i++) begin : g_inv
    fp_div #(.E(E), .M(M)) u_div (
      .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TCmp]), .a_i(One), .b_i(val[W*(3+i) +: W]),
      .valid_o(), .res_o(inv[W*i +: W])
    );
    assign abs_d[W*i +: W] = {1'b0, val[W*(3+i) +: W-1]};
  end

  logic lt01, lt02, lt12;
  fp_cmp #(.E(E), .M(M), .Stages(LCmp)) u_cmp01 (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TCmp]), .a_i(abs_d[W*0 +: W]), .b_i(abs_d[W*1 +: W]),
    .valid_o(), .lt_o(lt01), .le_o(), .eq_o(), .min_o(), .max_o()
  );
  fp_cmp #(.E(E), .M(M), .Stages(LCmp)) u_cmp02 (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TCmp]), .a_i(abs_d[W*0 +: W]), .b_i(abs_d[W*2 +: W]),
    .valid_o(), .lt_o(lt02), .le_o(), .eq_o(), .min_o(), .max_o()
  );
  fp_cmp #(.E(E), .M(M), .Stages(LCmp)) u_cmp12 (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TCmp]), .a_i(abs_d[W*1 +: W]), .b_i(abs_d[W*2 +: W]),
    .valid_o(), .lt_o(lt12), .le_o(), .eq_o(), .min_o(), .max_o()
  );

  // The loaded values travel beside the comparisons, then beside the divisions.
  logic [8*W-1:0] val_axis, val_out;
  rt_delay #(.Width(8 * W), .Depth(LCmp)) u_d_val (
    .clk_i, .en_i(en),
    .d_i(val),
    .q_o(val_axis)
  );

  // ------------------------------------------------ axis choice, shear
  logic [1:0]   kz, kx0, ky0, kx, ky;
  logic [3*W-1:0] dk;  // d[0..2] at TAxis
  logic [W-1:0] d_kx, d_ky, d_kz;
  for (genvar i = 0; i < 3; i++) begin : g_dk
    assign dk[W*i +: W] = val_axis[W*(3+i) +: W];
  end
  assign kz = lt01 ? (lt12 ? 2'd2 : 2'd1) : (lt02 ? 2'd2 : 2'd0);
  assign kx0 = kz == 2'd2 ? 2'd0 : kz + 2'd1;
  assign ky0 = kx0 == 2'd2 ? 2'd0 : kx0 + 2'd1;
  always_comb begin
    unique case (kz)
      2'd0:    d_kz = dk[W*0 +: W];
      2'd1:    d_kz = dk[W*1 +: W];
      default: d_kz = dk[W*2 +: W];
    endcase
  end
  // Swapping kx and ky for a negative d[kz] keeps the triangle winding.
  assign kx = d_kz[W-1] ? ky0 : kx0;
  assign ky = d_kz[W-1] ? kx0 : ky0;
  always_comb begin
    unique case (kx)
      2'd0:    d_kx = dk[W*0 +: W];
      2'd1:    d_kx = dk[W*1 +: W];
      default: d_kx = dk[W*2 +: W];
    endcase
    unique case (ky)
      2'd0:    d_ky = dk[W*0 +: W];
      2'd1:    d_ky = dk[W*1 +: W];
      default: d_ky = dk[W*2 +: W];
    endcase
  end

  fp_div #(.E(E), .M(M)) u_sx (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TAxis]), .a_i(d_kx), .b_i(d_kz),
    .valid_o(), .res_o(out_sx_o)
  );
  fp_div #(.E(E), .M(M)) u_sy (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TAxis]), .a_i(d_ky), .b_i(d_kz),
    .valid_o(), .res_o(out_sy_o)
  );
  fp_div #(.E(E), .M(M)) u_sz (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TAxis]), .a_i(One), .b_i(d_kz),
    .valid_o(), .res_o(out_sz_o)
  );

  rt_delay #(.Width(8 * W + 6), .Depth(LDiv)) u_d_out (
    .clk_i, .en_i(en), .d_i({val_axis, kx, ky, kz}), .q_o({val_out, out_kx_o, out_ky_o, out_kz_o})
  );
  // inv_d is ready one stage (LCmp) before the rest.
  logic [3*W-1:0] inv_out;
  rt_delay #(.Width(3 * W), .Depth(LCmp)) u_d_inv (
    .clk_i, .en_i(en), .d_i(inv), .q_o(inv_out)
  );
  rt_delay #(.Width(TagWidth), .Depth(Latency)) u_d_tag (
    .clk_i, .en_i(en), .d_i(in_tag_i), .q_o(out_tag_o)
  );

  assign out_o_o = val_out[0 +: 3*W];
  assign out_d_o = val_out[3*W +: 3*W];
  assign out_tmin_o = val_out[6*W +: W];
  assign out_tmax_o = val_out[7*W +: W];
  assign out_inv_o = inv_out;

  /* verilator lint_on PINCONNECTEMPTY */

  // The valid/ready rule on both streams.
  rt_stream_check #(.Width(TagWidth + 256), .Name("rt_ray_setup in")) u_in_check (
    .clk_i, .rst_ni, .valid_i(in_valid_i), .ready_i(in_ready_o), .payload_i({in_tag_i, raw})
  );
  rt_stream_check #(.Width(TagWidth + 14 * W + 6), .Name("rt_ray_setup out")) u_out_check (
    .clk_i, .rst_ni, .valid_i(out_valid_o), .ready_i(out_ready_i),
    .payload_i({out_tag_o, out_o_o, out_d_o, out_inv_o, out_tmin_o, out_tmax_o, out_kx_o, out_ky_o, out_kz_o,
                out_sx_o, out_sy_o, out_sz_o})
  );

endmodule

`default_nettype wire
