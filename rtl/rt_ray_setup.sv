// rt_ray_setup: the per-ray precomputation, pipelined, one ray per cycle.
//
// First the world ray goes into the image's frame, in fp32, exactly as the
// model's ToFrame(const Ray&, const Frame&) (sw/trace/frame.cpp,
// docs/dataflow.md step 0), with origin = frame_origin_i, s = frame_scale_i:
//   o'[i] = ldexp(o[i] - origin[i], s)            (fp32 fp_add, then fp_ldexp)
//   m = 127 - max(biased exponent of d[x], d[y], d[z]); 0 if all three are 0
//   d'[i] = ldexp(d[i], m); k = m - s
//   tmin' = ldexp(tmin, -k); tmax' = ldexp(tmax, -k)
// k leaves on out_t_scale_o: a distance t' along the framed ray is t' * 2^k
// along the world ray (rt_hit_out maps the hit's t back).
// Then exactly the model's operations (sw/trace/intersect.h SetupRay,
// docs/dataflow.md section 1) on the framed ray in the (E, M) format:
//   o[i] = load(o'[i]); d[i] = load(d'[i]); inv_d[i] = 1 / d[i]
//   tmin = load(tmin'); tmax = load(tmax')
//   kz = 0; if |d[kz]| < |d[1]|: kz = 1; if |d[kz]| < |d[2]|: kz = 2
//   kx = (kz + 1) mod 3; ky = (kx + 1) mod 3; if sign(d[kz]): swap(kx, ky)
//   sx = d[kx] / d[kz]; sy = d[ky] / d[kz]; sz = 1 / d[kz] (in one format
//   inv_d[kz], the same division)
//   a shear that flushed to zero zeroes its d component (sign kept) and makes
//   its inv_d an infinity of that sign, at the output
// The two comparisons of the kz rule are made as three in parallel:
// |d0| < |d1|, |d0| < |d2| and |d1| < |d2|; the second one the model makes is
// the second or the third, chosen by the first, so the outcome is the same.
// |x| clears the sign bit; the model's Abs also turns a NaN into the canonical
// NaN, which a comparison cannot tell apart (both compare false).
//
// Stages (enabled cycles after the ray is taken):
//   0  m, k and -k from d's exponents and s (registered); the three fp32
//      subtractions o - origin start (fp_add, 4 cycles)
//   1  d', tmin', tmax' (fp_ldexp, registered)
//   2  load d', tmin', tmax' (fp_from_f32)
//   3  the three comparisons, the reciprocals start
//   4  the axis choice and operand select, the three divisions start;
//      o' = ldexp(o - origin, s) (registered); load(o') at 5, then a delay line
// outputs after Latency = 4 + M + FpDivExtraLatency = M + 8 enabled cycles
// (fp32 31, fp24 24, bf16 15, fp16 18): the mapping adds two stages to the
// d path; the o path (sub 4, ldexp 1, load 1) is off the critical chain.
// A traversal wider than the triangle test (TravE, TravM above E, M; the
// model's TraversalRay, sw/trace/traversal.h): out_inv_o is 1 / d in
// (TravE, TravM), of the loaded d widened exactly (fp_widen), and the
// flushed-shear rule gives its infinity in that format. Latency is then
// max(M + 8, 3 + TravM + FpDivExtraLatency) (fp16 or bf16 beside binary32: 30).
// The frame inputs are sampled with the ray (part of its payload; the core
// holds them constant). Flow control as rt_isect_unit: a global stall with
// en = !out_valid_o || out_ready_i = in_ready_o.
`default_nettype none

module rt_ray_setup #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23,
  parameter int unsigned TagWidth = 8,
  parameter int unsigned TravE = E,  // the traversal's format (out_inv_o)
  parameter int unsigned TravM = M,
  localparam int unsigned W = E + M + 1,
  localparam int unsigned TW = TravE + TravM + 1
) (
  input  logic                clk_i,
  input  logic                rst_ni,

  input  logic                in_valid_i,
  output logic                in_ready_o,
  input  logic [TagWidth-1:0] in_tag_i,
  // fp32 words in the order of a KDRTRAYS record: o.x in [31:0], o.y, o.z,
  // d.x, d.y, d.z, tmin, tmax in [255:224]; world units.
  input  logic [255:0]        in_ray_i,
  // The image's frame (header): origin as fp32 bits, x in [31:0], and the
  // signed scale s, |s| <= 160. Sampled with the ray.
  input  logic [95:0]         frame_origin_i,
  input  logic signed [kdrt_pkg::FrameScaleWidth-1:0] frame_scale_i,

  output logic                out_valid_o,
  input  logic                out_ready_i,
  output logic [TagWidth-1:0] out_tag_o,
  // k: a distance along the framed ray times 2^k is the world distance.
  output logic signed [kdrt_pkg::TScaleWidth-1:0] out_t_scale_o,
  output logic [3*W-1:0]      out_o_o,    // (E, M) format, x in [W-1:0], framed
  output logic [3*W-1:0]      out_d_o,
  output logic [3*TW-1:0]     out_inv_o,  // 1 / d, in the traversal's format
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

  localparam int unsigned SW    = kdrt_pkg::FrameScaleWidth;
  localparam int unsigned KW    = kdrt_pkg::TScaleWidth;
  localparam int unsigned LAdd  = kdrt_fp_pkg::FpAddLatency;
  localparam int unsigned LConv = kdrt_fp_pkg::FpFromF32Latency;
  localparam int unsigned LDiv  = M + kdrt_fp_pkg::FpDivExtraLatency;
  localparam int unsigned LCmp  = 1;
  localparam int unsigned TScale = 1;                // d', tmin', tmax' (fp_ldexp)
  localparam int unsigned TLoad = TScale + 1;        // their loads
  localparam int unsigned TCmp  = TLoad + LConv;     // comparisons, 1 / d[i]
  localparam int unsigned TAxis = TCmp + LCmp;       // axis choice, the shear divisions
  localparam int unsigned LDivT = TravM + kdrt_fp_pkg::FpDivExtraLatency;
  localparam int unsigned LatencyI = TAxis + LDiv;   // the shears
  localparam int unsigned LatencyT = TCmp + LDivT;   // the traversal's 1 / d
  localparam int unsigned Latency = LatencyI > LatencyT ? LatencyI : LatencyT;
  localparam int unsigned TOScale = LAdd;            // o' = ldexp(o - origin, s)
  localparam int unsigned TOLoad = TOScale + 1;      // load(o')
  localparam int unsigned TODone = TOLoad + LConv;   // must not exceed Latency (M >= 0)

  localparam logic [W-1:0] One = {2'b00, {(E-1){1'b1}}, {M{1'b0}}};
  localparam logic [TW-1:0] OneT = {2'b00, {(TravE-1){1'b1}}, {TravM{1'b0}}};

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

  // ------------------------------------------------ 0: into the frame (fp32)
  // Words 0..2: o, 3..5: d, 6: tmin, 7: tmax.
  logic [255:0] raw;
  assign raw = in_ray_i;

  // m = 127 - the largest biased exponent of d (0 if it is 0), k = m - s.
  // m lies in [-128, 127] and s is 9 bits signed, so k and -k lie in
  // [-383, 383]: KW = 10 bits (kdrt_pkg) hold every value, nothing wraps.
  logic [7:0] dexp [3];
  logic [7:0] max01, max_exp;
  logic signed [KW-1:0] m_d, s_d, k_d, nk_d;
  for (genvar i = 0; i < 3; i++) begin : g_dexp
    assign dexp[i] = raw[32*(3+i)+23 +: 8];
  end
  assign max01 = dexp[0] > dexp[1] ? dexp[0] : dexp[1];
  assign max_exp = max01 > dexp[2] ? max01 : dexp[2];
  assign m_d = max_exp == '0 ? '0 : $signed(KW'(127)) - $signed({{(KW-8){1'b0}}, max_exp});
  assign s_d = {{(KW-SW){frame_scale_i[SW-1]}}, frame_scale_i};
  assign k_d = m_d - s_d;
  assign nk_d = s_d - m_d;

  // Stage 1: m, k, -k and the raw d, tmin, tmax words.
  logic signed [KW-1:0] m_q, k_q, nk_q;
  logic [5*32-1:0] dt_raw_q;
  rt_delay #(.Width(3 * KW + 5 * 32), .Depth(TScale)) u_d_scale (
    .clk_i, .en_i(en),
    .d_i({m_d, k_d, nk_d, raw[32*3 +: 5*32]}),
    .q_o({m_q, k_q, nk_q, dt_raw_q})
  );

  // d' = ldexp(d, m); tmin' = ldexp(tmin, -k); tmax' likewise (exact or
  // FTZ/overflow, as fp::Ldexp), registered: stage 2.
  logic [5*32-1:0] dt_framed;
  for (genvar j = 0; j < 5; j++) begin : g_dt_ldexp
    fp_ldexp #(.E(8), .M(23), .NW(KW)) u_ldexp (
      .a_i(dt_raw_q[32*j +: 32]), .n_i(j < 3 ? m_q : nk_q), .y_o(dt_framed[32*j +: 32])
    );
  end
  logic [5*32-1:0] dt_framed_q;
  rt_delay #(.Width(5 * 32), .Depth(TLoad - TScale)) u_d_framed (
    .clk_i, .en_i(en), .d_i(dt_framed), .q_o(dt_framed_q)
  );

  // o - origin (fp32), then o' = ldexp(., s) with s carried beside the adders.
  logic [95:0] o_rel, o_framed, o_framed_q;
  logic signed [SW-1:0] s_o;
  for (genvar i = 0; i < 3; i++) begin : g_o_sub
    fp_add #(.E(8), .M(23)) u_sub (
      .clk_i, .rst_ni, .en_i(en), .valid_i(vld[0]), .a_i(raw[32*i +: 32]), .b_i(frame_origin_i[32*i +: 32]),
      .sub_i(1'b1), .valid_o(), .res_o(o_rel[32*i +: 32])
    );
    fp_ldexp #(.E(8), .M(23), .NW(KW)) u_ldexp (
      .a_i(o_rel[32*i +: 32]), .n_i({{(KW-SW){s_o[SW-1]}}, s_o}), .y_o(o_framed[32*i +: 32])
    );
  end
  rt_delay #(.Width(SW), .Depth(TOScale)) u_d_s (
    .clk_i, .en_i(en), .d_i(frame_scale_i), .q_o(s_o)
  );
  rt_delay #(.Width(96), .Depth(TOLoad - TOScale)) u_d_o_framed (
    .clk_i, .en_i(en), .d_i(o_framed), .q_o(o_framed_q)
  );

  // k travels to the output beside everything else.
  rt_delay #(.Width(KW), .Depth(Latency - TScale)) u_d_k (
    .clk_i, .en_i(en), .d_i(k_q), .q_o(out_t_scale_o)
  );

  // ------------------------------------------------ load
  // Value arrays are flat vectors of W-bit words (word i at [W*i +: W]).
  // val: d[0..2] in words 0..2, tmin 3, tmax 4.
  logic [5*W-1:0] val;
  for (genvar j = 0; j < 5; j++) begin : g_load
    fp_from_f32 #(.E(E), .M(M)) u_load (
      .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TLoad]), .f32_i(dt_framed_q[32*j +: 32]),
      .valid_o(), .res_o(val[W*j +: W])
    );
  end
  logic [3*W-1:0] o_val;
  for (genvar i = 0; i < 3; i++) begin : g_load_o
    fp_from_f32 #(.E(E), .M(M)) u_load (
      .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TOLoad]), .f32_i(o_framed_q[32*i +: 32]),
      .valid_o(), .res_o(o_val[W*i +: W])
    );
  end
  rt_delay #(.Width(3 * W), .Depth(Latency - TODone)) u_d_o (
    .clk_i, .en_i(en), .d_i(o_val), .q_o(out_o_o)
  );

  // ------------------------------------------------ 1 / d, comparisons
  logic [3*TW-1:0] inv;
  logic [3*W-1:0] abs_d;
  for (genvar i = 0; i < 3; i++) begin : g_inv
    logic [TW-1:0] d_t;
    fp_widen #(.E(E), .M(M), .WE(TravE), .WM(TravM)) u_widen (.a_i(val[W*i +: W]), .res_o(d_t));
    fp_div #(.E(TravE), .M(TravM)) u_div (
      .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TCmp]), .a_i(OneT), .b_i(d_t),
      .valid_o(), .res_o(inv[TW*i +: TW])
    );
    assign abs_d[W*i +: W] = {1'b0, val[W*i +: W-1]};
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
  logic [5*W-1:0] val_axis, val_out;
  rt_delay #(.Width(5 * W), .Depth(LCmp)) u_d_val (
    .clk_i, .en_i(en),
    .d_i(val),
    .q_o(val_axis)
  );

  // ------------------------------------------------ axis choice, shear
  // Component k (0, 1 or 2) of three values of W bits.
  function automatic logic [W-1:0] axis(input logic [3*W-1:0] v, input logic [1:0] k);
    axis = k == 2'd0 ? v[0 +: W] : k == 2'd1 ? v[W +: W] : v[2*W +: W];
  endfunction
  logic [1:0]   kz, kx0, ky0, kx, ky;
  logic [3*W-1:0] dk;  // d[0..2] at TAxis
  logic [W-1:0] d_kx, d_ky, d_kz;
  assign dk = val_axis[3*W-1:0];
  assign kz = lt01 ? (lt12 ? 2'd2 : 2'd1) : (lt02 ? 2'd2 : 2'd0);
  assign kx0 = kz == 2'd2 ? 2'd0 : kz + 2'd1;
  assign ky0 = kx0 == 2'd2 ? 2'd0 : kx0 + 2'd1;
  assign d_kz = axis(dk, kz);
  // Swapping kx and ky for a negative d[kz] keeps the triangle winding.
  assign kx = d_kz[W-1] ? ky0 : kx0;
  assign ky = d_kz[W-1] ? kx0 : ky0;
  assign d_kx = axis(dk, kx);
  assign d_ky = axis(dk, ky);

  logic [2*W-1:0] shear;  // sx, sy
  fp_div #(.E(E), .M(M)) u_sx (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TAxis]), .a_i(d_kx), .b_i(d_kz),
    .valid_o(), .res_o(shear[0 +: W])
  );
  fp_div #(.E(E), .M(M)) u_sy (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TAxis]), .a_i(d_ky), .b_i(d_kz),
    .valid_o(), .res_o(shear[W +: W])
  );
  // With a wider traversal, the shears wait for its reciprocals.
  rt_delay #(.Width(2 * W), .Depth(Latency - LatencyI)) u_d_shear (
    .clk_i, .en_i(en), .d_i(shear), .q_o({out_sy_o, out_sx_o})
  );

  rt_delay #(.Width(5 * W + 6), .Depth(LDiv + Latency - LatencyI)) u_d_out (
    .clk_i, .en_i(en), .d_i({val_axis, kx, ky, kz}), .q_o({val_out, out_kx_o, out_ky_o, out_kz_o})
  );
  // In one format inv_d is ready one stage (LCmp) before the rest.
  logic [3*TW-1:0] inv_out;
  rt_delay #(.Width(3 * TW), .Depth(Latency - LatencyT)) u_d_inv (
    .clk_i, .en_i(en), .d_i(inv), .q_o(inv_out)
  );
  // sz = 1 / d[kz]: in one format the reciprocal of d[kz] already made for
  // inv_d (the same division of the same operands), else a division of its own.
  if (TravE == E && TravM == M) begin : g_sz_inv
    assign out_sz_o = axis(inv_out, out_kz_o);
  end else begin : g_sz_div
    logic [W-1:0] sz;
    fp_div #(.E(E), .M(M)) u_sz (
      .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TAxis]), .a_i(One), .b_i(d_kz),
      .valid_o(), .res_o(sz)
    );
    rt_delay #(.Width(W), .Depth(Latency - LatencyI)) u_d_sz (
      .clk_i, .en_i(en), .d_i(sz), .q_o(out_sz_o)
    );
  end
  rt_delay #(.Width(TagWidth), .Depth(Latency)) u_d_tag (
    .clk_i, .en_i(en), .d_i(in_tag_i), .q_o(out_tag_o)
  );

  // A shear that flushed to zero while its direction component is not zero:
  // the test traces a ray without that component, so the traversal must too.
  // The component becomes a zero of its sign, its reciprocal an infinity of
  // that sign (the model's SetupRay). Zero means a zero exponent field (DAZ).
  logic [E-1:0] exp_dx, exp_dy;  // the exponent fields of d[kx] and d[ky]
  always_comb begin
    unique case (out_kx_o)
      2'd0:    exp_dx = val_out[W*0 + M +: E];
      2'd1:    exp_dx = val_out[W*1 + M +: E];
      default: exp_dx = val_out[W*2 + M +: E];
    endcase
    unique case (out_ky_o)
      2'd0:    exp_dy = val_out[W*0 + M +: E];
      2'd1:    exp_dy = val_out[W*1 + M +: E];
      default: exp_dy = val_out[W*2 + M +: E];
    endcase
  end
  logic sx_flushed, sy_flushed;
  assign sx_flushed = out_sx_o[M +: E] == '0 && exp_dx != '0;
  assign sy_flushed = out_sy_o[M +: E] == '0 && exp_dy != '0;
  for (genvar i = 0; i < 3; i++) begin : g_flush
    logic zero_i, sign_i;
    assign zero_i = (sx_flushed && out_kx_o == 2'(i)) || (sy_flushed && out_ky_o == 2'(i));
    assign sign_i = val_out[W*i + W-1];
    assign out_d_o[W*i +: W] = zero_i ? {sign_i, {(W-1){1'b0}}} : val_out[W*i +: W];
    assign out_inv_o[TW*i +: TW] = zero_i ? {sign_i, {TravE{1'b1}}, {TravM{1'b0}}} : inv_out[TW*i +: TW];
  end
  assign out_tmin_o = val_out[3*W +: W];
  assign out_tmax_o = val_out[4*W +: W];

  /* verilator lint_on PINCONNECTEMPTY */

  // The valid/ready rule on both streams.
  rt_stream_check #(.Width(TagWidth + 256 + 96 + SW), .Name("rt_ray_setup in")) u_in_check (
    .clk_i, .rst_ni, .valid_i(in_valid_i), .ready_i(in_ready_o),
    .payload_i({in_tag_i, raw, frame_origin_i, frame_scale_i})
  );
  rt_stream_check #(.Width(TagWidth + KW + 11 * W + 3 * TW + 6), .Name("rt_ray_setup out")) u_out_check (
    .clk_i, .rst_ni, .valid_i(out_valid_o), .ready_i(out_ready_i),
    .payload_i({out_tag_o, out_t_scale_o, out_o_o, out_d_o, out_inv_o, out_tmin_o, out_tmax_o, out_kx_o, out_ky_o, out_kz_o,
                out_sx_o, out_sy_o, out_sz_o})
  );

endmodule

`default_nettype wire
