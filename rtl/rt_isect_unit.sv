// rt_isect_unit: the watertight ray/triangle test (Woop, Benthin & Wald
// 2013), fully pipelined: one (ray, triangle) test per cycle.
//
// Exactly the model's operations, in its order and with its rounding
// (sw/trace/intersect.h IntersectWatertight, docs/dataflow.md section 3),
// for any (E, M); docs/isect-unit.md describes the stages:
//   p[W*k +: W][i] = load(v_k[i]) - o[i]
//   x[k] = p[W*k +: W][kx] - sx * p[W*k +: W][kz];  y[k] = p[W*k +: W][ky] - sy * p[W*k +: W][kz]
//   e0 = x2*y1 - y2*x1; e1 = x0*y2 - y0*x2; e2 = x1*y0 - y1*x0
//   miss if some e < 0 and some e > 0
//   det = (e0 + e1) + e2; miss unless det < 0 or det > 0
//   z[W*k +: W] = sz * p[W*k +: W][kz]; T = (e0*z0 + e1*z1) + e2*z2
//   if det < 0: T, det, e1, e2 = -T, -det, -e1, -e2
//   hit iff tmin*det <= T and T <= tmax*det
//   r = 1 / det; t = T*r; u = e1*r; v = e2*r
// Only the p[W*k +: W][i] of the three axes kx, ky, kz are used, so the vertex and
// origin words are permuted before the subtraction (the same nine numbers).
// The reciprocal and the t, u, v products are computed for every test; the
// outputs are zero unless hit.
//
// Flow control: a global stall. en = !out_valid_o || out_ready_i drives every
// stage; in_ready_o = en. Inputs must follow the valid/ready rule (valid held
// and the payload stable until ready), and the outputs follow it too.
// Latency (enabled cycles from input to output): 34 + M with the current
// fp_* latencies of kdrt_fp_pkg (localparam Latency): fp32 57, fp24 50, bf16 41, fp16 44.
`default_nettype none

module rt_isect_unit #(
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
  input  logic [31:0]         in_id_i,    // triangle id, carried through
  // The ray, from rt_ray_setup, in the (E, M) format; x in the low bits.
  input  logic [3*W-1:0]      in_o_i,
  input  logic [1:0]          in_kx_i,    // 0..2, distinct
  input  logic [1:0]          in_ky_i,
  input  logic [1:0]          in_kz_i,
  input  logic [W-1:0]        in_sx_i,
  input  logic [W-1:0]        in_sy_i,
  input  logic [W-1:0]        in_sz_i,
  input  logic [W-1:0]        in_tmin_i,
  input  logic [W-1:0]        in_tmax_i,  // the leaf's tmax
  // Bytes [0, 36) of the triangle record as fp32 words: v0.x in [31:0],
  // v0.y, v0.z, v1.x, ..., v2.z in [287:256].
  input  logic [287:0]        in_tri_i,

  output logic                out_valid_o,
  input  logic                out_ready_i,
  output logic [TagWidth-1:0] out_tag_o,
  output logic [31:0]         out_id_o,
  output logic                out_hit_o,
  output logic [W-1:0]        out_t_o,    // zero unless hit
  output logic [W-1:0]        out_u_o,    // weight of v1
  output logic [W-1:0]        out_v_o     // weight of v2
);

  // The fp units' own valid_o and the unused comparison outputs are left
  // open: one valid chain (vld) serves the whole schedule.
  /* verilator lint_off PINCONNECTEMPTY */

  localparam int unsigned LConv = kdrt_fp_pkg::FpFromF32Latency;
  localparam int unsigned LAdd  = kdrt_fp_pkg::FpAddLatency;
  localparam int unsigned LMul  = kdrt_fp_pkg::FpMulLatency;
  localparam int unsigned LDiv  = M + kdrt_fp_pkg::FpDivExtraLatency;
  localparam int unsigned LCmp  = 1;

  // The schedule: the enabled cycle (after acceptance) at which each step
  // starts. Operands that arrive earlier wait in rt_delay lines.
  localparam int unsigned TSub    = LConv;           // p = load(v) - o
  localparam int unsigned TShear  = TSub + LAdd;     // s * p[W*kz +: W]
  localparam int unsigned TXY     = TShear + LMul;   // x, y
  localparam int unsigned TEMul   = TXY + LAdd;      // edge products
  localparam int unsigned TESub   = TEMul + LMul;    // edge differences
  localparam int unsigned TE      = TESub + LAdd;    // sign test, e0 + e1, e * z
  localparam int unsigned TDetAdd = TE + LAdd;       // (e0 + e1) + e2
  localparam int unsigned TDet    = TDetAdd + LAdd;  // det test, |det| products, 1 / |det|
  localparam int unsigned TTAdd1  = TE + LMul;       // e0*z0 + e1*z1
  localparam int unsigned TTAdd2  = TTAdd1 + LAdd;   // ... + e2*z2
  localparam int unsigned TT      = TTAdd2 + LAdd;   // T, sign folded
  localparam int unsigned TBound  = TDet + LMul;     // tmin*|det|, tmax*|det| ready
  localparam int unsigned TCmp    = TT > TBound ? TT : TBound;
  localparam int unsigned THit    = TCmp + LCmp;
  localparam int unsigned TRcp    = TDet + LDiv;
  localparam int unsigned TFin    = TRcp > TT ? TRcp : TT;  // t, u, v products
  localparam int unsigned TFinOut = TFin + LMul;
  localparam int unsigned Latency = TFinOut > THit ? TFinOut : THit;

  localparam logic [E-1:0] ExpOnes      = {E{1'b1}};
  localparam logic [W-1:0] CanonicalNaN = {1'b0, ExpOnes, 1'b1, {(M-1){1'b0}}};
  localparam logic [W-1:0] One          = {2'b00, {(E-1){1'b1}}, {M{1'b0}}};
  localparam logic [W-1:0] Zero         = '0;

  logic en;
  assign en = !out_valid_o || out_ready_i;
  assign in_ready_o = en;

  // vld[t]: the test at step t is a real one.
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

  // ------------------------------------------------ load, p = load(v) - o
  // Word 3*k + a: vertex k, a = 0 for the kx axis, 1 for ky, 2 for kz.
  // Arrays of values are flat vectors of W-bit words (word i at [W*i +: W]):
  // Yosys 0.23 loses unpacked-array words driven through port concatenations.
  logic [287:0]  v_raw;
  logic [9*W-1:0] v_load;
  logic [3*W-1:0] o_perm;
  logic [3*W-1:0] o_sub;
  logic [9*W-1:0] p;

  for (genvar a = 0; a < 3; a++) begin : g_perm
    logic [1:0] axis;
    assign axis = a == 0 ? in_kx_i : a == 1 ? in_ky_i : in_kz_i;
    assign o_perm[W*a +: W] = axis == 2'd0 ? in_o_i[0 +: W] :
                              axis == 2'd1 ? in_o_i[W +: W] : in_o_i[2*W +: W];
    for (genvar k = 0; k < 3; k++) begin : g_vertex
      assign v_raw[32*(3*k+a) +: 32] = axis == 2'd0 ? in_tri_i[96*k +: 32] :
                            axis == 2'd1 ? in_tri_i[96*k + 32 +: 32] : in_tri_i[96*k + 64 +: 32];
      fp_from_f32 #(.E(E), .M(M)) u_load (
        .clk_i, .rst_ni, .en_i(en), .valid_i(vld[0]), .f32_i(v_raw[32*(3*k+a) +: 32]),
        .valid_o(), .res_o(v_load[W*(3*k+a) +: W])
      );
      fp_add #(.E(E), .M(M)) u_p (
        .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TSub]), .a_i(v_load[W*(3*k+a) +: W]),
        .b_i(o_sub[W*a +: W]), .sub_i(1'b1), .valid_o(), .res_o(p[W*(3*k+a) +: W])
      );
    end
  end

  rt_delay #(.Width(3 * W), .Depth(TSub)) u_d_o (
    .clk_i, .en_i(en), .d_i(o_perm), .q_o(o_sub)
  );

  // ------------------------------------------------ shear: x, y, z
  logic [3*W-1:0] s_shear;  // sx, sy, sz at TShear
  logic [9*W-1:0] sp;       // 3*k + a: s_a * p[W*k +: W][kz]
  logic [6*W-1:0] pxy;      // 2*k + a: p[W*k +: W][kx], p[W*k +: W][ky] at TXY
  logic [6*W-1:0] xy;       // 2*k: x[k], 2*k + 1: y[k]
  logic [3*W-1:0] z;        // z[W*k +: W] at TE

  rt_delay #(.Width(3 * W), .Depth(TShear)) u_d_s (
    .clk_i, .en_i(en), .d_i({in_sz_i, in_sy_i, in_sx_i}), .q_o(s_shear)
  );

  for (genvar k = 0; k < 3; k++) begin : g_shear
    for (genvar a = 0; a < 3; a++) begin : g_axis
      fp_mul #(.E(E), .M(M)) u_mul (
        .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TShear]), .a_i(s_shear[W*a +: W]),
        .b_i(p[W*(3*k+2) +: W]),
        .valid_o(), .res_o(sp[W*(3*k+a) +: W])
      );
    end
    rt_delay #(.Width(2 * W), .Depth(LMul)) u_d_pxy (
      .clk_i, .en_i(en), .d_i(p[W*3*k +: 2*W]), .q_o(pxy[W*2*k +: 2*W])
    );
    for (genvar a = 0; a < 2; a++) begin : g_xy
      fp_add #(.E(E), .M(M)) u_sub (
        .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TXY]), .a_i(pxy[W*(2*k+a) +: W]),
        .b_i(sp[W*(3*k+a) +: W]), .sub_i(1'b1), .valid_o(), .res_o(xy[W*(2*k+a) +: W])
      );
    end
    rt_delay #(.Width(W), .Depth(TE - TXY)) u_d_z (
      .clk_i, .en_i(en), .d_i(sp[W*(3*k+2) +: W]), .q_o(z[W*k +: W])
    );
  end

  // ------------------------------------------------ edge functions
  // e_i = x[i+2]*y[i+1] - y[i+2]*x[i+1] (indices mod 3).
  logic [3*W-1:0] e;
  logic [6*W-1:0] eprod;  // 2*i: x[i+2]*y[i+1], 2*i + 1: y[i+2]*x[i+1]
  logic [2:0]   e_neg, e_pos;

  for (genvar i = 0; i < 3; i++) begin : g_edge
    localparam int unsigned K2 = (i + 2) % 3;
    localparam int unsigned K1 = (i + 1) % 3;
    fp_mul #(.E(E), .M(M)) u_mul_a (
      .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TEMul]), .a_i(xy[W*(2*K2) +: W]),
      .b_i(xy[W*(2*K1+1) +: W]),
      .valid_o(), .res_o(eprod[W*(2*i) +: W])
    );
    fp_mul #(.E(E), .M(M)) u_mul_b (
      .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TEMul]), .a_i(xy[W*(2*K2+1) +: W]),
      .b_i(xy[W*(2*K1) +: W]),
      .valid_o(), .res_o(eprod[W*(2*i+1) +: W])
    );
    fp_add #(.E(E), .M(M)) u_sub (
      .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TESub]), .a_i(eprod[W*(2*i) +: W]),
      .b_i(eprod[W*(2*i+1) +: W]),
      .sub_i(1'b1), .valid_o(), .res_o(e[W*i +: W])
    );
    fp_cmp #(.E(E), .M(M), .Stages(0)) u_neg (
      .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(e[W*i +: W]), .b_i(Zero),
      .valid_o(), .lt_o(e_neg[i]), .le_o(), .eq_o(), .min_o(), .max_o()
    );
    fp_cmp #(.E(E), .M(M), .Stages(0)) u_pos (
      .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(Zero), .b_i(e[W*i +: W]),
      .valid_o(), .lt_o(e_pos[i]), .le_o(), .eq_o(), .min_o(), .max_o()
    );
  end

  logic edge_miss, edge_miss_det;
  assign edge_miss = (|e_neg) && (|e_pos);
  rt_delay #(.Width(1), .Depth(TDet - TE)) u_d_edge_miss (
    .clk_i, .en_i(en), .d_i(edge_miss), .q_o(edge_miss_det)
  );

  // ------------------------------------------------ det and T
  logic [W-1:0] e01, e2_det_add, det;
  logic [3*W-1:0] ez;
  logic [W-1:0] ez01, ez2_add2, t_scaled;
  logic [W-1:0] e1_det, e2_det;

  fp_add #(.E(E), .M(M)) u_e01 (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TE]), .a_i(e[W*0 +: W]), .b_i(e[W*1 +: W]),
    .sub_i(1'b0), .valid_o(), .res_o(e01)
  );
  rt_delay #(.Width(W), .Depth(TDetAdd - TE)) u_d_e2 (
    .clk_i, .en_i(en), .d_i(e[W*2 +: W]), .q_o(e2_det_add)
  );
  fp_add #(.E(E), .M(M)) u_det (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TDetAdd]), .a_i(e01), .b_i(e2_det_add),
    .sub_i(1'b0), .valid_o(), .res_o(det)
  );
  rt_delay #(.Width(2 * W), .Depth(TDet - TE)) u_d_e12 (
    .clk_i, .en_i(en), .d_i({e[W*2 +: W], e[W*1 +: W]}), .q_o({e2_det, e1_det})
  );

  for (genvar k = 0; k < 3; k++) begin : g_ez
    fp_mul #(.E(E), .M(M)) u_mul (
      .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TE]), .a_i(e[W*k +: W]), .b_i(z[W*k +: W]),
      .valid_o(), .res_o(ez[W*k +: W])
    );
  end
  fp_add #(.E(E), .M(M)) u_t01 (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TTAdd1]), .a_i(ez[W*0 +: W]), .b_i(ez[W*1 +: W]),
    .sub_i(1'b0), .valid_o(), .res_o(ez01)
  );
  rt_delay #(.Width(W), .Depth(TTAdd2 - TTAdd1)) u_d_ez2 (
    .clk_i, .en_i(en), .d_i(ez[W*2 +: W]), .q_o(ez2_add2)
  );
  fp_add #(.E(E), .M(M)) u_t (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TTAdd2]), .a_i(ez01), .b_i(ez2_add2),
    .sub_i(1'b0), .valid_o(), .res_o(t_scaled)
  );

  // ------------------------------------------------ det test, sign folding
  // Neg as the model's: a bit flip, NaN -> canonical NaN.
  logic det_neg, det_pos, det_miss;
  logic [W-1:0] det_abs, e1_s, e2_s;
  logic [W-1:0] tmin_det, tmax_det;

  fp_cmp #(.E(E), .M(M), .Stages(0)) u_det_neg (
    .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(det), .b_i(Zero),
    .valid_o(), .lt_o(det_neg), .le_o(), .eq_o(), .min_o(), .max_o()
  );
  fp_cmp #(.E(E), .M(M), .Stages(0)) u_det_pos (
    .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(Zero), .b_i(det),
    .valid_o(), .lt_o(det_pos), .le_o(), .eq_o(), .min_o(), .max_o()
  );
  assign det_miss = edge_miss_det || !(det_neg || det_pos);

  logic det_nan, e1_nan, e2_nan;
  assign det_nan = det[W-2:M] == ExpOnes && det[M-1:0] != '0;
  assign e1_nan = e1_det[W-2:M] == ExpOnes && e1_det[M-1:0] != '0;
  assign e2_nan = e2_det[W-2:M] == ExpOnes && e2_det[M-1:0] != '0;
  assign det_abs = !det_neg ? det : det_nan ? CanonicalNaN : {1'b0, det[W-2:0]};
  assign e1_s = !det_neg ? e1_det : e1_nan ? CanonicalNaN : {~e1_det[W-1], e1_det[W-2:0]};
  assign e2_s = !det_neg ? e2_det : e2_nan ? CanonicalNaN : {~e2_det[W-1], e2_det[W-2:0]};

  logic [W-1:0] tmin_det_in, tmax_det_in;
  rt_delay #(.Width(2 * W), .Depth(TDet)) u_d_trange (
    .clk_i, .en_i(en), .d_i({in_tmax_i, in_tmin_i}), .q_o({tmax_det_in, tmin_det_in})
  );
  fp_mul #(.E(E), .M(M)) u_tmin_det (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TDet]), .a_i(tmin_det_in), .b_i(det_abs),
    .valid_o(), .res_o(tmin_det)
  );
  fp_mul #(.E(E), .M(M)) u_tmax_det (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TDet]), .a_i(tmax_det_in), .b_i(det_abs),
    .valid_o(), .res_o(tmax_det)
  );
  logic [W-1:0] rcp;
  fp_div #(.E(E), .M(M)) u_rcp (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TDet]), .a_i(One), .b_i(det_abs),
    .valid_o(), .res_o(rcp)
  );

  // T's sign, folded when T is ready.
  logic det_neg_tt, t_nan;
  logic [W-1:0] t_s;
  rt_delay #(.Width(1), .Depth(TT - TDet)) u_d_det_neg (
    .clk_i, .en_i(en), .d_i(det_neg), .q_o(det_neg_tt)
  );
  assign t_nan = t_scaled[W-2:M] == ExpOnes && t_scaled[M-1:0] != '0;
  assign t_s = !det_neg_tt ? t_scaled : t_nan ? CanonicalNaN : {~t_scaled[W-1], t_scaled[W-2:0]};

  // ------------------------------------------------ range test
  logic [W-1:0] t_s_cmp, tmin_det_cmp, tmax_det_cmp;
  logic         det_miss_cmp, lo_ok, hi_ok, hit_d, hit_out;
  if (TCmp - TT == 0) begin : g_d_ts_cmp_wire
    assign t_s_cmp = t_s;
  end else begin : g_d_ts_cmp
    rt_delay #(.Width(W), .Depth(TCmp - TT)) u_d_ts_cmp (
      .clk_i, .en_i(en), .d_i(t_s), .q_o(t_s_cmp)
    );
  end
  if (TCmp - TBound == 0) begin : g_d_bounds_wire
    assign {tmax_det_cmp, tmin_det_cmp} = {tmax_det, tmin_det};
  end else begin : g_d_bounds
    rt_delay #(.Width(2 * W), .Depth(TCmp - TBound)) u_d_bounds (
      .clk_i, .en_i(en), .d_i({tmax_det, tmin_det}), .q_o({tmax_det_cmp, tmin_det_cmp})
    );
  end
  rt_delay #(.Width(1), .Depth(THit - TDet)) u_d_det_miss (
    .clk_i, .en_i(en), .d_i(det_miss), .q_o(det_miss_cmp)
  );
  fp_cmp #(.E(E), .M(M), .Stages(LCmp)) u_lo (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TCmp]), .a_i(tmin_det_cmp), .b_i(t_s_cmp),
    .valid_o(), .lt_o(), .le_o(lo_ok), .eq_o(), .min_o(), .max_o()
  );
  fp_cmp #(.E(E), .M(M), .Stages(LCmp)) u_hi (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TCmp]), .a_i(t_s_cmp), .b_i(tmax_det_cmp),
    .valid_o(), .lt_o(), .le_o(hi_ok), .eq_o(), .min_o(), .max_o()
  );
  assign hit_d = !det_miss_cmp && lo_ok && hi_ok;
  if (Latency - THit == 0) begin : g_d_hit_wire
    assign hit_out = hit_d;
  end else begin : g_d_hit
    rt_delay #(.Width(1), .Depth(Latency - THit)) u_d_hit (
      .clk_i, .en_i(en), .d_i(hit_d), .q_o(hit_out)
    );
  end

  // ------------------------------------------------ t, u, v
  logic [W-1:0] rcp_fin, t_s_fin, e1_fin, e2_fin;
  logic [W-1:0] t_fin, u_fin, v_fin;
  if (TFin - TRcp == 0) begin : g_d_rcp_wire
    assign rcp_fin = rcp;
  end else begin : g_d_rcp
    rt_delay #(.Width(W), .Depth(TFin - TRcp)) u_d_rcp (
      .clk_i, .en_i(en), .d_i(rcp), .q_o(rcp_fin)
    );
  end
  if (TFin - TT == 0) begin : g_d_ts_fin_wire
    assign t_s_fin = t_s;
  end else begin : g_d_ts_fin
    rt_delay #(.Width(W), .Depth(TFin - TT)) u_d_ts_fin (
      .clk_i, .en_i(en), .d_i(t_s), .q_o(t_s_fin)
    );
  end
  rt_delay #(.Width(2 * W), .Depth(TFin - TDet)) u_d_e_fin (
    .clk_i, .en_i(en), .d_i({e2_s, e1_s}), .q_o({e2_fin, e1_fin})
  );
  fp_mul #(.E(E), .M(M)) u_t_mul (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TFin]), .a_i(t_s_fin), .b_i(rcp_fin),
    .valid_o(), .res_o(t_fin)
  );
  fp_mul #(.E(E), .M(M)) u_u_mul (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TFin]), .a_i(e1_fin), .b_i(rcp_fin),
    .valid_o(), .res_o(u_fin)
  );
  fp_mul #(.E(E), .M(M)) u_v_mul (
    .clk_i, .rst_ni, .en_i(en), .valid_i(vld[TFin]), .a_i(e2_fin), .b_i(rcp_fin),
    .valid_o(), .res_o(v_fin)
  );

  logic [3*W-1:0] tuv_out;
  if (Latency - TFinOut == 0) begin : g_d_tuv_wire
    assign tuv_out = {v_fin, u_fin, t_fin};
  end else begin : g_d_tuv
    rt_delay #(.Width(3 * W), .Depth(Latency - TFinOut)) u_d_tuv (
      .clk_i, .en_i(en), .d_i({v_fin, u_fin, t_fin}), .q_o(tuv_out)
    );
  end
  rt_delay #(.Width(TagWidth + 32), .Depth(Latency)) u_d_tag (
    .clk_i, .en_i(en), .d_i({in_tag_i, in_id_i}), .q_o({out_tag_o, out_id_o})
  );

  assign out_hit_o = hit_out;
  assign out_t_o = hit_out ? tuv_out[0 +: W] : '0;
  assign out_u_o = hit_out ? tuv_out[W +: W] : '0;
  assign out_v_o = hit_out ? tuv_out[2*W +: W] : '0;

  /* verilator lint_on PINCONNECTEMPTY */

  // The valid/ready rule on both streams: the input side checks the caller,
  // the output side this unit.
  rt_stream_check #(.Width(TagWidth + 32 + 3 * W + 6 + 5 * W + 288), .Name("rt_isect_unit in")) u_in_check (
    .clk_i, .rst_ni, .valid_i(in_valid_i), .ready_i(in_ready_o),
    .payload_i({in_tag_i, in_id_i, in_o_i, in_kx_i, in_ky_i, in_kz_i, in_sx_i, in_sy_i, in_sz_i, in_tmin_i,
                in_tmax_i, in_tri_i})
  );
  rt_stream_check #(.Width(TagWidth + 32 + 1 + 3 * W), .Name("rt_isect_unit out")) u_out_check (
    .clk_i, .rst_ni, .valid_i(out_valid_o), .ready_i(out_ready_i),
    .payload_i({out_tag_o, out_id_o, out_hit_o, out_t_o, out_u_o, out_v_o})
  );

endmodule

`default_nettype wire
