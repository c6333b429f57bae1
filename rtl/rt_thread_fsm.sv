// rt_thread_fsm: the state of each thread of rt_core (docs/core-interface.md)
// and its leaf-test counters.
//
//   FREE --alloc--> SETUP --clip--> FETCH, or DONE (the ray misses the box)
//   FETCH --fetch (either port)--> WAIT_NODE --node--> TRAV (inner node), LEAF (a leaf with
//                    tests) or EXIT (an empty leaf)
//   TRAV --trav--> FETCH, or DONE (the stack overflowed)
//   LEAF --> EXIT once all of the leaf's tests are issued and their results back
//   EXIT --exit--> FETCH (popped), or DONE
//   DONE --out--> FREE (the hit record is taken)
//
// Each event names one thread, which must be in the event's state (checked
// in simulation; an event for a thread in another state is ignored); events
// for different threads may come in the same cycle. In LEAF a thread counts
// the tests not yet issued (node_tests_i at the start, one less per issue_i)
// and the tests issued whose results are not back (issue_i, retire_i; both in
// one cycle leave it as it is); it leaves LEAF in the cycle after both are
// zero; setup_i (a new ray's constants are written, in SETUP) zeroes both.
// alloc_idx_o is the lowest free thread, the one alloc_i takes (a log-depth
// priority encoder, rtl/rt_prio_enc.sv).
`default_nettype none

module rt_thread_fsm #(
  parameter int unsigned Threads = 32,
  parameter int unsigned CountWidth = 25,
  localparam int unsigned ThW = (Threads > 1) ? $clog2(Threads) : 1
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // the threads in FREE, FETCH, EXIT and DONE; the free thread a ray takes
  output logic [Threads-1:0]    free_o,
  output logic [Threads-1:0]    fetch_o,
  output logic [Threads-1:0]    exit_o,
  output logic [Threads-1:0]    done_o,
  output logic [ThW-1:0]        alloc_idx_o,
  // every thread's state, 3 bits each, thread t in [3t+2:3t]: the encoding
  // of state_e below (sim/sim_report.cpp names them in this order)
  output logic [3*Threads-1:0]  state_o,
  // events
  input  logic                  alloc_i,
  input  logic                  setup_i,
  input  logic [ThW-1:0]        setup_idx_i,
  input  logic                  clip_i,
  input  logic [ThW-1:0]        clip_idx_i,
  input  logic                  clip_miss_i,
  input  logic                  fetch_i,
  input  logic [ThW-1:0]        fetch_idx_i,
  input  logic                  fetch2_i,      // a second fetch (the node cache's miss-only port), another thread
  input  logic [ThW-1:0]        fetch2_idx_i,
  input  logic                  node_i,
  input  logic [ThW-1:0]        node_idx_i,
  input  logic                  node_leaf_i,
  input  logic                  node_job_i,    // a leaf with tests (else an empty leaf)
  input  logic [CountWidth-1:0] node_tests_i,  // the leaf's tests, with node_job_i
  input  logic                  trav_i,
  input  logic [ThW-1:0]        trav_idx_i,
  input  logic                  trav_overflow_i,
  input  logic                  issue_i,
  input  logic [ThW-1:0]        issue_idx_i,
  input  logic                  retire_i,
  input  logic [ThW-1:0]        retire_idx_i,
  input  logic                  exit_i,
  input  logic [ThW-1:0]        exit_idx_i,
  input  logic                  exit_done_i,
  input  logic                  out_i,
  input  logic [ThW-1:0]        out_idx_i
);

  typedef enum logic [2:0] {
    SFree, SSetup, SFetch, SWaitNode, STrav, SLeaf, SExit, SDone
  } state_e;

  state_e                state_q [Threads], state_d [Threads];
  logic [CountWidth-1:0] remaining_q [Threads];    // tests of the leaf not yet issued
  logic [CountWidth-1:0] outstanding_q [Threads];  // tests issued, results not yet back

  logic [Threads-1:0] is_setup, is_wait, is_trav, is_leaf;
  always_comb begin
    for (int t = 0; t < Threads; t++) begin
      {done_o[t], exit_o[t], is_leaf[t], is_trav[t], is_wait[t], fetch_o[t], is_setup[t], free_o[t]} =
          8'b1 << state_q[t];
    end
  end
  // The lowest free thread (0 when none is free), in log2(Threads) levels.
  logic unused_any_free;
  rt_prio_enc #(.N(Threads)) u_alloc_enc (.req_i(free_o), .valid_o(unused_any_free), .idx_o(alloc_idx_o));

  // Each event as a one-hot vector of threads.
  function automatic logic [Threads-1:0] event_threads(input logic en, input logic [ThW-1:0] idx);
    event_threads = en ? Threads'(1) << idx : '0;
  endfunction
  logic [Threads-1:0] on_alloc, on_setup, on_clip, on_fetch, on_node, on_trav, on_issue, on_retire, on_exit, on_out;
  assign on_alloc = event_threads(alloc_i, alloc_idx_o);
  assign on_setup = event_threads(setup_i, setup_idx_i);
  assign on_clip = event_threads(clip_i, clip_idx_i);
  assign on_fetch = event_threads(fetch_i, fetch_idx_i) | event_threads(fetch2_i, fetch2_idx_i);
  assign on_node = event_threads(node_i, node_idx_i);
  assign on_trav = event_threads(trav_i, trav_idx_i);
  assign on_issue = event_threads(issue_i, issue_idx_i);
  assign on_retire = event_threads(retire_i, retire_idx_i);
  assign on_exit = event_threads(exit_i, exit_idx_i);
  assign on_out = event_threads(out_i, out_idx_i);

  // One case per state, looking at that state's events only.
  always_comb begin
    for (int t = 0; t < Threads; t++) begin
      state_d[t] = state_q[t];
      unique case (state_q[t])
        SFree:     if (on_alloc[t]) state_d[t] = SSetup;
        SSetup:    if (on_clip[t]) state_d[t] = clip_miss_i ? SDone : SFetch;
        SFetch:    if (on_fetch[t]) state_d[t] = SWaitNode;
        SWaitNode: if (on_node[t]) state_d[t] = !node_leaf_i ? STrav : node_job_i ? SLeaf : SExit;
        STrav:     if (on_trav[t]) state_d[t] = trav_overflow_i ? SDone : SFetch;
        SLeaf:     if (remaining_q[t] == '0 && outstanding_q[t] == '0) state_d[t] = SExit;
        SExit:     if (on_exit[t]) state_d[t] = exit_done_i ? SDone : SFetch;
        SDone:     if (on_out[t]) state_d[t] = SFree;
        default:   ;
      endcase
    end
  end
  for (genvar t = 0; t < Threads; t++) begin : g_state_out
    assign state_o[3*t +: 3] = state_q[t];
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int t = 0; t < Threads; t++) state_q[t] <= SFree;
    end else begin
      for (int t = 0; t < Threads; t++) state_q[t] <= state_d[t];
    end
  end

  always_ff @(posedge clk_i) begin
    for (int t = 0; t < Threads; t++) begin
      unique case (state_q[t])
        SSetup: if (on_setup[t]) {remaining_q[t], outstanding_q[t]} <= '0;
        SWaitNode: if (on_node[t] && node_job_i) remaining_q[t] <= node_tests_i;
        SLeaf: begin  // tests issued and results returned, possibly both in one cycle
          if (on_issue[t]) remaining_q[t] <= remaining_q[t] - 1'b1;
          if (on_issue[t] && !on_retire[t]) outstanding_q[t] <= outstanding_q[t] + 1'b1;
          if (!on_issue[t] && on_retire[t]) outstanding_q[t] <= outstanding_q[t] - 1'b1;
        end
        default: ;
      endcase
    end
  end

`ifndef SYNTHESIS
  always_ff @(posedge clk_i) begin
    if (rst_ni) assert ((on_alloc & ~free_o) == '0 && ((on_setup | on_clip) & ~is_setup) == '0 &&
                        (on_fetch & ~fetch_o) == '0 &&
                        (on_node & ~is_wait) == '0 && (on_trav & ~is_trav) == '0 &&
                        ((on_issue | on_retire) & ~is_leaf) == '0 && (on_exit & ~exit_o) == '0 &&
                        (on_out & ~done_o) == '0)
      else $error("rt_thread_fsm: an event for a thread that is not in the event's state");
  end
`endif

endmodule

`default_nettype wire
