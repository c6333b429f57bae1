// rt_thread_fsm: the state of each thread of rt_core (docs/core-interface.md)
// and its leaf-test counters.
//
//   FREE --alloc--> SETUP --clip--> FETCH, or DONE (the ray misses the box)
//   FETCH --fetch (either port)--> WAIT_NODE --node--> TRAV (inner node), LEAF (a leaf with
//                    tests) or EXIT (an empty leaf)
//   TRAV --trav--> FETCH, EXIT (the next node is an empty leaf, not fetched),
//                  or DONE (the stack overflowed)
//   LEAF --> EXIT once all of the leaf's tests are issued and their results back
//   EXIT --exit--> FETCH (popped), EXIT (popped an empty leaf), or DONE
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
  // the threads in EXIT in the next cycle (after this cycle's events)
  output logic [Threads-1:0]    exit_next_o,
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
  input  logic                  trav_exit_i,   // the step's next node is an empty leaf
  input  logic                  issue_i,
  input  logic [ThW-1:0]        issue_idx_i,
  input  logic                  retire_i,
  input  logic [ThW-1:0]        retire_idx_i,
  input  logic                  exit_i,
  input  logic [ThW-1:0]        exit_idx_i,
  input  logic                  exit_done_i,
  input  logic                  exit_again_i,  // not done: the popped node is an empty leaf
  input  logic                  out_i,
  input  logic [ThW-1:0]        out_idx_i
);

  typedef enum logic [2:0] {
    SFree, SSetup, SFetch, SWaitNode, STrav, SLeaf, SExit, SDone
  } state_e;

  // The states as one vector of threads per state (each thread in exactly
  // one), updated by the events, the encoded states beside them for state_o,
  // and the counters, each written through the ports of the events that
  // change them: a cycle's work does not grow with the thread count beyond
  // the vectors' width.
  logic [Threads-1:0]    free_q, setup_q, fetch_q, wait_q, trav_q, leaf_q, exit_q, done_q;
  logic [Threads-1:0]    free_d, setup_d, fetch_d, wait_d, trav_d, leaf_d, exit_d, done_d;
  logic [3*Threads-1:0]  state_q;
  logic [CountWidth-1:0] remaining_q [Threads];    // tests of the leaf not yet issued
  logic [CountWidth-1:0] outstanding_q [Threads];  // tests issued, results not yet back

  assign {free_o, fetch_o, exit_o, done_o} = {free_q, fetch_q, exit_q, done_q};
  assign exit_next_o = exit_d;
  assign state_o = state_q;
  // The lowest free thread (0 when none is free), in log2(Threads) levels.
  logic unused_any_free;
  rt_prio_enc #(.N(Threads)) u_alloc_enc (.req_i(free_q), .valid_o(unused_any_free), .idx_o(alloc_idx_o));

  // Each event as a one-hot vector of threads, kept only for a thread in the
  // event's state (others are ignored).
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

  // A thread in LEAF leaves in the cycle after its counters are both zero.
  // They reach zero only through an event of that thread (a result, a test
  // issued, or a leaf of no tests), at most three a cycle: those threads,
  // registered, leave in the next cycle.
  localparam int unsigned Zs = 3;  // issue, retire, node
  logic [Zs-1:0]  zero_d, zero_q;
  logic [ThW-1:0] zero_idx_d [Zs], zero_idx_q [Zs];
  logic [Threads-1:0] a_alloc, a_clip, a_fetch, a_node, a_trav, a_leaf, a_exit, a_out;
  logic               issue_ok, retire_ok, node_ok, both;
  assign issue_ok = issue_i && leaf_q[issue_idx_i];
  assign retire_ok = retire_i && leaf_q[retire_idx_i];
  assign node_ok = node_i && wait_q[node_idx_i];
  assign both = issue_ok && retire_ok && issue_idx_i == retire_idx_i;
  // Issue and result of one thread leave the tests in flight as they are.
  assign zero_d[0] = issue_ok && remaining_q[issue_idx_i] == CountWidth'(1) &&
                     outstanding_q[issue_idx_i] == '0 && both;
  assign zero_d[1] = retire_ok && !both && remaining_q[retire_idx_i] == '0 &&
                     outstanding_q[retire_idx_i] == CountWidth'(1);
  assign zero_d[2] = node_ok && node_leaf_i && node_job_i && node_tests_i == '0;
  assign zero_idx_d[0] = issue_idx_i;
  assign zero_idx_d[1] = retire_idx_i;
  assign zero_idx_d[2] = node_idx_i;
  always_comb begin
    a_leaf = '0;
    for (int z = 0; z < Zs; z++) a_leaf |= event_threads(zero_q[z], zero_idx_q[z]);
    a_leaf &= leaf_q;
  end

  assign a_alloc = on_alloc & free_q;
  assign a_clip = on_clip & setup_q;
  assign a_fetch = on_fetch & fetch_q;
  assign a_node = on_node & wait_q;
  assign a_trav = on_trav & trav_q;
  assign a_exit = on_exit & exit_q;
  assign a_out = on_out & done_q;
  assign free_d = (free_q & ~a_alloc) | a_out;
  assign setup_d = (setup_q & ~a_clip) | a_alloc;
  assign fetch_d = (fetch_q & ~a_fetch) | (clip_miss_i ? '0 : a_clip) |
                   (trav_overflow_i || trav_exit_i ? '0 : a_trav) | (exit_done_i || exit_again_i ? '0 : a_exit);
  assign wait_d = (wait_q & ~a_node) | a_fetch;
  assign trav_d = (trav_q & ~a_trav) | (node_leaf_i ? '0 : a_node);
  assign leaf_d = (leaf_q & ~a_leaf) | (node_leaf_i && node_job_i ? a_node : '0);
  assign exit_d = (exit_q & ~a_exit) | a_leaf | (node_leaf_i && !node_job_i ? a_node : '0) |
                  (!trav_overflow_i && trav_exit_i ? a_trav : '0) | (!exit_done_i && exit_again_i ? a_exit : '0);
  assign done_d = (done_q & ~a_out) | (clip_miss_i ? a_clip : '0) | (trav_overflow_i ? a_trav : '0) |
                  (exit_done_i ? a_exit : '0);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      {free_q, setup_q, fetch_q, wait_q, trav_q, leaf_q, exit_q, done_q} <= {{Threads{1'b1}}, {7 * Threads{1'b0}}};
      zero_q <= '0;
    end else begin
      {free_q, setup_q, fetch_q, wait_q, trav_q, leaf_q, exit_q, done_q} <=
          {free_d, setup_d, fetch_d, wait_d, trav_d, leaf_d, exit_d, done_d};
      zero_q <= zero_d;
    end
  end
  always_ff @(posedge clk_i) begin
    for (int z = 0; z < Zs; z++) zero_idx_q[z] <= zero_idx_d[z];
  end

  // The encoded states: each event writes its thread's (the threads differ:
  // each is in its event's state; the two fetches name two threads).
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= {Threads{SFree}};
    end else begin
      if (alloc_i && free_q[alloc_idx_o]) state_q[3*alloc_idx_o +: 3] <= SSetup;
      if (clip_i && setup_q[clip_idx_i]) state_q[3*clip_idx_i +: 3] <= clip_miss_i ? SDone : SFetch;
      if (fetch_i && fetch_q[fetch_idx_i]) state_q[3*fetch_idx_i +: 3] <= SWaitNode;
      if (fetch2_i && fetch_q[fetch2_idx_i]) state_q[3*fetch2_idx_i +: 3] <= SWaitNode;
      if (node_ok) state_q[3*node_idx_i +: 3] <= !node_leaf_i ? STrav : node_job_i ? SLeaf : SExit;
      if (trav_i && trav_q[trav_idx_i]) begin
        state_q[3*trav_idx_i +: 3] <= trav_overflow_i ? SDone : trav_exit_i ? SExit : SFetch;
      end
      for (int z = 0; z < Zs; z++) begin
        if (zero_q[z] && leaf_q[zero_idx_q[z]]) state_q[3*zero_idx_q[z] +: 3] <= SExit;
      end
      if (exit_i && exit_q[exit_idx_i]) begin
        state_q[3*exit_idx_i +: 3] <= exit_done_i ? SDone : exit_again_i ? SExit : SFetch;
      end
      if (out_i && done_q[out_idx_i]) state_q[3*out_idx_i +: 3] <= SFree;
    end
  end

  always_ff @(posedge clk_i) begin
    if (setup_i && setup_q[setup_idx_i]) begin
      remaining_q[setup_idx_i] <= '0;
      outstanding_q[setup_idx_i] <= '0;
    end
    if (node_ok && node_job_i) remaining_q[node_idx_i] <= node_tests_i;
    if (issue_ok) remaining_q[issue_idx_i] <= remaining_q[issue_idx_i] - 1'b1;
    if (issue_ok && !both) outstanding_q[issue_idx_i] <= outstanding_q[issue_idx_i] + 1'b1;
    if (retire_ok && !both) outstanding_q[retire_idx_i] <= outstanding_q[retire_idx_i] - 1'b1;
  end

`ifndef SYNTHESIS
  always_ff @(posedge clk_i) begin
    if (rst_ni) assert ((on_alloc & ~free_q) == '0 && ((on_setup | on_clip) & ~setup_q) == '0 &&
                        (on_fetch & ~fetch_q) == '0 &&
                        (on_node & ~wait_q) == '0 && (on_trav & ~trav_q) == '0 &&
                        ((on_issue | on_retire) & ~leaf_q) == '0 && (on_exit & ~exit_q) == '0 &&
                        (on_out & ~done_q) == '0)
      else $error("rt_thread_fsm: an event for a thread that is not in the event's state");
  end
`endif

endmodule

`default_nettype wire
