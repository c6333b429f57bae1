// rt_core: one kdrt ray tracing core (docs/core-interface.md).
//
// Threads rays are in flight at once; each has a slot in the thread table
// (ray, interval, node), a closest hit (rt_hit_merge), a traversal stack
// (rt_leaf_exit) and a state (rt_thread_fsm), one of those below. The units
// are shared pipelines that any thread may use, each taking one request per
// cycle, so while some threads wait for memory others keep the units busy
// (SaarCOR, the T&I engine):
//
//   ray in -> rt_ray_setup (into the image's frame) -> rt_clip_unit -> FETCH
//   FETCH -> node cache -> WAIT_NODE -> inner: rt_trav_unit -> FETCH (push/descend)
//                                                             -> EXIT (into an empty leaf)
//                                    -> leaf:  rt_list_unit -> LEAF -> EXIT
//   rt_list_unit -> list cache -> triangle cache -> rt_isect_unit -> closest-hit merge
//   EXIT (leaf done): finished, or pop the stack -> FETCH (-> EXIT: popped an empty leaf)
//   DONE -> hit out (t back to world units) -> FREE
//
// An inner node marks its children that are empty leaves, and a thread never
// fetches one: it exits as it would after that leaf (the model's walk counts
// no node for it).
//
// The caches and the memory port are rt_mem_system. The operations and
// decisions are exactly the model's (sw/trace/traversal.h, docs/dataflow.md),
// so the hit records are bit-identical to `kdrt render --format` whatever the
// memory latency and the interleaving of threads.
`default_nettype none
// Unused outputs of the units are left open on purpose.
/* verilator lint_off PINCONNECTEMPTY */

module rt_core #(
  parameter int unsigned E /*verilator public*/ = 8,
  parameter int unsigned M /*verilator public*/ = 23,
  // The traversal's format (ray setup's 1 / d, box clip, traversal step): E, M
  // or a wider one; intervals and stacks stay in (E, M) (docs/dataflow.md).
  parameter int unsigned TravE /*verilator public*/ = E,
  parameter int unsigned TravM /*verilator public*/ = M,
  // The memory image's format (splits and vertices as stored): E, M or a
  // narrower one, widened exactly on load (docs/memory-image.md).
  parameter int unsigned ImgE /*verilator public*/ = E,
  parameter int unsigned ImgM /*verilator public*/ = M,
  parameter int unsigned Threads /*verilator public*/ = 128,
  parameter int unsigned StackDepth /*verilator public*/ = 32,
  parameter int unsigned NodeIdxWidth /*verilator public*/ = 24,
  parameter int unsigned TriIdxWidth /*verilator public*/ = 24,
  parameter int unsigned AddrWidth /*verilator public*/ = 28,
  parameter int unsigned NodeCacheLines /*verilator public*/ = 512,
  parameter int unsigned ListCacheLines /*verilator public*/ = 64,
  parameter int unsigned TriCacheLines /*verilator public*/ = 256,
  parameter int unsigned NodeLineBeats = 2,
  parameter int unsigned ListLineBeats = 2,
  parameter int unsigned RayIdWidth = 32,
  // Miss registers per cache (outstanding line fetches); the memory tag
  // {cache, miss register, beat} must fit 16 bits.
  parameter int unsigned CacheMshrs /*verilator public*/ = 128,
  // Requests each miss register answers: misses to a line already being
  // fetched join its register (1 = no merging; they wait for the fill).
  parameter int unsigned CacheTargets /*verilator public*/ = 4,
  // Lines per set of each cache (pseudo-LRU replacement): 1 = direct-mapped.
  parameter int unsigned CacheWays /*verilator public*/ = 4,
  // 1 (the default): the list unit asks for a leaf's entries
  // a list line at a time and the memory side hands them on one a cycle
  // (rt_list_unit, rt_mem_system); 0: one list request per entry.
  parameter int unsigned ListStream /*verilator public*/ = 1,
  // N > 0: the list unit prefetches the list lines of the next N jobs in its
  // queue through the list cache's prefetch port (rt_list_unit, rt_cache
  // PrefetchPort); 0: no prefetch.
  parameter int unsigned ListPrefetch /*verilator public*/ = 16,
  localparam int unsigned W = E + M + 1,
  localparam int unsigned TW = TravE + TravM + 1,
  localparam int unsigned IW = ImgE + ImgM + 1,
  localparam int unsigned ThW = (Threads > 1) ? $clog2(Threads) : 1
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // configuration (image header), stable while busy
  input  logic [AddrWidth-1:0]  node_base_i, list_base_i, tri_base_i,
  input  logic [95:0]           bounds_min_i, bounds_max_i,
  // the image's frame (docs/dataflow.md step 0): origin as fp32 bits, x in
  // [31:0], and the signed log2 scale, |s| <= 160; rays and hits are in world units
  input  logic [95:0]           frame_origin_i,
  input  logic signed [kdrt_pkg::FrameScaleWidth-1:0] frame_scale_i,
  // rays in
  input  logic                  ray_valid_i,
  output logic                  ray_ready_o,
  input  logic [RayIdWidth-1:0] ray_id_i,
  input  logic [255:0]          ray_i,
  // an any-hit query (shadow ray): the ray ends after the first leaf that
  // gives it a hit, with that leaf's closest hit (docs/core-interface.md)
  input  logic                  ray_any_i,
  // hits out
  output logic                  hit_valid_o,
  input  logic                  hit_ready_i,
  output logic [RayIdWidth-1:0] hit_ray_id_o,
  output logic                  hit_o,
  output logic [31:0]           hit_prim_o, hit_t_o, hit_u_o, hit_v_o,
  output logic                  hit_overflow_o,
  // memory
  output logic                  mem_req_valid_o,
  input  logic                  mem_req_ready_i,
  output logic [AddrWidth-1:0]  mem_req_addr_o,
  output logic [15:0]           mem_req_tag_o,
  input  logic                  mem_resp_valid_i,
  input  logic [15:0]           mem_resp_tag_i,
  input  logic [127:0]          mem_resp_data_i,
  // status
  output logic                  busy_o,
  output kdrt_pkg::perf_t       perf_o,
  // every thread's state (rt_thread_fsm state_o), for the report's histogram
  output logic [3*Threads-1:0]  thread_state_o
);

  localparam int unsigned CountW = TriIdxWidth + 1;
  localparam int unsigned KW = kdrt_pkg::TScaleWidth;
  localparam int unsigned NodeOffW = $clog2(16 * NodeLineBeats);
  // The image of the image's format (docs/memory-image.md, "Packed formats"): node
  // slots in 16-byte beats, triangle lines of whole beats holding one or two records.
  localparam int unsigned NodeBits = kdrt_pkg::img_node_bits(IW);
  localparam int unsigned SlotBits = kdrt_pkg::img_slot_bits(IW);
  localparam bit ThreeSlots = kdrt_pkg::img_nodes_per_beat(IW) == 3;
  localparam int unsigned FirstBits = kdrt_pkg::img_first_bits(IW);
  localparam int unsigned TriBeats = kdrt_pkg::img_tri_line_beats(IW);
  localparam int unsigned TriPerLine = kdrt_pkg::img_tris_per_line(IW);
  localparam int unsigned TriRecBits = kdrt_pkg::img_tri_slot_bits(IW);

  // Thread idx as a one-hot vector, or none.
  function automatic logic [Threads-1:0] onehot(input logic en, input logic [ThW-1:0] idx);
    onehot = en ? Threads'(1) << idx : '0;
  endfunction

  // ------------------------------------------------------------ thread table
  // The ray as set up, written once per ray (at setup) and read by two
  // units, is in two memories with an SRAM's ports, one per reader, and the
  // ray id, read only by the hit output, in a third (below); the fields that
  // change during traversal and those read at an index chosen in the same
  // cycle are registers.
  logic [W-1:0]            t0_q [Threads], t1_q [Threads];
  logic signed [KW-1:0]    t_scale_q [Threads];  // k: world t = framed t * 2^k
  logic [NodeIdxWidth-1:0] node_q [Threads];
  logic [Threads-1:0]      ovf_q;              // the stack overflowed
  logic [Threads-1:0]      any_q;              // an any-hit query

  // The threads in FREE, FETCH, EXIT and DONE, and the ones chosen: the lowest
  // free thread takes the next ray, arbiters pick a leaf exit and a hit out.
  logic [Threads-1:0] is_free, is_fetch, is_exit, is_done, exit_next;
  logic [ThW-1:0]     alloc_idx, exit_idx, out_idx;
  assign busy_o = ~&is_free;

  // ------------------------------------------------------------ ray in, setup, clip
  logic setup_in_ready, ray_fire;
  assign ray_ready_o = (|is_free) && setup_in_ready;
  assign ray_fire = ray_valid_i && ray_ready_o;

  logic           setup_valid, clip_in_ready, setup_fire;
  logic [ThW-1:0] setup_tag;
  logic signed [KW-1:0] setup_t_scale;
  logic [3*W-1:0] setup_o, setup_d;
  logic [3*TW-1:0] setup_inv;
  logic [W-1:0]   setup_tmin, setup_tmax, setup_sx, setup_sy, setup_sz;
  logic [1:0]     setup_kx, setup_ky, setup_kz;
  rt_ray_setup #(.E(E), .M(M), .TagWidth(ThW), .TravE(TravE), .TravM(TravM)) u_setup (
    .clk_i, .rst_ni, .in_valid_i(ray_fire), .in_ready_o(setup_in_ready), .in_tag_i(alloc_idx), .in_ray_i(ray_i),
    .frame_origin_i, .frame_scale_i,
    .out_valid_o(setup_valid), .out_ready_i(clip_in_ready), .out_tag_o(setup_tag),
    .out_t_scale_o(setup_t_scale), .out_o_o(setup_o),
    .out_d_o(setup_d), .out_inv_o(setup_inv), .out_tmin_o(setup_tmin), .out_tmax_o(setup_tmax),
    .out_kx_o(setup_kx), .out_ky_o(setup_ky), .out_kz_o(setup_kz),
    .out_sx_o(setup_sx), .out_sy_o(setup_sy), .out_sz_o(setup_sz)
  );
  assign setup_fire = setup_valid && clip_in_ready;

  logic           clip_valid, clip_miss;
  logic [ThW-1:0] clip_tag;
  logic [W-1:0]   clip_t0, clip_t1;
  rt_clip_unit #(.E(E), .M(M), .TagWidth(ThW), .TravE(TravE), .TravM(TravM)) u_clip (
    .clk_i, .rst_ni, .bounds_min_i, .bounds_max_i,
    .in_valid_i(setup_valid), .in_ready_o(clip_in_ready), .in_tag_i(setup_tag), .in_o_i(setup_o),
    .in_inv_i(setup_inv), .in_tmin_i(setup_tmin), .in_tmax_i(setup_tmax),
    .out_valid_o(clip_valid), .out_ready_i(1'b1), .out_tag_o(clip_tag), .out_t0_o(clip_t0),
    .out_t1_o(clip_t1), .out_miss_o(clip_miss)
  );

  // ------------------------------------------------------------ node fetch and traversal
  logic           fetch_valid, node_req_ready, fetch_fire, fetch2_valid, node_req2_ready, fetch2_fire;
  logic [ThW-1:0] fetch_idx, fetch2_idx;
  // The pointer moves on every grant, taken or not: a fetch the node cache
  // cannot take now (a miss without a free miss register, a hit while its
  // response register is full) does not hold up the threads behind it.
  rt_rr_arb #(.N(Threads)) u_fetch_arb (
    .clk_i, .rst_ni, .req_i(is_fetch), .ack_i(1'b1), .valid_o(fetch_valid), .idx_o(fetch_idx)
  );
  assign fetch_fire = fetch_valid && node_req_ready;
  // A second thread in FETCH, offered to the node cache's miss-only port: if
  // its node misses, its fetch starts now instead of taking a cycle of the
  // first port later.
  logic [Threads-1:0] is_fetch2;
  assign is_fetch2 = is_fetch & ~onehot(fetch_valid, fetch_idx);
  rt_rr_arb #(.N(Threads)) u_fetch2_arb (
    .clk_i, .rst_ni, .req_i(is_fetch2), .ack_i(1'b1), .valid_o(fetch2_valid), .idx_o(fetch2_idx)
  );
  assign fetch2_fire = fetch2_valid && node_req2_ready;

  // A node: bits [IW-1:0] the split, then the axis (or NodeLeaf), then the
  // above child's index and the marks of an empty below and above child (the
  // top two bits); a leaf reads {above bits, split bits} as its count
  // (high) and first list entry (low FirstBits). Node i is slot i % 2^SlotBits
  // of beat i / 2^SlotBits; its below child is the next slot.
  logic                         node_valid, node_ready, node_fire, node_is_leaf;
  logic [NodeLineBeats*128-1:0] node_line;
  logic [ThW-1:0]               node_tag, node_tag_next;
  logic [AddrWidth-1:0]         node_addr;
  logic [NodeBits-1:0]          node_bits;
  logic [IW-1:0]                node_lo;
  logic [NodeBits-IW-3:0]       node_hi;
  logic [NodeBits-3:0]          node_payload;  // a leaf's {count, first}
  logic [1:0]                   node_axis;
  logic [31:0]                  node_split, node_first;
  logic [NodeBits-FirstBits-3:0] node_count;
  logic [NodeIdxWidth-1:0]      node_below;
  logic [NodeBits-IW-5:0]       node_above;
  logic                         node_below_empty, node_above_empty;
  assign node_addr = node_base_i + (AddrWidth'(node_q[node_tag]) >> SlotBits << 4);
  assign node_bits = node_line[128 * node_addr[NodeOffW-1:4] + NodeBits * node_q[node_tag][SlotBits-1:0] +: NodeBits];
  assign {node_hi, node_axis, node_lo} = node_bits;
  assign {node_above_empty, node_below_empty, node_above} = node_hi;
  assign node_is_leaf = node_axis == kdrt_pkg::NodeLeaf;
  assign node_payload = {node_hi, node_lo};
  assign node_first = 32'(node_payload[FirstBits-1:0]);
  assign node_count = node_payload[NodeBits-3:FirstBits];
  assign node_below = (ThreeSlots && node_q[node_tag][1:0] == 2'd2) ? node_q[node_tag] + NodeIdxWidth'(2)
                                                                    : node_q[node_tag] + 1'b1;
  // The units load binary32: a narrower split widens exactly (the unit's
  // load rounds it back to itself, as the image's format is at most its own).
  if (IW == 32) begin : g_split32
    assign node_split = node_lo;
  end else begin : g_split_widen
    fp_to_f32 #(.E(ImgE), .M(ImgM)) u_widen (.a_i(node_lo), .f32_o(node_split));
  end

  logic                    trav_in_ready, trav_valid, trav_push, trav_overflow, stack_full;
  logic                    trav_first_empty, trav_second_empty, trav_exit;
  logic [ThW-1:0]          trav_tag;
  kdrt_pkg::trav_action_e  trav_action;
  logic [NodeIdxWidth-1:0] trav_first, trav_second;
  logic [W-1:0]            trav_ts_lo, trav_ts_hi, trav_t1;
  assign node_ready = node_is_leaf || trav_in_ready;
  assign node_fire = node_valid && node_ready;
  // The traversal's ray (o, d, 1 / d of every axis): a memory written at
  // setup and read at the thread whose node the node cache shows in the
  // next cycle (its resp_tag_next_o), so the registered read gives the
  // thread of node_tag in the cycle its node is shown, as a register read at
  // node_tag would. (A thread is never set up in the cycle before its node
  // is shown: the clip and a fetch lie between; checked below.)
  logic [3*W-1:0]  trav_o, trav_d;
  logic [3*TW-1:0] trav_inv;
  rt_ram_1r1w #(.Words(Threads), .Width(6*W + 3*TW)) u_trav_ray (
    .clk_i, .we_i(setup_fire), .waddr_i(setup_tag), .wdata_i({setup_inv, setup_d, setup_o}),
    .re_i(1'b1), .raddr_i(node_tag_next), .rdata_o({trav_inv, trav_d, trav_o})
  );
  rt_trav_unit #(.E(E), .M(M), .TagWidth(ThW), .NodeIdxWidth(NodeIdxWidth), .TravE(TravE), .TravM(TravM)) u_trav (
    .clk_i, .rst_ni, .in_valid_i(node_valid && !node_is_leaf), .in_ready_o(trav_in_ready),
    .in_tag_i(node_tag), .in_split_i(node_split), .in_below_i(node_below),
    .in_above_i(NodeIdxWidth'(node_above)), .in_below_empty_i(node_below_empty),
    .in_above_empty_i(node_above_empty), .in_o_i(trav_o[W*node_axis +: W]),
    .in_d_i(trav_d[W*node_axis +: W]), .in_inv_i(trav_inv[TW*node_axis +: TW]),
    .in_t0_i(t0_q[node_tag]), .in_t1_i(t1_q[node_tag]),
    .out_valid_o(trav_valid), .out_ready_i(1'b1), .out_tag_o(trav_tag), .out_action_o(trav_action),
    .out_first_o(trav_first), .out_second_o(trav_second), .out_first_empty_o(trav_first_empty),
    .out_second_empty_o(trav_second_empty), .out_ts_o(), .out_ts_lo_o(trav_ts_lo),
    .out_ts_hi_o(trav_ts_hi), .out_t0_o(), .out_t1_o(trav_t1)
  );
  assign trav_push = trav_valid && trav_action == kdrt_pkg::TravPush;
  assign trav_overflow = trav_push && stack_full;
  // The step's next node is an empty leaf: the thread goes to its exit
  // without fetching it (a pushed far child keeps its mark on the stack).
  assign trav_exit = trav_action == kdrt_pkg::TravSecond ? trav_second_empty : trav_first_empty;

  // ------------------------------------------------------------ leaf exit and stack
  logic                    exit_valid, exit_done, exit_sel, pop_empty;
  logic [ThW-1:0]          exit_sel_idx;
  logic [NodeIdxWidth-1:0] pop_node;
  logic [W-1:0]            pop_t0, pop_t1, exit_best_t;
  logic                    exit_hit;
  rt_leaf_exit #(.E(E), .M(M), .Threads(Threads), .StackDepth(StackDepth), .NodeIdxWidth(NodeIdxWidth)) u_exit (
    .clk_i, .rst_ni, .clear_i(setup_fire), .clear_idx_i(setup_tag),
    .push_i(trav_push), .push_idx_i(trav_tag), .push_node_i(trav_second), .push_t0_i(trav_ts_lo),
    .push_t1_i(trav_t1), .push_empty_i(trav_second_empty), .push_full_o(stack_full), .req_next_i(exit_next),
    .sel_valid_o(exit_sel), .sel_idx_o(exit_sel_idx), .exit_valid_o(exit_valid),
    .exit_idx_o(exit_idx), .exit_any_i(any_q[exit_idx]), .exit_hit_i(exit_hit), .exit_best_t_i(exit_best_t),
    .exit_t1_i(t1_q[exit_idx]), .exit_done_o(exit_done), .pop_node_o(pop_node), .pop_empty_o(pop_empty),
    .pop_t0_o(pop_t0), .pop_t1_o(pop_t1)
  );

  // ------------------------------------------------------------ leaf lists, triangles, intersection
  // A leaf's job (at most one per thread, so the queue never fills: its ready is left open).
  logic                   job_push, list_req_valid, list_req_ready, entry_fire;
  logic [ThW-1:0]         list_req_tag, tri_tag;
  logic [AddrWidth-1:0]   list_req_addr;
  logic [kdrt_pkg::list_count_bits(16 * ListLineBeats)-1:0] list_req_count;
  logic                 list_pf_valid, list_pf_ready;
  logic [AddrWidth-1:0] list_pf_addr;
  logic                   tri_valid, tri_fire;
  logic [ThW-1:0]         tri_tag_next;
  logic [TriIdxWidth-1:0] tri_id;
  logic [TriRecBits-1:0]  tri_record;
  logic [kdrt_pkg::TriVertexBits-1:0] tri_vertices;  // binary32, as the unit loads them
  assign job_push = node_fire && node_is_leaf && node_count != '0;
  if (IW == 32) begin : g_tri32
    assign tri_vertices = tri_record[kdrt_pkg::TriVertexBits-1:0];
  end else begin : g_tri_widen
    for (genvar k = 0; k < 9; k++) begin : g_coord
      fp_to_f32 #(.E(ImgE), .M(ImgM)) u_widen (.a_i(tri_record[IW*k +: IW]), .f32_o(tri_vertices[32*k +: 32]));
    end
  end
  rt_list_unit #(.TagWidth(ThW), .Jobs(Threads), .CountWidth(CountW), .AddrWidth(AddrWidth),
                 .ListStream(ListStream), .LineBytes(16 * ListLineBeats), .ListPrefetch(ListPrefetch)) u_list (
    .clk_i, .rst_ni, .list_base_i, .job_valid_i(job_push), .job_ready_o(), .job_tag_i(node_tag),
    .job_first_i(node_first), .job_count_i(CountW'(node_count)), .req_valid_o(list_req_valid),
    .req_ready_i(list_req_ready), .req_tag_o(list_req_tag), .req_addr_o(list_req_addr),
    .req_count_o(list_req_count), .pf_valid_o(list_pf_valid), .pf_ready_i(list_pf_ready), .pf_addr_o(list_pf_addr)
  );

  logic           isect_in_ready, isect_valid, isect_hit;
  logic [ThW-1:0] isect_tag;
  logic [31:0]    isect_id;
  logic [W-1:0]   isect_t, isect_u, isect_v;
  assign tri_fire = tri_valid && isect_in_ready;
  // The intersection's ray (o, the shear and axes, tmin): a memory as the
  // traversal's, read at the thread of the next cycle's triangle.
  logic [3*W-1:0] isect_o, isect_shear;  // sx, sy, sz
  logic [5:0]     isect_axes;            // kz, ky, kx (2 bits each)
  logic [W-1:0]   isect_tmin;
  rt_ram_1r1w #(.Words(Threads), .Width(7*W + 6)) u_isect_ray (
    .clk_i, .we_i(setup_fire), .waddr_i(setup_tag),
    .wdata_i({setup_tmin, setup_kz, setup_ky, setup_kx, setup_sz, setup_sy, setup_sx, setup_o}),
    .re_i(1'b1), .raddr_i(tri_tag_next), .rdata_o({isect_tmin, isect_axes, isect_shear, isect_o})
  );
  // The closest t when the thread's leaf began, the leaf's tests' tmax:
  // written when a leaf's job is queued, read as the ray memory is.
  logic [W-1:0] isect_tmax;
  rt_ram_1r1w #(.Words(Threads), .Width(W)) u_leaf_tmax (
    .clk_i, .we_i(job_push), .waddr_i(node_tag), .wdata_i(leaf_best_t),
    .re_i(1'b1), .raddr_i(tri_tag_next), .rdata_o(isect_tmax)
  );
  rt_isect_unit #(.E(E), .M(M), .TagWidth(ThW)) u_isect (
    .clk_i, .rst_ni, .in_valid_i(tri_valid), .in_ready_o(isect_in_ready), .in_tag_i(tri_tag),
    .in_id_i(32'(tri_id)), .in_o_i(isect_o), .in_kx_i(isect_axes[1:0]),
    .in_ky_i(isect_axes[3:2]), .in_kz_i(isect_axes[5:4]), .in_sx_i(isect_shear[0 +: W]),
    .in_sy_i(isect_shear[W +: W]), .in_sz_i(isect_shear[2*W +: W]), .in_tmin_i(isect_tmin),
    .in_tmax_i(isect_tmax), .in_tri_i(tri_vertices),
    .out_valid_o(isect_valid), .out_ready_i(1'b1), .out_tag_o(isect_tag), .out_id_o(isect_id),
    .out_hit_o(isect_hit), .out_t_o(isect_t), .out_u_o(isect_u), .out_v_o(isect_v)
  );

  // The closest hits: smaller t wins, equal t goes to the smaller id.
  logic                   out_hit, out_fire;
  logic [TriIdxWidth-1:0] out_prim;
  logic [W-1:0]           leaf_best_t, out_t, out_u, out_v;
  rt_hit_merge #(.E(E), .M(M), .Threads(Threads), .PrimWidth(TriIdxWidth)) u_merge (
    .clk_i, .rst_ni, .init_i(setup_fire), .init_idx_i(setup_tag), .init_t_i(setup_tmax),
    .cand_valid_i(isect_valid), .cand_idx_i(isect_tag), .cand_hit_i(isect_hit),
    .cand_prim_i(TriIdxWidth'(isect_id)), .cand_t_i(isect_t), .cand_u_i(isect_u), .cand_v_i(isect_v),
    .cand_take_o(), .leaf_idx_i(node_tag), .leaf_t_o(leaf_best_t), .exit_idx_i(exit_idx),
    .exit_hit_o(exit_hit), .exit_t_o(exit_best_t), .out_idx_i(out_idx), .out_hit_o(out_hit),
    .out_prim_o(out_prim), .out_t_o(out_t), .out_re_i(out_fire), .out_u_o(out_u), .out_v_o(out_v)
  );

  // ------------------------------------------------------------ caches and memory
  logic [2:0] cache_hit, cache_miss, cache_merge, cache_wait_inflight, cache_wait_mshr;  // node, list, triangle
  logic       mem_wait, tri_wait, list_prefetch;
  rt_mem_system #(.AddrWidth(AddrWidth), .TagWidth(ThW), .TriIdxWidth(TriIdxWidth),
                  .NodeCacheLines(NodeCacheLines), .ListCacheLines(ListCacheLines), .TriCacheLines(TriCacheLines),
                  .NodeLineBeats(NodeLineBeats), .ListLineBeats(ListLineBeats), .CacheMshrs(CacheMshrs),
                  .CacheTargets(CacheTargets), .CacheWays(CacheWays), .TriLineBeats(TriBeats),
                  .TriPerLine(TriPerLine), .ListStream(ListStream), .ListPrefetch(ListPrefetch)) u_mem (
    .clk_i, .rst_ni, .tri_base_i,
    .node_req_valid_i(fetch_valid), .node_req_ready_o(node_req_ready), .node_req_tag_i(fetch_idx),
    .node_req_addr_i(node_base_i + (AddrWidth'(node_q[fetch_idx]) >> SlotBits << 4)),
    .node_req2_valid_i(fetch2_valid), .node_req2_ready_o(node_req2_ready), .node_req2_tag_i(fetch2_idx),
    .node_req2_addr_i(node_base_i + (AddrWidth'(node_q[fetch2_idx]) >> SlotBits << 4)),
    .node_resp_valid_o(node_valid), .node_resp_ready_i(node_ready), .node_resp_tag_o(node_tag),
    .node_resp_tag_next_o(node_tag_next),
    .node_resp_line_o(node_line),
    .list_req_valid_i(list_req_valid), .list_req_ready_o(list_req_ready), .list_req_tag_i(list_req_tag),
    .list_req_addr_i(list_req_addr), .list_req_count_i(list_req_count), .list_pf_valid_i(list_pf_valid),
    .list_pf_ready_o(list_pf_ready), .list_pf_addr_i(list_pf_addr), .tri_resp_valid_o(tri_valid), .tri_resp_ready_i(isect_in_ready),
    .tri_resp_tag_o(tri_tag), .tri_resp_tag_next_o(tri_tag_next), .tri_resp_id_o(tri_id), .tri_resp_o(tri_record),
    .mem_req_valid_o, .mem_req_ready_i, .mem_req_addr_o, .mem_req_tag_o, .mem_resp_valid_i, .mem_resp_tag_i,
    .mem_resp_data_i, .hit_o(cache_hit), .miss_o(cache_miss), .merge_o(cache_merge),
    .wait_inflight_o(cache_wait_inflight), .wait_mshr_o(cache_wait_mshr), .list_prefetch_o(list_prefetch),
    .tri_wait_o(tri_wait), .entry_fire_o(entry_fire), .mem_wait_o(mem_wait)
  );

  // ------------------------------------------------------------ hit out
  logic out_valid, out_ready;
  rt_rr_arb #(.N(Threads)) u_out_arb (
    .clk_i, .rst_ni, .req_i(is_done), .ack_i(out_ready), .valid_o(out_valid), .idx_o(out_idx)
  );
  assign out_fire = out_valid && out_ready;
  // A thread's ray id is written when it takes a ray and read when its hit
  // leaves: never in one cycle (a free thread is not a finished one).
  logic [RayIdWidth-1:0] out_ray_id;
  rt_ram_1r1w #(.Words(Threads), .Width(RayIdWidth)) u_ray_id (
    .clk_i, .we_i(ray_fire), .waddr_i(alloc_idx), .wdata_i(ray_id_i),
    .re_i(out_fire), .raddr_i(out_idx), .rdata_o(out_ray_id)
  );
  rt_hit_out #(.E(E), .M(M), .RayIdWidth(RayIdWidth), .PrimWidth(TriIdxWidth)) u_hit_out (
    .clk_i, .rst_ni, .in_valid_i(out_valid), .in_ready_o(out_ready),
    .in_hit_i(out_hit), .in_prim_i(out_prim), .in_t_i(out_t), .in_t_scale_i(t_scale_q[out_idx]),
    .in_overflow_i(ovf_q[out_idx]), .rd_ray_id_i(out_ray_id), .rd_u_i(out_u),
    .rd_v_i(out_v),
    .hit_valid_o, .hit_ready_i, .hit_ray_id_o, .hit_o, .hit_prim_o, .hit_t_o, .hit_u_o, .hit_v_o, .hit_overflow_o
  );

  // ------------------------------------------------------------ thread states and table updates
  rt_thread_fsm #(.Threads(Threads), .CountWidth(CountW)) u_fsm (
    .clk_i, .rst_ni, .free_o(is_free), .fetch_o(is_fetch), .exit_o(is_exit), .done_o(is_done),
    .exit_next_o(exit_next),
    .state_o(thread_state_o),
    .alloc_idx_o(alloc_idx), .alloc_i(ray_fire), .setup_i(setup_fire), .setup_idx_i(setup_tag),
    .clip_i(clip_valid), .clip_idx_i(clip_tag), .clip_miss_i(clip_miss), .fetch_i(fetch_fire),
    .fetch_idx_i(fetch_idx), .fetch2_i(fetch2_fire), .fetch2_idx_i(fetch2_idx), .node_i(node_fire),
    .node_idx_i(node_tag), .node_leaf_i(node_is_leaf),
    .node_job_i(job_push), .node_tests_i(CountW'(node_count)), .trav_i(trav_valid), .trav_idx_i(trav_tag),
    .trav_overflow_i(trav_overflow), .trav_exit_i(trav_exit), .issue_i(tri_fire), .issue_idx_i(tri_tag),
    .retire_i(isect_valid), .retire_idx_i(isect_tag), .exit_i(exit_valid), .exit_idx_i(exit_idx),
    .exit_done_i(exit_done), .exit_again_i(pop_empty),
    .out_i(out_fire), .out_idx_i(out_idx)
  );

  // Each event names one thread, which is always in the event's state
  // (rt_thread_fsm checks), so one thread's events never collide: each event
  // writes its thread's fields through one write port of the table.
  always_ff @(posedge clk_i) begin
    if (ray_fire) any_q[alloc_idx] <= ray_any_i;
    if (setup_fire) begin
      t_scale_q[setup_tag] <= setup_t_scale;
      ovf_q[setup_tag] <= 1'b0;
      node_q[setup_tag] <= '0;
    end
    if (clip_valid) begin
      t0_q[clip_tag] <= clip_t0;
      t1_q[clip_tag] <= clip_t1;
    end
    if (trav_valid) node_q[trav_tag] <= (trav_action == kdrt_pkg::TravSecond) ? trav_second : trav_first;
    if (trav_push) t1_q[trav_tag] <= trav_ts_hi;
    if (trav_overflow) ovf_q[trav_tag] <= 1'b1;
    if (exit_valid && !exit_done) begin
      node_q[exit_idx] <= pop_node;
      t0_q[exit_idx] <= pop_t0;
      t1_q[exit_idx] <= pop_t1;
    end
  end

  // Address bits outside a line, the record's id and padding words, and id
  // and child index bits above TriIdxWidth and NodeIdxWidth (zero for a scene
  // the parameters fit) are unused.
  /* verilator lint_off UNUSEDSIGNAL */
  logic unused_bits;
  assign unused_bits = ^{node_addr, tri_record, isect_id, node_above};
  /* verilator lint_on UNUSEDSIGNAL */

`ifndef SYNTHESIS
  // The ray memories are read a cycle ahead of their readers and a read of
  // the word written in the same cycle gives the word before it: a thread
  // set up in one cycle has neither its node nor a triangle shown in the
  // next, nor a triangle in the cycle after its leaf's job is queued.
  logic           setup_was_q, job_was_q;
  logic [ThW-1:0] setup_was_tag_q, job_was_tag_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      setup_was_q <= 1'b0;
      job_was_q <= 1'b0;
    end else begin
      setup_was_q <= setup_fire;
      job_was_q <= job_push;
    end
  end
  always_ff @(posedge clk_i) begin
    setup_was_tag_q <= setup_tag;
    job_was_tag_q <= node_tag;
    if (rst_ni && setup_was_q) begin
      assert (!(node_valid && node_tag == setup_was_tag_q) && !(tri_valid && tri_tag == setup_was_tag_q))
      else $error("rt_core: a node or triangle shown in the cycle after its thread's setup");
    end
    if (rst_ni && job_was_q) begin
      assert (!(tri_valid && tri_tag == job_was_tag_q))
      else $error("rt_core: a triangle shown in the cycle after its thread's leaf job was queued");
    end
  end
`endif

  // The ray-in stream's rule (the units check the other streams).
  rt_stream_check #(.Width(RayIdWidth + 257), .Name("rt_core ray in")) u_ray_check (
    .clk_i, .rst_ni, .valid_i(ray_valid_i), .ready_i(ray_ready_o), .payload_i({ray_id_i, ray_any_i, ray_i})
  );

  // ------------------------------------------------------------ performance events
  rt_perf_events #(.Threads(Threads)) u_perf (
    .busy_i(busy_o), .ray_in_i(ray_fire), .clip_i(clip_valid), .node_i(node_fire), .node_leaf_i(node_is_leaf),
    .node_stall_i(node_valid && !node_ready), .trav_i(trav_valid), .overflow_i(trav_overflow),
    .list_req_i(list_req_valid && list_req_ready), .list_entry_i(entry_fire), .isect_in_i(tri_fire),
    .isect_stall_i(tri_valid && !isect_in_ready), .isect_out_i(isect_valid), .exit_req_i(is_exit),
    .exit_i(exit_valid), .exit_idx_i(exit_idx), .exit_sel_i(exit_sel),
    .exit_sel_idx_i(exit_sel_idx), .out_i(out_fire), .hit_valid_i(hit_valid_o), .hit_ready_i,
    .cache_hit_i(cache_hit), .cache_miss_i(cache_miss), .mem_wait_i(mem_wait),
    .node_wait_i(fetch_valid && !node_req_ready), .list_wait_i(list_req_valid && !list_req_ready),
    .tri_wait_i(tri_wait), .cache_merge_i(cache_merge), .cache_wait_inflight_i(cache_wait_inflight),
    .cache_wait_mshr_i(cache_wait_mshr), .list_prefetch_i(list_prefetch), .perf_o
  );

endmodule

`default_nettype wire
