// rt_clip_unit: clips a ray's [tmin, tmax] to the scene box, fully pipelined,
// valid/ready with a global stall. Exactly the model's operations
// (sw/trace/traversal.h, docs/dataflow.md section 1):
//   per axis i: near = sign(inv[i]) ? max[i] : min[i]; far = the other
//               tn = (load(near) - o[i]) * inv[i]; tf = (load(far) - o[i]) * inv[i]
//   t0 = tmin; t1 = tmax; for i = x, y, z: if t0 < tn: t0 = tn; if tf < t1: t1 = tf
//   t0 = nudge_down(t0); t1 = nudge_up(t1)      (conservative cells, fp_nudge)
//   miss = t1 < t0
// Latency = FpFromF32Latency + FpAddLatency + FpMulLatency + 3 cycles (one
// register per axis of the compare-select chain).
//
// A traversal wider than the triangle test (TravE, TravM above E, M; the
// model's TraceRayIn<Mixed>): the planes are loaded into (E, M) as before and
// widened exactly (fp_widen), as are o, tmin and tmax; the distances, the
// chain and the nudges run in (TravE, TravM), with inv in that format; then
// t0 and t1 are moved outwards into (E, M) (fp_round_out, one more
// FpFromF32Latency stage), so the interval leaves in the test's format.
`default_nettype none
// Unused outputs of the shared fp_cmp are left open on purpose.
/* verilator lint_off PINCONNECTEMPTY */

module rt_clip_unit #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23,
  parameter int unsigned TagWidth = 4,
  parameter int unsigned SlackUlps = 4,  // kTraversalSlackUlps (sw/trace/traversal.h)
  parameter int unsigned TravE = E,      // the traversal's format: (E, M) or a wider one
  parameter int unsigned TravM = M,
  localparam int unsigned W = E + M + 1,
  localparam int unsigned TW = TravE + TravM + 1
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic [95:0]         bounds_min_i,  // fp32 x, y, z
  input  logic [95:0]         bounds_max_i,
  input  logic                in_valid_i,
  output logic                in_ready_o,
  input  logic [TagWidth-1:0] in_tag_i,
  input  logic [3*W-1:0]      in_o_i,
  input  logic [3*TW-1:0]     in_inv_i,   // traversal format
  input  logic [W-1:0]        in_tmin_i,
  input  logic [W-1:0]        in_tmax_i,
  output logic                out_valid_o,
  input  logic                out_ready_i,
  output logic [TagWidth-1:0] out_tag_o,
  output logic [W-1:0]        out_t0_o,
  output logic [W-1:0]        out_t1_o,
  output logic                out_miss_o
);

  localparam int unsigned LConv = kdrt_fp_pkg::FpFromF32Latency;
  localparam int unsigned LAdd = kdrt_fp_pkg::FpAddLatency;
  localparam int unsigned LMul = kdrt_fp_pkg::FpMulLatency;
  localparam bit Mixed = TravE != E || TravM != M;

  logic en;
  assign en = !out_valid_o || out_ready_i;
  assign in_ready_o = en;

  // Flat vectors, not unpacked arrays: Yosys 0.23 silently drops logic wired
  // through unpacked arrays on ports.
  logic [5:0]      v_conv, v_sub, v_mul;
  logic [6*W-1:0]  plane;
  logic [6*TW-1:0] plane_t;  // in the traversal's format
  logic [3*W-1:0]  o_conv;
  logic [3*TW-1:0] o_conv_t, inv_conv, inv_sub;
  logic [6*TW-1:0] diff;
  logic [6*TW-1:0] tdist;  // slot 2i: near distance on axis i, 2i+1: far

  // o and inv travel beside the conversion and the subtraction.
  for (genvar i = 0; i < 3; i++) begin : g_axis
    logic         neg;
    logic [31:0]  near_f32, far_f32;
    assign neg = in_inv_i[TW*i + TW - 1];
    assign near_f32 = neg ? bounds_max_i[32*i +: 32] : bounds_min_i[32*i +: 32];
    assign far_f32 = neg ? bounds_min_i[32*i +: 32] : bounds_max_i[32*i +: 32];

    fp_from_f32 #(.E(E), .M(M)) u_near (
      .clk_i, .rst_ni, .en_i(en), .valid_i(in_valid_i), .f32_i(near_f32),
      .valid_o(v_conv[2*i]), .res_o(plane[W*(2*i) +: W])
    );
    fp_from_f32 #(.E(E), .M(M)) u_far (
      .clk_i, .rst_ni, .en_i(en), .valid_i(in_valid_i), .f32_i(far_f32),
      .valid_o(v_conv[2*i+1]), .res_o(plane[W*(2*i+1) +: W])
    );
    rt_delay #(.Width(W + TW), .Depth(LConv)) u_d1 (
      .clk_i, .en_i(en), .d_i({in_o_i[W*i +: W], in_inv_i[TW*i +: TW]}),
      .q_o({o_conv[W*i +: W], inv_conv[TW*i +: TW]})
    );
    rt_delay #(.Width(TW), .Depth(LAdd)) u_d2 (
      .clk_i, .en_i(en), .d_i(inv_conv[TW*i +: TW]), .q_o(inv_sub[TW*i +: TW])
    );
    fp_widen #(.E(E), .M(M), .WE(TravE), .WM(TravM)) u_widen_o (
      .a_i(o_conv[W*i +: W]), .res_o(o_conv_t[TW*i +: TW])
    );
    for (genvar k = 0; k < 2; k++) begin : g_side
      fp_widen #(.E(E), .M(M), .WE(TravE), .WM(TravM)) u_widen_plane (
        .a_i(plane[W*(2*i+k) +: W]), .res_o(plane_t[TW*(2*i+k) +: TW])
      );
      fp_add #(.E(TravE), .M(TravM)) u_sub (
        .clk_i, .rst_ni, .en_i(en), .valid_i(v_conv[2*i+k]), .a_i(plane_t[TW*(2*i+k) +: TW]),
        .b_i(o_conv_t[TW*i +: TW]), .sub_i(1'b1), .valid_o(v_sub[2*i+k]), .res_o(diff[TW*(2*i+k) +: TW])
      );
      fp_mul #(.E(TravE), .M(TravM)) u_mul (
        .clk_i, .rst_ni, .en_i(en), .valid_i(v_sub[2*i+k]), .a_i(diff[TW*(2*i+k) +: TW]),
        .b_i(inv_sub[TW*i +: TW]), .valid_o(v_mul[2*i+k]), .res_o(tdist[TW*(2*i+k) +: TW])
      );
    end
  end

  logic [TagWidth-1:0] tag_mul;
  logic [W-1:0]        tmin_q, tmax_q;
  logic [TW-1:0]       tmin_t, tmax_t;
  rt_delay #(.Width(TagWidth + 2 * W), .Depth(LConv + LAdd + LMul)) u_side (
    .clk_i, .en_i(en), .d_i({in_tag_i, in_tmin_i, in_tmax_i}), .q_o({tag_mul, tmin_q, tmax_q})
  );
  fp_widen #(.E(E), .M(M), .WE(TravE), .WM(TravM)) u_widen_tmin (.a_i(tmin_q), .res_o(tmin_t));
  fp_widen #(.E(E), .M(M), .WE(TravE), .WM(TravM)) u_widen_tmax (.a_i(tmax_q), .res_o(tmax_t));
  // All six distances advance together; one valid bit speaks for them.
  /* verilator lint_off UNUSEDSIGNAL */
  logic unused_valid;
  assign unused_valid = ^v_mul[5:1];
  /* verilator lint_on UNUSEDSIGNAL */

  // The compare-select chain, x then y then z, one register stage per axis so
  // that only one comparison lies between registers. Axis i's distances wait
  // i stages for their turn.
  logic [3:0]            chain_valid;
  logic [4*TagWidth-1:0] chain_tag;
  logic [4*TW-1:0]       t0_chain, t1_chain;
  assign chain_valid[0] = v_mul[0];
  assign chain_tag[0 +: TagWidth] = tag_mul;
  assign t0_chain[0 +: TW] = tmin_t;
  assign t1_chain[0 +: TW] = tmax_t;
  for (genvar i = 0; i < 3; i++) begin : g_chain
    logic [2*TW-1:0] axis_dist;
    rt_delay #(.Width(2 * TW), .Depth(i)) u_wait (
      .clk_i, .en_i(en), .d_i(tdist[TW*2*i +: 2*TW]), .q_o(axis_dist)
    );
    logic near_later, far_earlier;
    fp_cmp #(.E(TravE), .M(TravM), .Stages(0)) u_cmp_near (
      .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(t0_chain[TW*i +: TW]), .b_i(axis_dist[0 +: TW]),
      .valid_o(), .lt_o(near_later), .le_o(), .eq_o(), .min_o(), .max_o()
    );
    fp_cmp #(.E(TravE), .M(TravM), .Stages(0)) u_cmp_far (
      .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(axis_dist[TW +: TW]), .b_i(t1_chain[TW*i +: TW]),
      .valid_o(), .lt_o(far_earlier), .le_o(), .eq_o(), .min_o(), .max_o()
    );
    logic               valid_q;
    logic [TagWidth-1:0] tag_q;
    logic [TW-1:0]       t0_q, t1_q;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) valid_q <= 1'b0;
      else if (en) valid_q <= chain_valid[i];
    end
    always_ff @(posedge clk_i) begin
      if (en) begin
        tag_q <= chain_tag[TagWidth*i +: TagWidth];
        t0_q <= near_later ? axis_dist[0 +: TW] : t0_chain[TW*i +: TW];
        t1_q <= far_earlier ? axis_dist[TW +: TW] : t1_chain[TW*i +: TW];
      end
    end
    assign chain_valid[i+1] = valid_q;
    assign chain_tag[TagWidth*(i+1) +: TagWidth] = tag_q;
    assign t0_chain[TW*(i+1) +: TW] = t0_q;
    assign t1_chain[TW*(i+1) +: TW] = t1_q;
  end

  logic [TW-1:0] t0_up_unused, t1_down_unused, t0_nudged, t1_nudged;
  fp_nudge #(.E(TravE), .M(TravM), .K(SlackUlps)) u_nudge_t0 (
    .a_i(t0_chain[3*TW +: TW]), .up_o(t0_up_unused), .down_o(t0_nudged)
  );
  fp_nudge #(.E(TravE), .M(TravM), .K(SlackUlps)) u_nudge_t1 (
    .a_i(t1_chain[3*TW +: TW]), .up_o(t1_nudged), .down_o(t1_down_unused)
  );
  /* verilator lint_off UNUSEDSIGNAL */
  logic unused_nudge;
  assign unused_nudge = ^{t0_up_unused, t1_down_unused};
  /* verilator lint_on UNUSEDSIGNAL */

  // The interval in the test's format: as it is, or moved outwards into it.
  if (Mixed) begin : g_round_out
    fp_round_out #(.E(E), .M(M), .WE(TravE), .WM(TravM), .Up(1'b0)) u_t0 (
      .clk_i, .rst_ni, .en_i(en), .valid_i(chain_valid[3]), .a_i(t0_nudged), .valid_o(out_valid_o), .res_o(out_t0_o)
    );
    fp_round_out #(.E(E), .M(M), .WE(TravE), .WM(TravM), .Up(1'b1)) u_t1 (
      .clk_i, .rst_ni, .en_i(en), .valid_i(chain_valid[3]), .a_i(t1_nudged), .valid_o(), .res_o(out_t1_o)
    );
    rt_delay #(.Width(TagWidth), .Depth(LConv)) u_tag (
      .clk_i, .en_i(en), .d_i(chain_tag[3*TagWidth +: TagWidth]), .q_o(out_tag_o)
    );
  end else begin : g_same_ends
    assign out_valid_o = chain_valid[3];
    assign out_tag_o = chain_tag[3*TagWidth +: TagWidth];
    assign out_t0_o = t0_nudged;
    assign out_t1_o = t1_nudged;
  end
  fp_cmp #(.E(E), .M(M), .Stages(0)) u_cmp_miss (
    .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(out_t1_o), .b_i(out_t0_o),
    .valid_o(), .lt_o(out_miss_o), .le_o(), .eq_o(), .min_o(), .max_o()
  );

endmodule

`default_nettype wire
