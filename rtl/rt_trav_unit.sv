// rt_trav_unit: the kd-tree traversal step, fully pipelined (one inner node
// per cycle), valid/ready with a global stall.
//
// For an inner node it computes, in the datapath format (E, M), exactly the
// model's operations (sw/trace/traversal.h, docs/dataflow.md section 2):
//   split = load(split word)                      fp_from_f32
//   ts    = (split - o[a]) * inv[a]               fp_add (sub), fp_mul
//   below_first = o[a] < split or (o[a] == split and d[a] <= 0)
//   lo = nudge_down(ts), hi = nudge_up(ts)      fp_nudge (conservative cells)
//   action: first only  if t1 < lo or ts <= 0
//           second only if hi < t0
//           push (second, lo, t1) and go first with t1 = hi otherwise
// The children's empty marks (the node's, img::Node) ride along and leave as
// the first and second child's (rt_core sends a thread whose next node is an
// empty leaf to its exit without fetching it).
// Latency = FpFromF32Latency + FpAddLatency + FpMulLatency cycles.
//
// A traversal wider than the triangle test (TravE, TravM above E, M; the
// model's TraceRayIn<Mixed>, docs/dataflow.md section 2): the split is loaded
// into (E, M) as before and widened exactly (fp_widen), as is o; the
// subtraction, multiplication and nudge run in (TravE, TravM), with inv in
// that format; then each nudged end is moved outwards into (E, M)
// (fp_round_out, one more FpFromF32Latency stage), so t0, t1 and the child
// intervals stay (E, M) values and the stack keeps its width. The decision
// compares (E, M) values, except ts <= 0 on the wide ts.
`default_nettype none
// Unused outputs of the shared fp_cmp are left open on purpose.
/* verilator lint_off PINCONNECTEMPTY */

module rt_trav_unit #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23,
  parameter int unsigned TagWidth = 4,
  parameter int unsigned NodeIdxWidth = 24,
  parameter int unsigned SlackUlps = 4,  // kTraversalSlackUlps (sw/trace/traversal.h)
  parameter int unsigned TravE = E,      // the traversal's format: (E, M) or a wider one
  parameter int unsigned TravM = M,
  localparam int unsigned W = E + M + 1,
  localparam int unsigned TW = TravE + TravM + 1
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  input  logic                    in_valid_i,
  output logic                    in_ready_o,
  input  logic [TagWidth-1:0]     in_tag_i,
  input  logic [31:0]             in_split_i,   // fp32 bits from the node
  input  logic [NodeIdxWidth-1:0] in_below_i,   // node index + 1
  input  logic [NodeIdxWidth-1:0] in_above_i,
  input  logic                    in_below_empty_i,  // the below child is an empty leaf
  input  logic                    in_above_empty_i,  // the above child is an empty leaf
  input  logic [W-1:0]            in_o_i,       // ray origin on the split axis
  input  logic [W-1:0]            in_d_i,       // ray direction on the split axis
  input  logic [TW-1:0]           in_inv_i,     // 1 / d on the split axis, traversal format
  input  logic [W-1:0]            in_t0_i,
  input  logic [W-1:0]            in_t1_i,
  output logic                    out_valid_o,
  input  logic                    out_ready_i,
  output logic [TagWidth-1:0]     out_tag_o,
  output kdrt_pkg::trav_action_e  out_action_o,
  output logic [NodeIdxWidth-1:0] out_first_o,
  output logic [NodeIdxWidth-1:0] out_second_o,
  output logic                    out_first_empty_o,
  output logic                    out_second_empty_o,
  output logic [TW-1:0]           out_ts_o,     // traversal format
  output logic [W-1:0]            out_ts_lo_o,  // ts nudged down: the far child's start
  output logic [W-1:0]            out_ts_hi_o,  // ts nudged up: the near child's end
  output logic [W-1:0]            out_t0_o,
  output logic [W-1:0]            out_t1_o
);

  localparam int unsigned LConv = kdrt_fp_pkg::FpFromF32Latency;
  localparam int unsigned LAdd = kdrt_fp_pkg::FpAddLatency;
  localparam int unsigned LMul = kdrt_fp_pkg::FpMulLatency;
  localparam bit Mixed = TravE != E || TravM != M;
  /* verilator lint_off UNUSEDPARAM */
  localparam int unsigned Latency = LConv + LAdd + LMul + (Mixed ? LConv : 0);
  /* verilator lint_on UNUSEDPARAM */

  logic en;
  assign en = !out_valid_o || out_ready_i;
  assign in_ready_o = en;

  // Stage group 1: load the split.
  logic         v1;
  logic [W-1:0] split;
  fp_from_f32 #(.E(E), .M(M)) u_conv (
    .clk_i, .rst_ni, .en_i(en), .valid_i(in_valid_i), .f32_i(in_split_i),
    .valid_o(v1), .res_o(split)
  );
  // A child: its index and its empty mark.
  localparam int unsigned CW = NodeIdxWidth + 1;
  localparam int unsigned SideW = TagWidth + 2 * CW + 4 * W + TW;
  logic [SideW-1:0] side0, side1;
  assign side0 = {in_tag_i, in_below_empty_i, in_below_i, in_above_empty_i, in_above_i, in_o_i, in_d_i, in_inv_i,
                  in_t0_i, in_t1_i};
  rt_delay #(.Width(SideW), .Depth(LConv)) u_side1 (.clk_i, .en_i(en), .d_i(side0), .q_o(side1));

  logic [TagWidth-1:0]     tag1;
  logic [CW-1:0]           below1, above1;
  logic [W-1:0]            o1, d1, t01, t11;
  logic [TW-1:0]           inv1;
  assign {tag1, below1, above1, o1, d1, inv1, t01, t11} = side1;

  // Which child is near: decided now, carried along.
  logic o_lt, o_eq, d_le0, below_first1;
  fp_cmp #(.E(E), .M(M), .Stages(0)) u_cmp_o (
    .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(o1), .b_i(split),
    .valid_o(), .lt_o(o_lt), .le_o(), .eq_o(o_eq), .min_o(), .max_o()
  );
  fp_cmp #(.E(E), .M(M), .Stages(0)) u_cmp_d (
    .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(d1), .b_i('0),
    .valid_o(), .lt_o(), .le_o(d_le0), .eq_o(), .min_o(), .max_o()
  );
  assign below_first1 = o_lt || (o_eq && d_le0);

  // The split and o in the traversal's format (exact).
  logic [TW-1:0] split_t, o1_t;
  fp_widen #(.E(E), .M(M), .WE(TravE), .WM(TravM)) u_widen_split (.a_i(split), .res_o(split_t));
  fp_widen #(.E(E), .M(M), .WE(TravE), .WM(TravM)) u_widen_o (.a_i(o1), .res_o(o1_t));

  // Stage group 2: split - o.
  logic          v2;
  logic [TW-1:0] diff;
  fp_add #(.E(TravE), .M(TravM)) u_sub (
    .clk_i, .rst_ni, .en_i(en), .valid_i(v1), .a_i(split_t), .b_i(o1_t), .sub_i(1'b1),
    .valid_o(v2), .res_o(diff)
  );
  localparam int unsigned Side2W = TagWidth + 2 * CW + 2 * W + TW + 1;
  logic [Side2W-1:0] side2;
  rt_delay #(.Width(Side2W), .Depth(LAdd)) u_side2 (
    .clk_i, .en_i(en), .d_i({tag1, below1, above1, inv1, t01, t11, below_first1}), .q_o(side2)
  );
  logic [TagWidth-1:0]     tag2;
  logic [CW-1:0]           below2, above2;
  logic [TW-1:0]           inv2;
  logic [W-1:0]            t02, t12;
  logic                    bf2;
  assign {tag2, below2, above2, inv2, t02, t12, bf2} = side2;

  // Stage group 3: ts = diff * inv, and its nudged ends.
  logic          v3;
  logic [TW-1:0] ts3, lo3, hi3;
  fp_mul #(.E(TravE), .M(TravM)) u_mul (
    .clk_i, .rst_ni, .en_i(en), .valid_i(v2), .a_i(diff), .b_i(inv2),
    .valid_o(v3), .res_o(ts3)
  );
  localparam int unsigned Side3W = TagWidth + 2 * CW + 2 * W + 1;
  logic [Side3W-1:0] side3;
  rt_delay #(.Width(Side3W), .Depth(LMul)) u_side3 (
    .clk_i, .en_i(en), .d_i({tag2, below2, above2, t02, t12, bf2}), .q_o(side3)
  );
  fp_nudge #(.E(TravE), .M(TravM), .K(SlackUlps)) u_nudge (.a_i(ts3), .up_o(hi3), .down_o(lo3));

  // The ends in the test's format: as they are, or moved outwards into it.
  logic [CW-1:0]           below3, above3;
  logic                    bf3;
  if (Mixed) begin : g_round_out
    fp_round_out #(.E(E), .M(M), .WE(TravE), .WM(TravM), .Up(1'b0)) u_lo (
      .clk_i, .rst_ni, .en_i(en), .valid_i(v3), .a_i(lo3), .valid_o(out_valid_o), .res_o(out_ts_lo_o)
    );
    fp_round_out #(.E(E), .M(M), .WE(TravE), .WM(TravM), .Up(1'b1)) u_hi (
      .clk_i, .rst_ni, .en_i(en), .valid_i(v3), .a_i(hi3), .valid_o(), .res_o(out_ts_hi_o)
    );
    rt_delay #(.Width(Side3W + TW), .Depth(LConv)) u_side4 (
      .clk_i, .en_i(en), .d_i({side3, ts3}),
      .q_o({out_tag_o, below3, above3, out_t0_o, out_t1_o, bf3, out_ts_o})
    );
  end else begin : g_same_ends
    assign out_valid_o = v3;
    assign out_ts_o = ts3;
    assign out_ts_lo_o = lo3;
    assign out_ts_hi_o = hi3;
    assign {out_tag_o, below3, above3, out_t0_o, out_t1_o, bf3} = side3;
  end

  // Decision on the pipeline's output.
  logic t1_lt_ts, ts_le0, ts_lt_t0;
  fp_cmp #(.E(E), .M(M), .Stages(0)) u_cmp_far (
    .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(out_t1_o), .b_i(out_ts_lo_o),
    .valid_o(), .lt_o(t1_lt_ts), .le_o(), .eq_o(), .min_o(), .max_o()
  );
  fp_cmp #(.E(TravE), .M(TravM), .Stages(0)) u_cmp_zero (
    .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(out_ts_o), .b_i('0),
    .valid_o(), .lt_o(), .le_o(ts_le0), .eq_o(), .min_o(), .max_o()
  );
  fp_cmp #(.E(E), .M(M), .Stages(0)) u_cmp_near (
    .clk_i, .rst_ni, .en_i(en), .valid_i(1'b1), .a_i(out_ts_hi_o), .b_i(out_t0_o),
    .valid_o(), .lt_o(ts_lt_t0), .le_o(), .eq_o(), .min_o(), .max_o()
  );
  assign {out_first_empty_o, out_first_o} = bf3 ? below3 : above3;
  assign {out_second_empty_o, out_second_o} = bf3 ? above3 : below3;
  assign out_action_o = (t1_lt_ts || ts_le0) ? kdrt_pkg::TravFirst
                       : (ts_lt_t0 ? kdrt_pkg::TravSecond : kdrt_pkg::TravPush);

  // picorv32's stream rule on both sides.
  rt_stream_check #(.Width(SideW + 32), .Name("rt_trav_unit in")) u_in_check (
    .clk_i, .rst_ni, .valid_i(in_valid_i), .ready_i(in_ready_o), .payload_i({side0, in_split_i})
  );
  rt_stream_check #(.Width(TagWidth + 2 + 2 * CW + 4 * W + TW), .Name("rt_trav_unit out")) u_out_check (
    .clk_i, .rst_ni, .valid_i(out_valid_o), .ready_i(out_ready_i),
    .payload_i({out_tag_o, out_action_o, out_first_empty_o, out_first_o, out_second_empty_o, out_second_o, out_ts_o,
                out_ts_lo_o, out_ts_hi_o, out_t0_o, out_t1_o})
  );

endmodule

`default_nettype wire
