// rt_fifo: a first-in first-out queue of Depth entries, valid/ready on both
// sides (picorv32's rule). An entry written in one cycle can be read from the
// next (no fall-through); in_ready_o is low only when all Depth entries are
// full, and a push and a pop may happen in the same cycle. Any Depth >= 1
// (not only powers of two): the pointers wrap at Depth and carry a lap bit
// that tells full from empty.
`default_nettype none

module rt_fifo #(
  parameter int unsigned Width = 8,
  parameter int unsigned Depth = 4,
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

  logic [Width-1:0] mem_q [Depth];
  logic [IdxW:0]    rd_q, wr_q;  // {lap, index}

  // The next pointer: index + 1, or index 0 of the next lap after Depth - 1.
  function automatic logic [IdxW:0] next_ptr(input logic [IdxW:0] p);
    next_ptr = (p[IdxW-1:0] == IdxW'(Depth - 1)) ? {~p[IdxW], {IdxW{1'b0}}} : p + 1'b1;
  endfunction

  logic push, pop;
  assign out_valid_o = rd_q != wr_q;
  assign in_ready_o = !(rd_q[IdxW] != wr_q[IdxW] && rd_q[IdxW-1:0] == wr_q[IdxW-1:0]);
  assign out_data_o = mem_q[rd_q[IdxW-1:0]];
  assign push = in_valid_i && in_ready_o;
  assign pop = out_valid_o && out_ready_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rd_q <= '0;
      wr_q <= '0;
    end else begin
      if (push) wr_q <= next_ptr(wr_q);
      if (pop) rd_q <= next_ptr(rd_q);
    end
  end

  always_ff @(posedge clk_i) begin
    if (push) mem_q[wr_q[IdxW-1:0]] <= in_data_i;
  end

  rt_stream_check #(.Width(Width), .Name("rt_fifo in")) u_in_check (
    .clk_i, .rst_ni, .valid_i(in_valid_i), .ready_i(in_ready_o), .payload_i(in_data_i)
  );
  rt_stream_check #(.Width(Width), .Name("rt_fifo out")) u_out_check (
    .clk_i, .rst_ni, .valid_i(out_valid_o), .ready_i(out_ready_i), .payload_i(out_data_o)
  );

endmodule

`default_nettype wire
