// rt_thread_stack: one traversal stack of StackDepth entries per thread, the
// entries of all threads in one memory (rt_ram_banked: one write port, one
// registered read port, Threads * StackDepth words in banks of BankWords,
// thread t's entry k at t * StackDepth + k), a stack pointer per thread
// beside it.
//
// The top entry is read two cycles ahead, so that the memory's word goes to a
// register before anything decides on it: read_idx_i names the thread whose
// top the cycle after next looks at, and in that cycle top_o and top_empty_o
// are that thread's top entry and emptiness as they are after the cycle
// before it, and pop_i pops that thread's stack. The read forwards what the
// two cycles in between do to the thread (a push: the pushed entry; a clear:
// empty; in the first of them also a pop: the entry below the top), so a
// thread may be read in any cycle (read_i), except that a thread popped in
// a cycle must not have been read again in the cycle after its own read (that
// read's top would be the entry below the one it read): the leaf exit never
// chooses the thread it has just chosen (checked in simulation).
//
// In one cycle a thread's stack may be cleared (a new ray), another's pushed
// and another's popped; if they name the same thread, the pop wins over the
// push and the push over the clear. A push onto a full stack is dropped
// (push_full_o tells the caller: the ray overflowed) and a pop of an empty
// stack does nothing. top_o is unknown when the stack is empty.
`default_nettype none

module rt_thread_stack #(
  parameter int unsigned Threads = 32,
  parameter int unsigned StackDepth = 32,
  parameter int unsigned Width = 8,
  // the words of one SRAM macro (a power of two): the memory is banked so
  // that its access time is a small macro's (up to 256 words a macro's
  // access barely grows, docs/physical.md)
  parameter int unsigned BankWords = 256,
  localparam int unsigned ThW = (Threads > 1) ? $clog2(Threads) : 1,
  localparam int unsigned Words = Threads * StackDepth,
  localparam int unsigned AddrW = (Words > 1) ? $clog2(Words) : 1
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             clear_i,
  input  logic [ThW-1:0]   clear_idx_i,
  input  logic             push_i,
  input  logic [ThW-1:0]   push_idx_i,
  input  logic [Width-1:0] push_data_i,
  output logic             push_full_o,   // push_idx_i's stack holds StackDepth entries
  input  logic             read_i,        // a read: of read_idx_i's top
  input  logic [ThW-1:0]   read_idx_i,    // the thread whose top the cycle after next looks at
  output logic             top_empty_o,   // the thread read two cycles before: its stack is empty
  output logic [Width-1:0] top_o,         // its top entry
  input  logic             pop_i          // pop its stack
);

  localparam int unsigned SpW = $clog2(StackDepth + 1);

  function automatic logic [AddrW-1:0] addr(input logic [ThW-1:0] idx, input logic [SpW-1:0] k);
    addr = AddrW'(32'(idx) * StackDepth + 32'(k));
  endfunction

  logic [SpW-1:0]   sp_q [Threads];
  // The read's two stages: the thread read in the previous cycle (rd_*: its
  // word on the memory's output) and the one read two cycles before (top_*:
  // the top the caller looks at).
  logic [ThW-1:0]   rd_idx_q, top_idx_q;
  logic             rd_valid_q, rd_empty_q, rd_fwd_q, top_empty_q;
  logic [Width-1:0] rd_fwd_data_q;  // the entry pushed onto it as it was read
  logic [Width-1:0] top_q;
  logic [Width-1:0] ram_rdata;

  logic [SpW-1:0] push_sp, pop_sp, read_sp, read_sp_next, read_sp_kept;
  logic           push_ok, pop_ok, push_wins, read_popped, read_pushed;
  logic           read_same, kept_pushed, kept_cleared;
  assign push_sp = sp_q[push_idx_i];
  assign pop_sp = sp_q[top_idx_q];
  assign read_sp = sp_q[read_idx_i];
  assign push_full_o = push_sp == SpW'(StackDepth);
  assign push_ok = push_i && !push_full_o;
  assign pop_ok = pop_i && !top_empty_q;
  assign push_wins = push_ok && !(pop_ok && push_idx_i == top_idx_q);

  // The read thread's pointer after this cycle, with the events' priorities.
  // The pop is known last (the caller decides it from top_o), so the read is
  // made for both outcomes, popped and kept, and chosen by it.
  assign read_same = top_idx_q == read_idx_i;
  assign read_popped = pop_ok && read_same;
  assign kept_pushed = push_ok && push_idx_i == read_idx_i;
  assign kept_cleared = !kept_pushed && clear_i && clear_idx_i == read_idx_i;
  assign read_pushed = !read_popped && kept_pushed;
  always_comb begin
    read_sp_kept = read_sp;
    if (kept_pushed) read_sp_kept = read_sp + 1'b1;
    else if (kept_cleared) read_sp_kept = '0;
  end
  assign read_sp_next = read_popped ? read_sp - 1'b1 : read_sp_kept;

  logic             re_popped, re_kept;
  logic [AddrW-1:0] raddr_popped, raddr_kept;
  assign re_popped = read_sp != SpW'(1);
  assign raddr_popped = addr(read_idx_i, read_sp - SpW'(2));
  assign re_kept = read_sp_kept != '0 && !kept_pushed;
  assign raddr_kept = addr(read_idx_i, read_sp_kept - 1'b1);
  rt_ram_banked #(.Words(Words), .Width(Width), .BankWords(BankWords)) u_ram (
    .clk_i, .we_i(push_ok), .waddr_i(addr(push_idx_i, push_sp)), .wdata_i(push_data_i),
    .re_i(read_i && (read_popped ? re_popped : re_kept)), .raddr_i(read_popped ? raddr_popped : raddr_kept),
    .rdata_o(ram_rdata)
  );

  // The second stage: the word read (or forwarded) to a register, with this
  // cycle's push or clear of the thread (its pop cannot be: see above).
  logic rd_pushed, rd_cleared;
  assign rd_pushed = push_ok && push_idx_i == rd_idx_q;
  assign rd_cleared = !rd_pushed && clear_i && clear_idx_i == rd_idx_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rd_valid_q <= 1'b0;
      rd_idx_q <= '0;
      rd_empty_q <= 1'b1;
      rd_fwd_q <= 1'b0;
      top_idx_q <= '0;
      top_empty_q <= 1'b1;
    end else begin
      rd_valid_q <= read_i;
      rd_idx_q <= read_idx_i;
      rd_empty_q <= read_sp_next == '0;
      rd_fwd_q <= read_pushed;
      top_idx_q <= rd_idx_q;
      top_empty_q <= rd_cleared || (rd_empty_q && !rd_pushed);
    end
  end
  always_ff @(posedge clk_i) begin
    if (read_pushed) rd_fwd_data_q <= push_data_i;
    top_q <= rd_pushed ? push_data_i : rd_fwd_q ? rd_fwd_data_q : ram_rdata;
  end
  assign top_empty_o = top_empty_q;
  assign top_o = top_q;

  // The pointers: the events name different threads here (the pop wins over
  // the push, the push over the clear), so each thread takes one update.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int t = 0; t < Threads; t++) sp_q[t] <= '0;
    end else begin
      if (clear_i && !(push_ok && push_idx_i == clear_idx_i) && !(pop_ok && top_idx_q == clear_idx_i)) begin
        sp_q[clear_idx_i] <= '0;
      end
      if (push_wins) sp_q[push_idx_i] <= push_sp + 1'b1;
      if (pop_ok) sp_q[top_idx_q] <= pop_sp - 1'b1;
    end
  end

`ifndef SYNTHESIS
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      assert (!(pop_ok && rd_valid_q && rd_idx_q == top_idx_q))
      else $error("rt_thread_stack: thread %0d popped in the cycle after it was read again", top_idx_q);
    end
  end
`endif

endmodule

`default_nettype wire
