// rt_thread_stack: one traversal stack of StackDepth entries per thread, in
// registers, with a stack pointer per thread.
//
// In one cycle a thread's stack may be cleared (a new ray), another's pushed
// and another's popped; if they name the same thread, the pop wins over the
// push and the push over the clear. A push onto a full stack is dropped
// (push_full_o tells the caller: the ray overflowed) and a pop of an empty
// stack does nothing. top_o is the top entry of pop_idx_i's stack (entry 0
// when it is empty), read combinationally, so the caller can look at it
// before it decides to pop.
`default_nettype none

module rt_thread_stack #(
  parameter int unsigned Threads = 32,
  parameter int unsigned StackDepth = 32,
  parameter int unsigned Width = 8,
  localparam int unsigned ThW = (Threads > 1) ? $clog2(Threads) : 1
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             clear_i,
  input  logic [ThW-1:0]   clear_idx_i,
  input  logic             push_i,
  input  logic [ThW-1:0]   push_idx_i,
  input  logic [Width-1:0] push_data_i,
  output logic             push_full_o,   // push_idx_i's stack holds StackDepth entries
  input  logic             pop_i,
  input  logic [ThW-1:0]   pop_idx_i,
  output logic             pop_empty_o,   // pop_idx_i's stack is empty
  output logic [Width-1:0] top_o
);

  localparam int unsigned SpW = $clog2(StackDepth + 1);

  logic [SpW-1:0]   sp_q [Threads];
  logic [Width-1:0] mem_q [Threads * StackDepth];  // thread t's entry k at t * StackDepth + k

  logic [SpW-1:0] push_sp, pop_sp;
  logic           push_ok, pop_ok;
  assign push_sp = sp_q[push_idx_i];
  assign pop_sp = sp_q[pop_idx_i];
  assign push_full_o = push_sp == SpW'(StackDepth);
  assign pop_empty_o = pop_sp == '0;
  assign push_ok = push_i && !push_full_o;
  assign pop_ok = pop_i && !pop_empty_o;
  assign top_o = mem_q[32'(pop_idx_i) * StackDepth + (pop_empty_o ? 0 : 32'(pop_sp) - 1)];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int t = 0; t < Threads; t++) sp_q[t] <= '0;
    end else begin
      for (int t = 0; t < Threads; t++) begin
        if (pop_ok && pop_idx_i == ThW'(t)) begin
          sp_q[t] <= pop_sp - 1'b1;
        end else if (push_ok && push_idx_i == ThW'(t)) begin
          sp_q[t] <= push_sp + 1'b1;
        end else if (clear_i && clear_idx_i == ThW'(t)) begin
          sp_q[t] <= '0;
        end
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (push_ok) mem_q[32'(push_idx_i) * StackDepth + 32'(push_sp)] <= push_data_i;
  end

endmodule

`default_nettype wire
