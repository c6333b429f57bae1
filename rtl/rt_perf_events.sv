// rt_perf_events: rt_core's performance events (perf_o, kdrt_pkg::perf_t:
// the meaning of each bit is there) from the handshakes and waits of this
// cycle; combinational.
//
// The stall events classify a cycle: stall_mem when rays are in flight, no
// unit made progress (no ray taken or set up, no node step, list entry, test
// taken or finished, leaf exit or hit out) and a cache waits for memory;
// stall_stack when a thread in EXIT is neither the one the leaf exit takes
// nor the one it has chosen to take next;
// stall_backpressure when a hit record waits on hit_ready_i or a node
// response or triangle waits on the unit it goes to. The waits, merges and
// stalls per cache and per unit are passed through as they come.
`default_nettype none

module rt_perf_events #(
  parameter int unsigned Threads = 32,
  localparam int unsigned ThW = (Threads > 1) ? $clog2(Threads) : 1
) (
  input  logic               busy_i,         // rays in flight
  input  logic               ray_in_i,       // a ray taken
  input  logic               clip_i,         // a new ray's interval clipped
  input  logic               node_i,         // a node response taken
  input  logic               node_leaf_i,    // ... and it is a leaf (else the traversal unit took it)
  input  logic               node_stall_i,   // a node response waits
  input  logic               trav_i,         // a traversal step done
  input  logic               overflow_i,     // ... and its push overflowed the stack
  input  logic               list_req_i,     // a list entry requested
  input  logic               list_entry_i,   // a list entry answered, its triangle fetched
  input  logic               isect_in_i,     // a test taken
  input  logic               isect_stall_i,  // a triangle waits for the intersection unit
  input  logic               isect_out_i,    // a test done
  input  logic [Threads-1:0] exit_req_i,     // the threads in EXIT
  input  logic               exit_i,         // a leaf exit, of thread exit_idx_i
  input  logic [ThW-1:0]     exit_idx_i,
  input  logic               exit_sel_i,     // the leaf exit's next thread, exit_sel_idx_i (it exits in the next cycle)
  input  logic [ThW-1:0]     exit_sel_idx_i,
  input  logic               out_i,          // a finished ray taken by the hit output
  input  logic               hit_valid_i,    // rt_core's hit output stream
  input  logic               hit_ready_i,
  input  logic [2:0]         cache_hit_i,    // node, list, triangle cache
  input  logic [2:0]         cache_miss_i,
  input  logic               mem_wait_i,     // a cache waits for memory
  input  logic               node_wait_i,    // a node fetch is offered and not taken
  input  logic               list_wait_i,    // a list entry request is offered and not taken
  input  logic               tri_wait_i,     // a list entry waits for the triangle cache
  input  logic [2:0]         cache_merge_i,  // node, list, triangle cache
  input  logic [2:0]         cache_wait_inflight_i,
  input  logic [2:0]         cache_wait_mshr_i,
  input  logic               list_prefetch_i,  // a list line prefetch took a miss register
  output kdrt_pkg::perf_t    perf_o
);

  logic trav_in, list_busy, any_progress;
  logic [Threads-1:0] exit_taken, exit_chosen;
  assign trav_in = node_i && !node_leaf_i;
  assign list_busy = list_req_i || list_entry_i;
  assign any_progress = trav_in || list_busy || isect_in_i || exit_i || out_i || ray_in_i || clip_i || trav_i ||
                        isect_out_i;
  assign exit_taken = exit_i ? Threads'(1) << exit_idx_i : '0;
  assign exit_chosen = exit_sel_i ? Threads'(1) << exit_sel_idx_i : '0;

  assign perf_o.trav_busy = trav_in;
  assign perf_o.list_busy = list_busy;
  assign perf_o.isect_busy = isect_in_i;
  assign {perf_o.tri_hit, perf_o.list_hit, perf_o.node_hit} = cache_hit_i;
  assign {perf_o.tri_miss, perf_o.list_miss, perf_o.node_miss} = cache_miss_i;
  assign perf_o.stall_mem = busy_i && !any_progress && mem_wait_i;
  assign perf_o.stall_stack = (exit_req_i & ~exit_taken & ~exit_chosen) != '0;
  assign perf_o.stall_backpressure = (hit_valid_i && !hit_ready_i) || isect_stall_i || node_stall_i;
  assign perf_o.ray_in = ray_in_i;
  assign perf_o.ray_out = hit_valid_i && hit_ready_i;
  assign perf_o.overflow = overflow_i;
  assign perf_o.trav_leaf = node_i && node_leaf_i;
  assign perf_o.busy = busy_i;
  assign perf_o.node_wait = node_wait_i;
  assign perf_o.list_wait = list_wait_i;
  assign perf_o.tri_wait = tri_wait_i;
  assign {perf_o.tri_wait_inflight, perf_o.list_wait_inflight, perf_o.node_wait_inflight} = cache_wait_inflight_i;
  assign {perf_o.tri_wait_mshr, perf_o.list_wait_mshr, perf_o.node_wait_mshr} = cache_wait_mshr_i;
  assign {perf_o.tri_merge, perf_o.list_merge, perf_o.node_merge} = cache_merge_i;
  assign perf_o.trav_stall = node_stall_i;
  assign perf_o.isect_stall = isect_stall_i;
  assign perf_o.hit_stall = hit_valid_i && !hit_ready_i;
  assign perf_o.list_prefetch = list_prefetch_i;

endmodule

`default_nettype wire
