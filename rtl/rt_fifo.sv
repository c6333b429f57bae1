// rt_fifo: a first-in first-out queue of Depth entries, valid/ready on both
// sides (picorv32's rule). An entry written in one cycle can be read from the
// next (no fall-through); in_ready_o is low only when all Depth entries are
// full, and a push and a pop may happen in the same cycle. Any Depth >= 1
// (not only powers of two): the pointers wrap at Depth and carry a lap bit
// that tells full from empty.
//
// Ram selects the storage, not the behaviour (tests/rtl/fifo_bench.cpp runs
// both against one model, cycle for cycle):
//   0: flip-flops, the head read combinationally (small queues);
//   1: a memory with an SRAM's ports (rt_ram_1r1w: one write port, one read
//      port with a registered read), for queues too deep for flip-flops. The
//      memory is read every cycle at the next cycle's head (the read position
//      after this cycle's pop), so the head's word is in the read register
//      when it is shown; an entry pushed in the cycle in which it becomes the
//      next head (the queue is empty after this cycle) is not yet in that
//      read, and is forwarded through a register beside it.
`default_nettype none

module rt_fifo #(
  parameter int unsigned Width = 8,
  parameter int unsigned Depth = 4,
  parameter bit          Ram   = 1'b0,
  localparam int unsigned IdxW = (Depth > 1) ? $clog2(Depth) : 1
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             in_valid_i,
  output logic             in_ready_o,
  input  logic [Width-1:0] in_data_i,
  output logic             out_valid_o,
  input  logic             out_ready_i,
  output logic [Width-1:0] out_data_o
);

  logic [IdxW:0] rd_q, wr_q, rd_inc;  // {lap, index}

  // The next pointer: index + 1, or index 0 of the next lap after Depth - 1.
  function automatic logic [IdxW:0] next_ptr(input logic [IdxW:0] p);
    next_ptr = (p[IdxW-1:0] == IdxW'(Depth - 1)) ? {~p[IdxW], {IdxW{1'b0}}} : p + 1'b1;
  endfunction

  logic push, pop;
  assign out_valid_o = rd_q != wr_q;
  assign in_ready_o = !(rd_q[IdxW] != wr_q[IdxW] && rd_q[IdxW-1:0] == wr_q[IdxW-1:0]);
  assign push = in_valid_i && in_ready_o;
  assign pop = out_valid_o && out_ready_i;
  assign rd_inc = next_ptr(rd_q);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rd_q <= '0;
      wr_q <= '0;
    end else begin
      if (push) wr_q <= next_ptr(wr_q);
      if (pop) rd_q <= rd_inc;
    end
  end

  if (Ram) begin : g_ram
    logic [IdxW-1:0]  rd_next;  // the next cycle's head
    logic             fwd_q;
    logic [Width-1:0] fwd_data_q, rdata;
    assign rd_next = pop ? rd_inc[IdxW-1:0] : rd_q[IdxW-1:0];
    // A push goes to wr_q; it is the next head when it lands where the head
    // will be read (a push needs a queue that is not full, so equal indices
    // there mean an empty queue after this cycle's pop).
    always_ff @(posedge clk_i) begin
      fwd_q <= push && wr_q[IdxW-1:0] == rd_next;
      if (push) fwd_data_q <= in_data_i;
    end
    rt_ram_1r1w #(.Words(Depth), .Width(Width)) u_ram (
      .clk_i, .we_i(push), .waddr_i(wr_q[IdxW-1:0]), .wdata_i(in_data_i),
      .re_i(1'b1), .raddr_i(rd_next), .rdata_o(rdata)
    );
    assign out_data_o = fwd_q ? fwd_data_q : rdata;
  end else begin : g_flops
    logic [Width-1:0] mem_q [Depth];
    always_ff @(posedge clk_i) begin
      if (push) mem_q[wr_q[IdxW-1:0]] <= in_data_i;
    end
    assign out_data_o = mem_q[rd_q[IdxW-1:0]];
  end

  rt_stream_check #(.Width(Width), .Name("rt_fifo in")) u_in_check (
    .clk_i, .rst_ni, .valid_i(in_valid_i), .ready_i(in_ready_o), .payload_i(in_data_i)
  );
  rt_stream_check #(.Width(Width), .Name("rt_fifo out")) u_out_check (
    .clk_i, .rst_ni, .valid_i(out_valid_o), .ready_i(out_ready_i), .payload_i(out_data_o)
  );

endmodule

`default_nettype wire
