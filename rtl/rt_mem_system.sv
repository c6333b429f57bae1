// rt_mem_system: the core's memory side. Three non-blocking direct-mapped
// caches (rtl/rt_cache.sv) share one memory port (rtl/rt_mem_arb.sv):
//
//   node port:  a byte address -> the node cache line holding it; a second
//               node port takes misses only, so that a miss does not take
//               a cycle from the hits of the first
//   list port:  a list entry's byte address -> list cache -> the entry's
//               triangle id -> triangle cache (lines of TriPerLine records,
//               named by id / TriPerLine) -> the triangle's record
//
// With ListStream 1 a list request names list_req_count_i entries from its
// address on, all in one list line: the list cache's response (the whole
// line) goes into a line register that hands the triangle cache one entry a
// cycle, and the cache's next response waits until the register gives its
// last entry. Responses come back out of order, each with its request's tag
// (the list port's tag comes back on the triangle response, with the id). Streams are
// valid/ready; all but the node request follow picorv32's rule (checked): a
// node request may change or drop while not ready (the cache decides each
// cycle). The memory tag is {cache (node 0, list 1, triangle 2), miss
// register, beat}, zero-extended to 16 bits.
`default_nettype none

module rt_mem_system #(
  parameter int unsigned AddrWidth = 28,
  parameter int unsigned TagWidth = 5,
  parameter int unsigned TriIdxWidth = 24,
  parameter int unsigned NodeCacheLines = 256,
  parameter int unsigned ListCacheLines = 256,
  parameter int unsigned TriCacheLines = 1024,
  parameter int unsigned NodeLineBeats = 2,
  parameter int unsigned ListLineBeats = 2,
  parameter int unsigned CacheMshrs = 16,
  // Requests one miss register answers (rt_cache Targets): 1 = no merging.
  parameter int unsigned CacheTargets = 8,
  // Lines per set of each cache (rt_cache Ways): 1 = direct-mapped.
  parameter int unsigned CacheWays = 4,
  // Beats of a triangle line: kdrt_pkg::img_tri_line_beats of the format (3 for fp32).
  parameter int unsigned TriLineBeats = 3,
  // Triangle records per line, 1 or 2 (kdrt_pkg::img_tris_per_line; 2 for
  // fp16 and bf16): record id % 2 of line id / 2 is the line's lower or upper half.
  parameter int unsigned TriPerLine = 1,
  // 1: a list request names the entries of one line (list_req_count_i).
  parameter int unsigned ListStream = 1,
  // 1: the list cache takes line prefetches on its second port (list_pf_*,
  // rt_cache PrefetchPort; from rt_list_unit's ListPrefetch).
  parameter int unsigned ListPrefetch = 0,
  localparam int unsigned TriBits = 128 * TriLineBeats / TriPerLine,
  localparam int unsigned ListCountW = kdrt_pkg::list_count_bits(16 * ListLineBeats)
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,
  input  logic [AddrWidth-1:0]         tri_base_i,  // stable while busy
  // node lines
  input  logic                         node_req_valid_i,
  output logic                         node_req_ready_o,
  input  logic [TagWidth-1:0]          node_req_tag_i,
  input  logic [AddrWidth-1:0]         node_req_addr_i,
  // a second node request, taken only if it misses (rt_cache MissPort)
  input  logic                         node_req2_valid_i,
  output logic                         node_req2_ready_o,
  input  logic [TagWidth-1:0]          node_req2_tag_i,
  input  logic [AddrWidth-1:0]         node_req2_addr_i,
  output logic                         node_resp_valid_o,
  input  logic                         node_resp_ready_i,
  output logic [TagWidth-1:0]          node_resp_tag_o,
  output logic [TagWidth-1:0]          node_resp_tag_next_o,  // node_resp_tag_o of the next cycle (rt_cache)
  output logic [NodeLineBeats*128-1:0] node_resp_line_o,
  // list entries, answered with their triangles
  input  logic                         list_req_valid_i,
  output logic                         list_req_ready_o,
  input  logic [TagWidth-1:0]          list_req_tag_i,
  input  logic [AddrWidth-1:0]         list_req_addr_i,
  input  logic [ListCountW-1:0]        list_req_count_i,  // entries from the address on (ListStream)
  // list line prefetches (ListPrefetch; the line's first byte)
  input  logic                         list_pf_valid_i,
  output logic                         list_pf_ready_o,
  input  logic [AddrWidth-1:0]         list_pf_addr_i,
  output logic                         tri_resp_valid_o,
  input  logic                         tri_resp_ready_i,
  output logic [TagWidth-1:0]          tri_resp_tag_o,
  output logic [TagWidth-1:0]          tri_resp_tag_next_o,  // tri_resp_tag_o of the next cycle (rt_cache)
  output logic [TriIdxWidth-1:0]       tri_resp_id_o,
  output logic [TriBits-1:0]           tri_resp_o,
  // memory
  output logic                         mem_req_valid_o,
  input  logic                         mem_req_ready_i,
  output logic [AddrWidth-1:0]         mem_req_addr_o,
  output logic [15:0]                  mem_req_tag_o,
  input  logic                         mem_resp_valid_i,
  input  logic [15:0]                  mem_resp_tag_i,
  input  logic [127:0]                 mem_resp_data_i,
  // events this cycle: node, list, triangle cache (bits 0, 1, 2)
  output logic [2:0]                   hit_o,
  output logic [2:0]                   miss_o,
  output logic [2:0]                   merge_o,          // a miss joined a line being fetched
  output logic [2:0]                   wait_inflight_o,  // a miss waits on a line being fetched
  output logic [2:0]                   wait_mshr_o,      // a miss waits for a free miss register
  output logic                         list_prefetch_o,  // a list line prefetch took a miss register
  output logic                         tri_wait_o,       // a list entry waits for the triangle cache
  output logic                         entry_fire_o,  // a list entry went on to the triangle cache
  output logic                         mem_wait_o     // a cache waits for memory
);

  localparam int unsigned NodeOffW = $clog2(16 * NodeLineBeats);
  localparam int unsigned ListOffW = $clog2(16 * ListLineBeats);
  localparam int unsigned EntryShift = $clog2(kdrt_pkg::ListEntryBytes);
  // A cache's memory id: {miss register, beat}.
  localparam int unsigned MemIdW = ((CacheMshrs > 1) ? $clog2(CacheMshrs) : 1) + 2;

  logic [2:0]           mem_valid, mem_ready, mem_resp_valid, filling;
  logic                 unused_req2_ready;  // the triangle cache has no second port
  logic [1:0]           unused_prefetch;    // the node and triangle caches take no prefetches
  logic [AddrWidth-1:0] node_mem_addr, list_mem_addr, tri_mem_addr;
  logic [MemIdW-1:0]    node_mem_id, list_mem_id, tri_mem_id, mem_resp_id;
  logic [127:0]         mem_resp_data;

  rt_cache #(.Lines(NodeCacheLines), .LineBeats(NodeLineBeats), .KeyWidth(AddrWidth - NodeOffW),
             .AddrWidth(AddrWidth), .TagWidth(TagWidth), .Mshrs(CacheMshrs), .Targets(CacheTargets), .Ways(CacheWays),
             .MissPort(1'b1), .KeyIsLine(1'b1)) u_node_cache (
    .clk_i, .rst_ni,
    .req_valid_i(node_req_valid_i), .req_ready_o(node_req_ready_o),
    .req_key_i(node_req_addr_i[AddrWidth-1:NodeOffW]),
    .req_addr_i({node_req_addr_i[AddrWidth-1:NodeOffW], {NodeOffW{1'b0}}}), .req_tag_i(node_req_tag_i),
    .req2_valid_i(node_req2_valid_i), .req2_ready_o(node_req2_ready_o),
    .req2_key_i(node_req2_addr_i[AddrWidth-1:NodeOffW]),
    .req2_addr_i({node_req2_addr_i[AddrWidth-1:NodeOffW], {NodeOffW{1'b0}}}), .req2_tag_i(node_req2_tag_i),
    .resp_valid_o(node_resp_valid_o), .resp_ready_i(node_resp_ready_i), .resp_data_o(node_resp_line_o),
    .resp_tag_o(node_resp_tag_o), .resp_tag_next_o(node_resp_tag_next_o),
    .mem_req_valid_o(mem_valid[0]), .mem_req_ready_i(mem_ready[0]), .mem_req_addr_o(node_mem_addr),
    .mem_req_id_o(node_mem_id), .mem_resp_valid_i(mem_resp_valid[0]), .mem_resp_id_i(mem_resp_id),
    .mem_resp_data_i(mem_resp_data), .hit_o(hit_o[0]), .miss_o(miss_o[0]), .merge_o(merge_o[0]),
    .wait_inflight_o(wait_inflight_o[0]), .wait_mshr_o(wait_mshr_o[0]), .prefetch_o(unused_prefetch[0]),
    .filling_o(filling[0])
  );

  // The list cache's tag carries the entry's offset in its line and, with
  // ListStream, the request's count (without it the cache is the one it was
  // before ListStream existed).
  localparam int unsigned ListTagW = TagWidth + ListOffW + (ListStream != 0 ? ListCountW : 0);
  logic                         list_resp_valid, list_resp_ready, tri_req_valid, tri_req_ready;
  logic [ListLineBeats*128-1:0] list_line;
  logic [ListTagW-1:0]          list_req_tag_full, list_resp_tag_full;
  logic [TagWidth-1:0]          list_resp_tag, entry_tag;
  logic [ListOffW-1:0]          list_resp_off;
  logic [TriIdxWidth-1:0]       entry_tri;
  logic [ListTagW-1:0]          unused_list_tag_next;  // the list cache's responses go to the line register
  logic [TriIdxWidth-1:0]       unused_tri_id_next;
  rt_cache #(.Lines(ListCacheLines), .LineBeats(ListLineBeats), .KeyWidth(AddrWidth - ListOffW),
             .AddrWidth(AddrWidth), .TagWidth(ListTagW), .Mshrs(CacheMshrs),
             .Targets(CacheTargets), .Ways(CacheWays), .PrefetchPort(ListPrefetch != 0), .KeyIsLine(1'b1))
      u_list_cache (
    .clk_i, .rst_ni,
    .req_valid_i(list_req_valid_i), .req_ready_o(list_req_ready_o),
    .req_key_i(list_req_addr_i[AddrWidth-1:ListOffW]),
    .req_addr_i({list_req_addr_i[AddrWidth-1:ListOffW], {ListOffW{1'b0}}}),
    .req_tag_i(list_req_tag_full),
    .req2_valid_i(ListPrefetch != 0 && list_pf_valid_i), .req2_ready_o(list_pf_ready_o),
    .req2_key_i(list_pf_addr_i[AddrWidth-1:ListOffW]),
    .req2_addr_i({list_pf_addr_i[AddrWidth-1:ListOffW], {ListOffW{1'b0}}}), .req2_tag_i('0),
    .resp_valid_o(list_resp_valid), .resp_ready_i(list_resp_ready), .resp_data_o(list_line),
    .resp_tag_o(list_resp_tag_full), .resp_tag_next_o(unused_list_tag_next),
    .mem_req_valid_o(mem_valid[1]), .mem_req_ready_i(mem_ready[1]), .mem_req_addr_o(list_mem_addr),
    .mem_req_id_o(list_mem_id), .mem_resp_valid_i(mem_resp_valid[1]), .mem_resp_id_i(mem_resp_id),
    .mem_resp_data_i(mem_resp_data), .hit_o(hit_o[1]), .miss_o(miss_o[1]), .merge_o(merge_o[1]),
    .wait_inflight_o(wait_inflight_o[1]), .wait_mshr_o(wait_mshr_o[1]), .prefetch_o(list_prefetch_o),
    .filling_o(filling[1])
  );
  localparam int unsigned EntryIdxW = ListOffW - EntryShift;
  if (ListStream != 0) begin : g_stream
    logic [ListCountW-1:0] list_resp_count;
    assign list_req_tag_full = {list_req_tag_i, list_req_addr_i[ListOffW-1:0], list_req_count_i};
    assign {list_resp_tag, list_resp_off, list_resp_count} = list_resp_tag_full;
    // The line register: the entries of one response, handed on one a cycle.
    // The entry's place is one-hot (a bit per entry, rotated as the entries
    // are handed on): the entry is an AND-OR of the line's words, so the
    // triangle cache's lookup, which the entry starts, is not behind a
    // select decode.
    localparam int unsigned Entries = 1 << EntryIdxW;
    logic                         em_valid_q;
    logic [ListLineBeats*128-1:0] em_line_q;
    logic [Entries-1:0]           em_sel_q;
    logic [ListCountW-1:0]        em_left_q;
    logic [TagWidth-1:0]          em_tag_q;
    logic                         em_last;
    assign em_last = em_left_q == ListCountW'(1);
    assign list_resp_ready = !em_valid_q || (tri_req_ready && em_last);
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        em_valid_q <= 1'b0;
      end else if (list_resp_valid && list_resp_ready) begin
        em_valid_q <= 1'b1;
      end else if (tri_req_ready && em_last) begin
        em_valid_q <= 1'b0;
      end
    end
    always_ff @(posedge clk_i) begin
      if (list_resp_valid && list_resp_ready) begin
        em_line_q <= list_line;
        em_sel_q <= Entries'(1) << list_resp_off[ListOffW-1:EntryShift];
        em_left_q <= list_resp_count;
        em_tag_q <= list_resp_tag;
      end else if (em_valid_q && tri_req_ready) begin
        em_sel_q <= {em_sel_q[Entries-2:0], em_sel_q[Entries-1]};
        em_left_q <= em_left_q - 1'b1;
      end
    end
    assign tri_req_valid = em_valid_q;
    assign entry_tag = em_tag_q;
    logic [31:0] entry;
    always_comb begin
      entry = '0;
      for (int unsigned e = 0; e < Entries; e++) begin
        entry |= em_line_q[8 * kdrt_pkg::ListEntryBytes * e +: 32] & {32{em_sel_q[e]}};
      end
      entry_tri = TriIdxWidth'(entry);
    end
    // Only the line register's tag bits are used.
    /* verilator lint_off UNUSEDSIGNAL */
    logic unused_stream;
    assign unused_stream = ^list_resp_off[EntryShift-1:0];
    /* verilator lint_on UNUSEDSIGNAL */
  end else begin : g_entry
    assign list_req_tag_full = {list_req_tag_i, list_req_addr_i[ListOffW-1:0]};
    assign {list_resp_tag, list_resp_off} = list_resp_tag_full;
    // The response is the entry: straight on to the triangle cache.
    assign list_resp_ready = tri_req_ready;
    assign tri_req_valid = list_resp_valid;
    assign entry_tag = list_resp_tag;
    assign entry_tri = TriIdxWidth'(list_line[8 * kdrt_pkg::ListEntryBytes * list_resp_off[ListOffW-1:EntryShift] +: 32]);
    /* verilator lint_off UNUSEDSIGNAL */
    logic unused_entry;
    assign unused_entry = ^{list_resp_off[EntryShift-1:0], list_req_count_i};
    /* verilator lint_on UNUSEDSIGNAL */
  end
  assign entry_fire_o = tri_req_valid && tri_req_ready;
  assign tri_wait_o = tri_req_valid && !tri_req_ready;

  // A triangle line holds TriPerLine records and is named by id / TriPerLine.
  localparam int unsigned PairShift = TriPerLine == 2 ? 1 : 0;
  logic [TriIdxWidth-1:0]        tri_line_key;
  logic [128*TriLineBeats-1:0]   tri_line;
  assign tri_line_key = entry_tri >> PairShift;
  rt_cache #(.Lines(TriCacheLines), .LineBeats(TriLineBeats), .KeyWidth(TriIdxWidth),
             .AddrWidth(AddrWidth), .TagWidth(TagWidth + TriIdxWidth), .Mshrs(CacheMshrs), .Targets(CacheTargets),
             .Ways(CacheWays))
      u_tri_cache (
    .clk_i, .rst_ni,
    .req_valid_i(tri_req_valid), .req_ready_o(tri_req_ready), .req_key_i(tri_line_key),
    .req_addr_i(tri_base_i + (AddrWidth'(tri_line_key) << 4) * AddrWidth'(TriLineBeats)),
    .req_tag_i({entry_tag, entry_tri}),
    .req2_valid_i(1'b0), .req2_ready_o(unused_req2_ready), .req2_key_i('0), .req2_addr_i('0), .req2_tag_i('0),
    .resp_valid_o(tri_resp_valid_o), .resp_ready_i(tri_resp_ready_i), .resp_data_o(tri_line),
    .resp_tag_o({tri_resp_tag_o, tri_resp_id_o}), .resp_tag_next_o({tri_resp_tag_next_o, unused_tri_id_next}),
    .mem_req_valid_o(mem_valid[2]), .mem_req_ready_i(mem_ready[2]), .mem_req_addr_o(tri_mem_addr),
    .mem_req_id_o(tri_mem_id), .mem_resp_valid_i(mem_resp_valid[2]), .mem_resp_id_i(mem_resp_id),
    .mem_resp_data_i(mem_resp_data), .hit_o(hit_o[2]), .miss_o(miss_o[2]), .merge_o(merge_o[2]),
    .wait_inflight_o(wait_inflight_o[2]), .wait_mshr_o(wait_mshr_o[2]), .prefetch_o(unused_prefetch[1]),
    .filling_o(filling[2])
  );

  // The record of the response's triangle: the id (from the tag) picks the
  // half of a two-record line.
  if (TriPerLine == 2) begin : g_tri_pair
    assign tri_resp_o = tri_resp_id_o[0] ? tri_line[TriBits +: TriBits] : tri_line[TriBits-1:0];
  end else begin : g_tri_one
    assign tri_resp_o = tri_line;
  end

  rt_mem_arb #(.N(3), .AddrWidth(AddrWidth), .IdW(MemIdW)) u_mem_arb (
    .clk_i, .rst_ni,
    .req_valid_i(mem_valid), .req_ready_o(mem_ready),
    .req_addr_i({tri_mem_addr, list_mem_addr, node_mem_addr}), .req_id_i({tri_mem_id, list_mem_id, node_mem_id}),
    .resp_valid_o(mem_resp_valid), .resp_id_o(mem_resp_id), .resp_data_o(mem_resp_data),
    .mem_req_valid_o, .mem_req_ready_i, .mem_req_addr_o, .mem_req_tag_o,
    .mem_resp_valid_i, .mem_resp_tag_i, .mem_resp_data_i
  );
  assign mem_wait_o = (|mem_valid) || (|filling);

  rt_stream_check #(.Width(AddrWidth + 16), .Name("rt_mem_system memory request")) u_mem_check (
    .clk_i, .rst_ni, .valid_i(mem_req_valid_o), .ready_i(mem_req_ready_i), .payload_i({mem_req_addr_o, mem_req_tag_o})
  );
  rt_stream_check #(.Width(TagWidth + AddrWidth + ListCountW), .Name("rt_mem_system list request")) u_list_check (
    .clk_i, .rst_ni, .valid_i(list_req_valid_i), .ready_i(list_req_ready_o),
    .payload_i({list_req_tag_i, list_req_addr_i, list_req_count_i})
  );
  rt_stream_check #(.Width(TagWidth + NodeLineBeats * 128), .Name("rt_mem_system node response")) u_node_check (
    .clk_i, .rst_ni, .valid_i(node_resp_valid_o), .ready_i(node_resp_ready_i),
    .payload_i({node_resp_tag_o, node_resp_line_o})
  );
  rt_stream_check #(.Width(TagWidth + TriIdxWidth + TriBits), .Name("rt_mem_system triangle response")) u_tri_check (
    .clk_i, .rst_ni, .valid_i(tri_resp_valid_o), .ready_i(tri_resp_ready_i),
    .payload_i({tri_resp_tag_o, tri_resp_id_o, tri_resp_o})
  );

  // Entry bits above TriIdxWidth (zero for a scene the parameters fit), the
  // line's other entries and the node address bits within a line are unused.
  /* verilator lint_off UNUSEDSIGNAL */
  logic unused_bits;
  assign unused_bits = ^{list_line, node_req_addr_i, node_req2_addr_i, unused_req2_ready, list_pf_addr_i, unused_prefetch};
  /* verilator lint_on UNUSEDSIGNAL */

endmodule

`default_nettype wire
