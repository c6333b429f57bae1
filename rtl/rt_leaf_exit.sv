// rt_leaf_exit: the per-thread traversal stacks and the leaf-exit decision of
// rt_core (docs/core-interface.md).
//
// A thread whose leaf is done asks to exit; the round-robin arbiter takes one
// a cycle (no backpressure). It chooses among the threads that ask in the
// next cycle (req_next_i) but the one it chose in this cycle, and the chosen
// thread exits two cycles later: its top entry is read from the stack memory
// (rt_thread_stack) and held in a register before the decision looks at it.
// The thread chosen in a cycle is announced in the next (sel_valid_o,
// sel_idx_o: it exits in the cycle after) and still asks until it exits.
// For the chosen thread exit_idx_o the caller gives its closest hit and
// interval end, and exit_done_o is the rule of TraceRay after a leaf
// (sw/trace/traversal.h):
//   if hit and (any-hit query or best.t <= t1): done; if the stack is empty: done;
//   pop; if hit and best.t < popped t0: done
// except that while the thread's stack holds an entry whose t0 is NaN (the
// far child of a node whose split plane the ray lies in, InPlane in
// traversal.h), neither hit rule ends a closest-hit ray: only the empty
// stack does. A counter per thread holds the number of such entries.
// The decision in one cycle: the top entry is looked at before the pop, and
// the stack is popped only when the thread goes on (exit_done_o low), to the popped
// node with [pop_t0_o, pop_t1_o]; pop_empty_o: the popped node is an empty
// leaf (pushed with its parent's mark), which the thread does not fetch: it
// exits again, with the popped interval's end. Stacks are cleared for a new
// ray (clear_i) and pushed by traversal steps (push_i; push_full_o: the push is dropped,
// the ray overflows), with rt_thread_stack's rules when events collide.
`default_nettype none
// Unused outputs of fp_cmp are left open on purpose.
/* verilator lint_off PINCONNECTEMPTY */

module rt_leaf_exit #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23,
  parameter int unsigned Threads = 32,
  parameter int unsigned StackDepth = 32,
  parameter int unsigned NodeIdxWidth = 24,
  localparam int unsigned W = E + M + 1,
  localparam int unsigned ThW = (Threads > 1) ? $clog2(Threads) : 1
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  // a new ray: its thread's stack is emptied
  input  logic                    clear_i,
  input  logic [ThW-1:0]          clear_idx_i,
  // a traversal step pushes the far child and its interval
  input  logic                    push_i,
  input  logic [ThW-1:0]          push_idx_i,
  input  logic [NodeIdxWidth-1:0] push_node_i,
  input  logic [W-1:0]            push_t0_i,
  input  logic [W-1:0]            push_t1_i,
  input  logic                    push_empty_i,  // the pushed node is an empty leaf
  output logic                    push_full_o,  // push_idx_i's stack is full: the push is dropped
  // the threads whose leaf is done, in the next cycle
  input  logic [Threads-1:0]      req_next_i,
  output logic                    sel_valid_o,  // sel_idx_o exits in the next cycle
  output logic [ThW-1:0]          sel_idx_o,
  output logic                    exit_valid_o,
  output logic [ThW-1:0]          exit_idx_o,
  // exit_idx_o's closest hit (hit, t), interval end t1, and whether its ray
  // is an any-hit query (it ends at the first leaf with a hit)
  input  logic                    exit_any_i,
  input  logic                    exit_hit_i,
  input  logic [W-1:0]            exit_best_t_i,
  input  logic [W-1:0]            exit_t1_i,
  // the decision: done, or go on to the popped node and interval
  output logic                    exit_done_o,
  output logic [NodeIdxWidth-1:0] pop_node_o,
  output logic                    pop_empty_o,
  output logic [W-1:0]            pop_t0_o,
  output logic [W-1:0]            pop_t1_o
);

  localparam int unsigned SpW = $clog2(StackDepth + 1);

  logic stack_empty, best_le_t1, best_lt_pop;
  logic pop_ok, push_ok, push_in_plane, pop_in_plane, exit_in_plane;
  logic [SpW-1:0] in_plane_q [Threads];  // entries with a NaN t0 on each thread's stack

  // The choice, registered twice: the chosen thread (sel_*) and, a cycle
  // later, the exiting one. The thread chosen in this cycle is out of the
  // next choice (it asks until it exits).
  logic               next_valid;
  logic [ThW-1:0]     next_idx;
  logic [Threads-1:0] req_next, sel_onehot;
  assign sel_onehot = sel_valid_o ? Threads'(1) << sel_idx_o : '0;
  assign req_next = req_next_i & ~sel_onehot;
  rt_rr_arb #(.N(Threads)) u_arb (
    .clk_i, .rst_ni, .req_i(req_next), .ack_i(1'b1), .valid_o(next_valid), .idx_o(next_idx)
  );
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sel_valid_o <= 1'b0;
      sel_idx_o <= '0;
      exit_valid_o <= 1'b0;
      exit_idx_o <= '0;
    end else begin
      sel_valid_o <= next_valid;
      sel_idx_o <= next_idx;
      exit_valid_o <= sel_valid_o;
      exit_idx_o <= sel_idx_o;
    end
  end

  rt_thread_stack #(.Threads(Threads), .StackDepth(StackDepth), .Width(1 + NodeIdxWidth + 2 * W)) u_stack (
    .clk_i, .rst_ni, .clear_i, .clear_idx_i,
    .push_i, .push_idx_i, .push_data_i({push_empty_i, push_node_i, push_t0_i, push_t1_i}), .push_full_o,
    .read_i(next_valid), .read_idx_i(next_idx), .top_empty_o(stack_empty),
    .top_o({pop_empty_o, pop_node_o, pop_t0_o, pop_t1_o}),
    .pop_i(pop_ok)
  );

  fp_cmp #(.E(E), .M(M), .Stages(0)) u_cmp_t1 (
    .clk_i, .rst_ni, .en_i(1'b1), .valid_i(1'b1), .a_i(exit_best_t_i), .b_i(exit_t1_i),
    .valid_o(), .lt_o(), .le_o(best_le_t1), .eq_o(), .min_o(), .max_o()
  );
  fp_cmp #(.E(E), .M(M), .Stages(0)) u_cmp_pop (
    .clk_i, .rst_ni, .en_i(1'b1), .valid_i(1'b1), .a_i(exit_best_t_i), .b_i(pop_t0_o),
    .valid_o(), .lt_o(best_lt_pop), .le_o(), .eq_o(), .min_o(), .max_o()
  );

  assign exit_in_plane = in_plane_q[exit_idx_o] != '0;
  assign exit_done_o = (exit_hit_i && exit_any_i) || stack_empty ||
                       (exit_hit_i && !exit_in_plane && (best_le_t1 || best_lt_pop));

  // The counters follow rt_thread_stack's rules: a pop (never of an empty
  // stack) wins over a push, a push (dropped when full) over a clear.
  assign pop_ok = exit_valid_o && !exit_done_o;
  assign push_ok = push_i && !push_full_o;
  // NaN: exponent all ones, mantissa not zero (any sign).
  assign push_in_plane = (&push_t0_i[W-2:M]) && (|push_t0_i[M-1:0]);
  assign pop_in_plane = (&pop_t0_o[W-2:M]) && (|pop_t0_o[M-1:0]);

  // One update per thread: the events name different threads here.
  logic push_wins;
  assign push_wins = push_ok && !(pop_ok && push_idx_i == exit_idx_o);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int t = 0; t < Threads; t++) in_plane_q[t] <= '0;
    end else begin
      if (clear_i && !(push_ok && push_idx_i == clear_idx_i) && !(pop_ok && exit_idx_o == clear_idx_i)) begin
        in_plane_q[clear_idx_i] <= '0;
      end
      if (push_wins && push_in_plane) in_plane_q[push_idx_i] <= in_plane_q[push_idx_i] + 1'b1;
      if (pop_ok && pop_in_plane) in_plane_q[exit_idx_o] <= in_plane_q[exit_idx_o] - 1'b1;
    end
  end

endmodule

`default_nettype wire
