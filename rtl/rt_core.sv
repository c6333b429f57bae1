// rt_core: one kdrt ray tracing core (docs/core-interface.md).
//
// Threads rays are in flight at once; each has a slot in the thread table
// (ray, interval, closest hit, traversal stack) and is in one of the states
// below. The units are shared pipelines that any thread may use, each taking
// one request per cycle, so while some threads wait for memory others keep
// the units busy (SaarCOR, the T&I engine):
//
//   ray in -> rt_ray_setup -> rt_clip_unit -> FETCH
//   FETCH -> node cache -> WAIT_NODE -> inner: rt_trav_unit -> FETCH (push/descend)
//                                    -> leaf:  list unit -> LEAF -> EXIT
//   list unit: list cache -> triangle cache -> rt_isect_unit -> closest-hit merge
//   EXIT (leaf done): finished, or pop the stack -> FETCH
//   DONE -> hit out -> FREE
//
// The operations and decisions are exactly the model's (sw/trace/traversal.h,
// docs/dataflow.md), so the hit records are bit-identical to `kdrt render
// --format` whatever the memory latency and the interleaving of threads.
`default_nettype none
// Unused outputs of the shared fp_cmp are left open on purpose.
/* verilator lint_off PINCONNECTEMPTY */

module rt_core #(
  parameter int unsigned E /*verilator public*/ = 8,
  parameter int unsigned M /*verilator public*/ = 23,
  parameter int unsigned Threads /*verilator public*/ = 16,
  parameter int unsigned StackDepth /*verilator public*/ = 32,
  parameter int unsigned NodeIdxWidth /*verilator public*/ = 24,
  parameter int unsigned TriIdxWidth /*verilator public*/ = 24,
  parameter int unsigned AddrWidth /*verilator public*/ = 28,
  parameter int unsigned NodeCacheLines /*verilator public*/ = 64,
  parameter int unsigned ListCacheLines /*verilator public*/ = 64,
  parameter int unsigned TriCacheLines /*verilator public*/ = 64,
  parameter int unsigned NodeLineBeats = 2,
  parameter int unsigned ListLineBeats = 2,
  parameter int unsigned RayIdWidth = 32,
  // Miss registers per cache (outstanding line fetches); at most 16.
  parameter int unsigned CacheMshrs = 8,
  localparam int unsigned W = E + M + 1,
  localparam int unsigned ThW = (Threads > 1) ? $clog2(Threads) : 1
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // configuration (image header), stable while busy
  input  logic [AddrWidth-1:0]  node_base_i,
  input  logic [AddrWidth-1:0]  list_base_i,
  input  logic [AddrWidth-1:0]  tri_base_i,
  input  logic [95:0]           bounds_min_i,
  input  logic [95:0]           bounds_max_i,
  // rays in
  input  logic                  ray_valid_i,
  output logic                  ray_ready_o,
  input  logic [RayIdWidth-1:0] ray_id_i,
  input  logic [255:0]          ray_i,
  // hits out
  output logic                  hit_valid_o,
  input  logic                  hit_ready_i,
  output logic [RayIdWidth-1:0] hit_ray_id_o,
  output logic                  hit_o,
  output logic [31:0]           hit_prim_o,
  output logic [31:0]           hit_t_o,
  output logic [31:0]           hit_u_o,
  output logic [31:0]           hit_v_o,
  output logic                  hit_overflow_o,
  // memory
  output logic                  mem_req_valid_o,
  input  logic                  mem_req_ready_i,
  output logic [AddrWidth-1:0]  mem_req_addr_o,
  output logic [7:0]            mem_req_tag_o,
  input  logic                  mem_resp_valid_i,
  input  logic [7:0]            mem_resp_tag_i,
  input  logic [127:0]          mem_resp_data_i,
  // status
  output logic                  busy_o,
  output logic [15:0]           perf_o
);

  localparam int unsigned SpW = $clog2(StackDepth + 1);
  localparam int unsigned CountW = TriIdxWidth + 1;
  localparam int unsigned NodeLineBytes = 16 * NodeLineBeats;
  localparam int unsigned ListLineBytes = 16 * ListLineBeats;
  localparam int unsigned NodeOffW = $clog2(NodeLineBytes);
  localparam int unsigned ListOffW = $clog2(ListLineBytes);
  localparam int unsigned NodeKeyW = AddrWidth - NodeOffW;
  localparam int unsigned ListKeyW = AddrWidth - ListOffW;
  localparam int unsigned StackW = NodeIdxWidth + 2 * W;

  typedef enum logic [2:0] {
    SFree, SSetup, SFetch, SWaitNode, STrav, SLeaf, SExit, SDone
  } state_e;

  // ------------------------------------------------------------ thread table
  state_e                  state_q [Threads];
  logic [RayIdWidth-1:0]   ray_id_q [Threads];
  logic [3*W-1:0]          o_q [Threads];
  logic [3*W-1:0]          d_q [Threads];
  logic [3*W-1:0]          inv_q [Threads];
  logic [3*W-1:0]          shear_q [Threads];  // sx, sy, sz
  logic [5:0]              axes_q [Threads];   // kz, ky, kx (2 bits each)
  logic [W-1:0]            tmin_q [Threads];
  logic [NodeIdxWidth-1:0] node_q [Threads];
  logic [W-1:0]            t0_q [Threads];
  logic [W-1:0]            t1_q [Threads];
  logic [W-1:0]            best_t_q [Threads];
  logic [W-1:0]            best_u_q [Threads];
  logic [W-1:0]            best_v_q [Threads];
  logic [TriIdxWidth-1:0]  best_prim_q [Threads];
  logic [Threads-1:0]      hit_q;
  logic [Threads-1:0]      ovf_q;
  logic [W-1:0]            leaf_tmax_q [Threads];
  logic [CountW-1:0]       remaining_q [Threads];
  logic [CountW-1:0]       outstanding_q [Threads];
  logic [SpW-1:0]          sp_q [Threads];
  logic [StackW-1:0]       stack_q [Threads * StackDepth];

  logic [Threads-1:0] is_free, is_fetch, is_exit, is_done, is_leaf_done;
  for (genvar t = 0; t < Threads; t++) begin : g_state
    assign is_free[t] = state_q[t] == SFree;
    assign is_fetch[t] = state_q[t] == SFetch;
    assign is_exit[t] = state_q[t] == SExit;
    assign is_done[t] = state_q[t] == SDone;
    assign is_leaf_done[t] = state_q[t] == SLeaf && remaining_q[t] == '0 && outstanding_q[t] == '0;
  end
  assign busy_o = ~&is_free;

  // ------------------------------------------------------------ (A) ray in
  logic          alloc_valid;
  logic [ThW-1:0] alloc_idx;
  always_comb begin
    alloc_valid = 1'b0;
    alloc_idx = '0;
    for (int t = Threads - 1; t >= 0; t--) begin
      if (is_free[t]) begin
        alloc_valid = 1'b1;
        alloc_idx = ThW'(t);
      end
    end
  end

  logic setup_in_ready, ray_fire;
  assign ray_ready_o = alloc_valid && setup_in_ready;
  assign ray_fire = ray_valid_i && ray_ready_o;

  // ------------------------------------------------------------ (B) setup
  logic           setup_valid, clip_in_ready, setup_fire;
  logic [ThW-1:0] setup_tag;
  logic [3*W-1:0] setup_o, setup_d, setup_inv;
  logic [W-1:0]   setup_tmin, setup_tmax, setup_sx, setup_sy, setup_sz;
  logic [1:0]     setup_kx, setup_ky, setup_kz;

  rt_ray_setup #(.E(E), .M(M), .TagWidth(ThW)) u_setup (
    .clk_i, .rst_ni,
    .in_valid_i (ray_fire),
    .in_ready_o (setup_in_ready),
    .in_tag_i   (alloc_idx),
    .in_ray_i   (ray_i),
    .out_valid_o(setup_valid),
    .out_ready_i(clip_in_ready),
    .out_tag_o  (setup_tag),
    .out_o_o    (setup_o),
    .out_d_o    (setup_d),
    .out_inv_o  (setup_inv),
    .out_tmin_o (setup_tmin),
    .out_tmax_o (setup_tmax),
    .out_kx_o   (setup_kx),
    .out_ky_o   (setup_ky),
    .out_kz_o   (setup_kz),
    .out_sx_o   (setup_sx),
    .out_sy_o   (setup_sy),
    .out_sz_o   (setup_sz)
  );
  assign setup_fire = setup_valid && clip_in_ready;

  // ------------------------------------------------------------ (C) clip
  logic           clip_valid, clip_miss;
  logic [ThW-1:0] clip_tag;
  logic [W-1:0]   clip_t0, clip_t1;
  rt_clip_unit #(.E(E), .M(M), .TagWidth(ThW)) u_clip (
    .clk_i, .rst_ni,
    .bounds_min_i, .bounds_max_i,
    .in_valid_i (setup_valid),
    .in_ready_o (clip_in_ready),
    .in_tag_i   (setup_tag),
    .in_o_i     (setup_o),
    .in_inv_i   (setup_inv),
    .in_tmin_i  (setup_tmin),
    .in_tmax_i  (setup_tmax),
    .out_valid_o(clip_valid),
    .out_ready_i(1'b1),
    .out_tag_o  (clip_tag),
    .out_t0_o   (clip_t0),
    .out_t1_o   (clip_t1),
    .out_miss_o (clip_miss)
  );

  // ------------------------------------------------------------ (D) node fetch
  logic           fetch_valid, node_req_ready, fetch_fire;
  logic [ThW-1:0] fetch_idx;
  rt_rr_arb #(.N(Threads)) u_fetch_arb (
    .clk_i, .rst_ni, .req_i(is_fetch), .ack_i(node_req_ready), .valid_o(fetch_valid), .idx_o(fetch_idx)
  );
  assign fetch_fire = fetch_valid && node_req_ready;
  logic [AddrWidth-1:0] fetch_addr;
  assign fetch_addr = node_base_i + (AddrWidth'(node_q[fetch_idx]) << 3);

  // Node cache response.
  logic                        node_resp_valid, node_resp_ready, node_resp_fire;
  logic [NodeLineBeats*128-1:0] node_line;
  logic [ThW-1:0]              node_tag;
  logic [AddrWidth-1:0]        node_addr;
  logic [31:0]                 node_w0, node_w1;
  logic                        node_is_leaf;
  logic [1:0]                  node_axis;
  assign node_addr = node_base_i + (AddrWidth'(node_q[node_tag]) << 3);
  assign {node_w1, node_w0} = node_line[64 * node_addr[NodeOffW-1:3] +: 64];
  assign node_axis = node_w1[1:0];
  assign node_is_leaf = node_axis == 2'd3;

  // ------------------------------------------------------------ (E, F) traversal
  logic                    trav_in_ready, trav_fire;
  logic                    trav_valid;
  logic [ThW-1:0]          trav_tag;
  logic [1:0]              trav_action;
  logic [NodeIdxWidth-1:0] trav_first, trav_second;
  logic [W-1:0]            trav_ts, trav_ts_lo, trav_ts_hi, trav_t0, trav_t1;
  assign node_resp_ready = node_is_leaf || trav_in_ready;
  assign node_resp_fire = node_resp_valid && node_resp_ready;
  assign trav_fire = node_resp_fire && !node_is_leaf;

  rt_trav_unit #(.E(E), .M(M), .TagWidth(ThW), .NodeIdxWidth(NodeIdxWidth)) u_trav (
    .clk_i, .rst_ni,
    .in_valid_i  (node_resp_valid && !node_is_leaf),
    .in_ready_o  (trav_in_ready),
    .in_tag_i    (node_tag),
    .in_split_i  (node_w0),
    .in_below_i  (node_q[node_tag] + 1'b1),
    .in_above_i  (NodeIdxWidth'(node_w1[31:2])),
    .in_o_i      (o_q[node_tag][W*node_axis +: W]),
    .in_d_i      (d_q[node_tag][W*node_axis +: W]),
    .in_inv_i    (inv_q[node_tag][W*node_axis +: W]),
    .in_t0_i     (t0_q[node_tag]),
    .in_t1_i     (t1_q[node_tag]),
    .out_valid_o (trav_valid),
    .out_ready_i (1'b1),
    .out_tag_o   (trav_tag),
    .out_action_o(trav_action),
    .out_first_o (trav_first),
    .out_second_o(trav_second),
    .out_ts_o    (trav_ts),
    .out_ts_lo_o (trav_ts_lo),
    .out_ts_hi_o (trav_ts_hi),
    .out_t0_o    (trav_t0),
    .out_t1_o    (trav_t1)
  );
  logic trav_push, trav_overflow;
  assign trav_push = trav_valid && trav_action == 2'd2;
  assign trav_overflow = trav_push && sp_q[trav_tag] == SpW'(StackDepth);

  // ------------------------------------------------------------ (G) list unit
  // Leaf jobs wait in a FIFO (one per thread at most, so it never fills).
  logic                    job_push, job_pop, job_valid;
  logic [ThW-1:0]          job_tag;
  logic [31:0]             job_first;
  logic [CountW-1:0]       job_count;
  assign job_push = node_resp_fire && node_is_leaf && node_w1[31:2] != '0;

  logic [ThW+32+CountW-1:0] fifo_q [Threads];
  logic [ThW:0]             fifo_rd_q, fifo_wr_q;
  assign job_valid = fifo_rd_q != fifo_wr_q;
  assign {job_tag, job_first, job_count} = fifo_q[fifo_rd_q[ThW-1:0]];

  // The active job walks its list one entry per cycle.
  logic                 walk_active_q;
  logic [ThW-1:0]       walk_tag_q;
  logic [AddrWidth-1:0] walk_addr_q;
  logic [CountW-1:0]    walk_left_q;
  assign job_pop = job_valid && (!walk_active_q);

  logic                         list_req_ready, list_req_fire;
  logic                         list_resp_valid, list_resp_ready, list_resp_fire;
  logic [ListLineBeats*128-1:0] list_line;
  logic [ThW+ListOffW-1:0]      list_resp_tag;
  assign list_req_fire = walk_active_q && list_req_ready;

  logic [ThW-1:0]       entry_tag;
  logic [ListOffW-1:0]  entry_off;
  logic [31:0]          entry_id;
  assign {entry_tag, entry_off} = list_resp_tag;
  assign entry_id = list_line[32 * entry_off[ListOffW-1:2] +: 32];

  logic                 tri_req_ready, tri_resp_valid, tri_resp_fire;
  logic [383:0]         tri_line;
  logic [ThW+TriIdxWidth-1:0] tri_resp_tag;
  logic [ThW-1:0]       tri_tag;
  logic [TriIdxWidth-1:0] tri_id;
  assign {tri_tag, tri_id} = tri_resp_tag;
  assign list_resp_ready = tri_req_ready;
  assign list_resp_fire = list_resp_valid && list_resp_ready;

  // ------------------------------------------------------------ (H, I) intersection
  logic isect_in_ready, isect_valid, isect_hit;
  logic [ThW-1:0] isect_tag;
  logic [31:0] isect_id;
  logic [W-1:0] isect_t, isect_u, isect_v;
  assign tri_resp_fire = tri_resp_valid && isect_in_ready;

  rt_isect_unit #(.E(E), .M(M), .TagWidth(ThW)) u_isect (
    .clk_i, .rst_ni,
    .in_valid_i (tri_resp_valid),
    .in_ready_o (isect_in_ready),
    .in_tag_i   (tri_tag),
    .in_id_i    (32'(tri_id)),
    .in_o_i     (o_q[tri_tag]),
    .in_kx_i    (axes_q[tri_tag][1:0]),
    .in_ky_i    (axes_q[tri_tag][3:2]),
    .in_kz_i    (axes_q[tri_tag][5:4]),
    .in_sx_i    (shear_q[tri_tag][0 +: W]),
    .in_sy_i    (shear_q[tri_tag][W +: W]),
    .in_sz_i    (shear_q[tri_tag][2*W +: W]),
    .in_tmin_i  (tmin_q[tri_tag]),
    .in_tmax_i  (leaf_tmax_q[tri_tag]),
    .in_tri_i   (tri_line[287:0]),
    .out_valid_o(isect_valid),
    .out_ready_i(1'b1),
    .out_tag_o  (isect_tag),
    .out_id_o   (isect_id),
    .out_hit_o  (isect_hit),
    .out_t_o    (isect_t),
    .out_u_o    (isect_u),
    .out_v_o    (isect_v)
  );

  // Closest-hit merge: smaller t wins, equal t goes to the smaller id.
  logic t_lt_best, t_eq_best, take_hit;
  fp_cmp #(.E(E), .M(M), .Stages(0)) u_cmp_best (
    .clk_i, .rst_ni, .en_i(1'b1), .valid_i(1'b1), .a_i(isect_t), .b_i(best_t_q[isect_tag]),
    .valid_o(), .lt_o(t_lt_best), .le_o(), .eq_o(t_eq_best), .min_o(), .max_o()
  );
  assign take_hit = isect_valid && isect_hit &&
                    (t_lt_best || (t_eq_best && (!hit_q[isect_tag] ||
                                                 TriIdxWidth'(isect_id) < best_prim_q[isect_tag])));

  // ------------------------------------------------------------ (K) leaf exit
  logic           exit_valid, exit_fire;
  logic [ThW-1:0] exit_idx;
  rt_rr_arb #(.N(Threads)) u_exit_arb (
    .clk_i, .rst_ni, .req_i(is_exit), .ack_i(1'b1), .valid_o(exit_valid), .idx_o(exit_idx)
  );
  assign exit_fire = exit_valid;
  logic [SpW-1:0]          exit_sp;
  logic [StackW-1:0]       exit_top;
  logic [NodeIdxWidth-1:0] pop_node;
  logic [W-1:0]            pop_t0, pop_t1;
  assign exit_sp = sp_q[exit_idx];
  assign exit_top = stack_q[32'(exit_idx) * StackDepth + ((exit_sp == '0) ? 0 : 32'(exit_sp) - 1)];
  assign {pop_node, pop_t0, pop_t1} = exit_top;
  logic best_le_t1, best_lt_pop;
  fp_cmp #(.E(E), .M(M), .Stages(0)) u_cmp_exit (
    .clk_i, .rst_ni, .en_i(1'b1), .valid_i(1'b1), .a_i(best_t_q[exit_idx]), .b_i(t1_q[exit_idx]),
    .valid_o(), .lt_o(), .le_o(best_le_t1), .eq_o(), .min_o(), .max_o()
  );
  fp_cmp #(.E(E), .M(M), .Stages(0)) u_cmp_pop (
    .clk_i, .rst_ni, .en_i(1'b1), .valid_i(1'b1), .a_i(best_t_q[exit_idx]), .b_i(pop_t0),
    .valid_o(), .lt_o(best_lt_pop), .le_o(), .eq_o(), .min_o(), .max_o()
  );
  logic exit_done;
  assign exit_done = (hit_q[exit_idx] && best_le_t1) || exit_sp == '0 ||
                     (hit_q[exit_idx] && best_lt_pop);

  // ------------------------------------------------------------ (L) hit out
  logic           out_valid, out_fire, hit_slot_free;
  logic [ThW-1:0] out_idx;
  assign hit_slot_free = !hit_valid_o || hit_ready_i;
  rt_rr_arb #(.N(Threads)) u_out_arb (
    .clk_i, .rst_ni, .req_i(is_done), .ack_i(hit_slot_free), .valid_o(out_valid), .idx_o(out_idx)
  );
  assign out_fire = out_valid && hit_slot_free;
  logic [31:0] wide_t, wide_u, wide_v;
  fp_to_f32 #(.E(E), .M(M)) u_wide_t (.a_i(best_t_q[out_idx]), .f32_o(wide_t));
  fp_to_f32 #(.E(E), .M(M)) u_wide_u (.a_i(best_u_q[out_idx]), .f32_o(wide_u));
  fp_to_f32 #(.E(E), .M(M)) u_wide_v (.a_i(best_v_q[out_idx]), .f32_o(wide_v));

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      hit_valid_o <= 1'b0;
    end else begin
      if (hit_valid_o && hit_ready_i) hit_valid_o <= 1'b0;
      if (out_fire) hit_valid_o <= 1'b1;
    end
  end
  always_ff @(posedge clk_i) begin
    if (out_fire) begin
      hit_ray_id_o <= ray_id_q[out_idx];
      hit_o <= hit_q[out_idx];
      hit_prim_o <= hit_q[out_idx] ? 32'(best_prim_q[out_idx]) : 32'hFFFF_FFFF;
      hit_t_o <= hit_q[out_idx] ? wide_t : 32'h7F80_0000;
      hit_u_o <= hit_q[out_idx] ? wide_u : 32'h0;
      hit_v_o <= hit_q[out_idx] ? wide_v : 32'h0;
      hit_overflow_o <= ovf_q[out_idx];
    end
  end

  // ------------------------------------------------------------ thread table updates
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int t = 0; t < Threads; t++) state_q[t] <= SFree;
      fifo_rd_q <= '0;
      fifo_wr_q <= '0;
      walk_active_q <= 1'b0;
    end else begin
      if (ray_fire) state_q[alloc_idx] <= SSetup;
      if (clip_valid) state_q[clip_tag] <= clip_miss ? SDone : SFetch;
      if (fetch_fire) state_q[fetch_idx] <= SWaitNode;
      if (node_resp_fire) begin
        if (!node_is_leaf) state_q[node_tag] <= STrav;
        else state_q[node_tag] <= job_push ? SLeaf : SExit;
      end
      if (trav_valid) state_q[trav_tag] <= trav_overflow ? SDone : SFetch;
      for (int t = 0; t < Threads; t++) begin
        if (is_leaf_done[t]) state_q[t] <= SExit;
      end
      if (exit_fire) state_q[exit_idx] <= exit_done ? SDone : SFetch;
      if (out_fire) state_q[out_idx] <= SFree;

      if (job_push) begin
        fifo_q[fifo_wr_q[ThW-1:0]] <= {node_tag, node_w0, CountW'(node_w1[31:2])};
        fifo_wr_q <= (fifo_wr_q[ThW-1:0] == ThW'(Threads - 1)) ? {~fifo_wr_q[ThW], {ThW{1'b0}}}
                                                               : fifo_wr_q + 1'b1;
      end
      if (job_pop) begin
        fifo_rd_q <= (fifo_rd_q[ThW-1:0] == ThW'(Threads - 1)) ? {~fifo_rd_q[ThW], {ThW{1'b0}}}
                                                               : fifo_rd_q + 1'b1;
        walk_active_q <= 1'b1;
      end else if (list_req_fire && walk_left_q == CountW'(1)) begin
        walk_active_q <= 1'b0;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (job_pop) begin
      walk_tag_q <= job_tag;
      walk_addr_q <= list_base_i + (AddrWidth'(job_first) << 2);
      walk_left_q <= job_count;
    end else if (list_req_fire) begin
      walk_addr_q <= walk_addr_q + AddrWidth'(4);
      walk_left_q <= walk_left_q - 1'b1;
    end

    if (ray_fire) ray_id_q[alloc_idx] <= ray_id_i;
    if (setup_fire) begin
      o_q[setup_tag] <= setup_o;
      d_q[setup_tag] <= setup_d;
      inv_q[setup_tag] <= setup_inv;
      shear_q[setup_tag] <= {setup_sz, setup_sy, setup_sx};
      axes_q[setup_tag] <= {setup_kz, setup_ky, setup_kx};
      tmin_q[setup_tag] <= setup_tmin;
      best_t_q[setup_tag] <= setup_tmax;
      best_u_q[setup_tag] <= '0;
      best_v_q[setup_tag] <= '0;
      best_prim_q[setup_tag] <= '1;
      hit_q[setup_tag] <= 1'b0;
      ovf_q[setup_tag] <= 1'b0;
      sp_q[setup_tag] <= '0;
      node_q[setup_tag] <= '0;
      remaining_q[setup_tag] <= '0;
      outstanding_q[setup_tag] <= '0;
    end
    if (clip_valid) begin
      t0_q[clip_tag] <= clip_t0;
      t1_q[clip_tag] <= clip_t1;
    end
    if (job_push) begin
      remaining_q[node_tag] <= CountW'(node_w1[31:2]);
      leaf_tmax_q[node_tag] <= best_t_q[node_tag];
    end
    if (trav_valid) begin
      case (trav_action)
        2'd0: node_q[trav_tag] <= trav_first;
        2'd1: node_q[trav_tag] <= trav_second;
        default: begin
          node_q[trav_tag] <= trav_first;
          t1_q[trav_tag] <= trav_ts_hi;
          if (trav_overflow) begin
            ovf_q[trav_tag] <= 1'b1;
          end else begin
            stack_q[32'(trav_tag) * StackDepth + 32'(sp_q[trav_tag])] <= {trav_second, trav_ts_lo, trav_t1};
            sp_q[trav_tag] <= sp_q[trav_tag] + 1'b1;
          end
        end
      endcase
    end
    // Tests issued and results returned, possibly for one thread at once.
    for (int t = 0; t < Threads; t++) begin
      logic issue, retire;
      issue = tri_resp_fire && tri_tag == ThW'(t);
      retire = isect_valid && isect_tag == ThW'(t);
      if (issue) remaining_q[t] <= remaining_q[t] - 1'b1;
      if (issue && !retire) outstanding_q[t] <= outstanding_q[t] + 1'b1;
      if (!issue && retire) outstanding_q[t] <= outstanding_q[t] - 1'b1;
    end
    if (take_hit) begin
      best_t_q[isect_tag] <= isect_t;
      best_u_q[isect_tag] <= isect_u;
      best_v_q[isect_tag] <= isect_v;
      best_prim_q[isect_tag] <= TriIdxWidth'(isect_id);
      hit_q[isect_tag] <= 1'b1;
    end
    if (exit_fire && !exit_done) begin
      node_q[exit_idx] <= pop_node;
      t0_q[exit_idx] <= pop_t0;
      t1_q[exit_idx] <= pop_t1;
      sp_q[exit_idx] <= exit_sp - 1'b1;
    end
  end

  // ------------------------------------------------------------ caches and memory
  logic                 node_mem_valid, list_mem_valid, tri_mem_valid;
  logic [2:0]           mem_ready, mem_resp_valid;
  logic [AddrWidth-1:0] node_mem_addr, list_mem_addr, tri_mem_addr;
  // A cache's memory id: {miss register, beat}.
  localparam int unsigned MemIdW = ((CacheMshrs > 1) ? $clog2(CacheMshrs) : 1) + 2;
  logic [MemIdW-1:0]    node_mem_id, list_mem_id, tri_mem_id, mem_resp_id;
  logic [127:0]         mem_resp_data;
  logic                 node_hit, node_miss, list_hit, list_miss, tri_hit, tri_miss;
  logic                 node_filling, list_filling, tri_filling;

  rt_cache #(.Lines(NodeCacheLines), .LineBeats(NodeLineBeats), .KeyWidth(NodeKeyW),
             .AddrWidth(AddrWidth), .TagWidth(ThW), .Mshrs(CacheMshrs)) u_node_cache (
    .clk_i, .rst_ni,
    .req_valid_i    (fetch_valid),
    .req_ready_o    (node_req_ready),
    .req_key_i      (fetch_addr[AddrWidth-1:NodeOffW]),
    .req_addr_i     ({fetch_addr[AddrWidth-1:NodeOffW], {NodeOffW{1'b0}}}),
    .req_tag_i      (fetch_idx),
    .resp_valid_o   (node_resp_valid),
    .resp_ready_i   (node_resp_ready),
    .resp_data_o    (node_line),
    .resp_tag_o     (node_tag),
    .mem_req_valid_o(node_mem_valid),
    .mem_req_ready_i(mem_ready[0]),
    .mem_req_addr_o (node_mem_addr),
    .mem_req_id_o   (node_mem_id),
    .mem_resp_valid_i(mem_resp_valid[0]),
    .mem_resp_id_i  (mem_resp_id),
    .mem_resp_data_i(mem_resp_data),
    .hit_o          (node_hit),
    .miss_o         (node_miss),
    .filling_o      (node_filling)
  );

  rt_cache #(.Lines(ListCacheLines), .LineBeats(ListLineBeats), .KeyWidth(ListKeyW),
             .AddrWidth(AddrWidth), .TagWidth(ThW + ListOffW), .Mshrs(CacheMshrs)) u_list_cache (
    .clk_i, .rst_ni,
    .req_valid_i    (walk_active_q),
    .req_ready_o    (list_req_ready),
    .req_key_i      (walk_addr_q[AddrWidth-1:ListOffW]),
    .req_addr_i     ({walk_addr_q[AddrWidth-1:ListOffW], {ListOffW{1'b0}}}),
    .req_tag_i      ({walk_tag_q, walk_addr_q[ListOffW-1:0]}),
    .resp_valid_o   (list_resp_valid),
    .resp_ready_i   (list_resp_ready),
    .resp_data_o    (list_line),
    .resp_tag_o     (list_resp_tag),
    .mem_req_valid_o(list_mem_valid),
    .mem_req_ready_i(mem_ready[1]),
    .mem_req_addr_o (list_mem_addr),
    .mem_req_id_o   (list_mem_id),
    .mem_resp_valid_i(mem_resp_valid[1]),
    .mem_resp_id_i  (mem_resp_id),
    .mem_resp_data_i(mem_resp_data),
    .hit_o          (list_hit),
    .miss_o         (list_miss),
    .filling_o      (list_filling)
  );

  // A triangle line is one 48-byte record, named by the triangle id.
  logic [TriIdxWidth-1:0] entry_tri;
  assign entry_tri = TriIdxWidth'(entry_id);
  rt_cache #(.Lines(TriCacheLines), .LineBeats(3), .KeyWidth(TriIdxWidth),
             .AddrWidth(AddrWidth), .TagWidth(ThW + TriIdxWidth), .Mshrs(CacheMshrs)) u_tri_cache (
    .clk_i, .rst_ni,
    .req_valid_i    (list_resp_valid),
    .req_ready_o    (tri_req_ready),
    .req_key_i      (entry_tri),
    .req_addr_i     (tri_base_i + AddrWidth'(entry_tri) * AddrWidth'(48)),
    .req_tag_i      ({entry_tag, entry_tri}),
    .resp_valid_o   (tri_resp_valid),
    .resp_ready_i   (isect_in_ready),
    .resp_data_o    (tri_line),
    .resp_tag_o     (tri_resp_tag),
    .mem_req_valid_o(tri_mem_valid),
    .mem_req_ready_i(mem_ready[2]),
    .mem_req_addr_o (tri_mem_addr),
    .mem_req_id_o   (tri_mem_id),
    .mem_resp_valid_i(mem_resp_valid[2]),
    .mem_resp_id_i  (mem_resp_id),
    .mem_resp_data_i(mem_resp_data),
    .hit_o          (tri_hit),
    .miss_o         (tri_miss),
    .filling_o      (tri_filling)
  );

  rt_mem_arb #(.N(3), .AddrWidth(AddrWidth), .IdW(MemIdW)) u_mem_arb (
    .clk_i, .rst_ni,
    .req_valid_i    ({tri_mem_valid, list_mem_valid, node_mem_valid}),
    .req_ready_o    (mem_ready),
    .req_addr_i     ({tri_mem_addr, list_mem_addr, node_mem_addr}),
    .req_id_i       ({tri_mem_id, list_mem_id, node_mem_id}),
    .resp_valid_o   (mem_resp_valid),
    .resp_id_o      (mem_resp_id),
    .resp_data_o    (mem_resp_data),
    .mem_req_valid_o,
    .mem_req_ready_i,
    .mem_req_addr_o,
    .mem_req_tag_o,
    .mem_resp_valid_i,
    .mem_resp_tag_i,
    .mem_resp_data_i
  );

  // Address bits below a line, the record's id and padding words, and id
  // bits above TriIdxWidth (zero for a scene the parameters fit) are unused.
  /* verilator lint_off UNUSEDSIGNAL */
  logic unused_bits;
  assign unused_bits = ^{fetch_addr, node_addr, trav_t0, trav_ts, entry_off, entry_id, tri_line, isect_id};
  /* verilator lint_on UNUSEDSIGNAL */

  // ------------------------------------------------------------ stream rules
  rt_stream_check #(.Width(RayIdWidth + 256), .Name("rt_core ray in")) u_ray_check (
    .clk_i, .rst_ni, .valid_i(ray_valid_i), .ready_i(ray_ready_o), .payload_i({ray_id_i, ray_i})
  );
  rt_stream_check #(.Width(RayIdWidth + 1 + 4 * 32 + 1), .Name("rt_core hit out")) u_hit_check (
    .clk_i, .rst_ni, .valid_i(hit_valid_o), .ready_i(hit_ready_i),
    .payload_i({hit_ray_id_o, hit_o, hit_prim_o, hit_t_o, hit_u_o, hit_v_o, hit_overflow_o})
  );
  rt_stream_check #(.Width(AddrWidth + 8), .Name("rt_core memory request")) u_mem_check (
    .clk_i, .rst_ni, .valid_i(mem_req_valid_o), .ready_i(mem_req_ready_i),
    .payload_i({mem_req_addr_o, mem_req_tag_o})
  );

  // ------------------------------------------------------------ performance events
  logic any_progress, waiting_mem;
  assign any_progress = trav_fire || list_req_fire || list_resp_fire || tri_resp_fire || exit_fire ||
                        out_fire || ray_fire || clip_valid || trav_valid || isect_valid;
  assign waiting_mem = node_mem_valid || list_mem_valid || tri_mem_valid ||
                       node_filling || list_filling || tri_filling;
  assign perf_o[0] = trav_fire;
  assign perf_o[1] = list_req_fire || list_resp_fire;
  assign perf_o[2] = tri_resp_fire;
  assign perf_o[3] = node_hit;
  assign perf_o[4] = node_miss;
  assign perf_o[5] = list_hit;
  assign perf_o[6] = list_miss;
  assign perf_o[7] = tri_hit;
  assign perf_o[8] = tri_miss;
  assign perf_o[9] = busy_o && !any_progress && waiting_mem;
  assign perf_o[10] = (is_exit & ~(exit_valid ? (Threads'(1) << exit_idx) : '0)) != '0;
  assign perf_o[11] = (hit_valid_o && !hit_ready_i) || (tri_resp_valid && !isect_in_ready) ||
                      (node_resp_valid && !node_resp_ready);
  assign perf_o[12] = ray_fire;
  assign perf_o[13] = hit_valid_o && hit_ready_i;
  assign perf_o[14] = trav_overflow;
  assign perf_o[15] = node_resp_fire && node_is_leaf;

endmodule

`default_nettype wire
