// rt_ram_1r1w: a memory of Words words of Width bits with one write port and
// one read port whose data is registered, the ports an SRAM compiler's
// two-port macro has (as lowRISC's prim_ram_2p keeps its array behind them).
//
// A read (re_i) of raddr_i gives the word on rdata_o from the next cycle on,
// held until the next read. A read of the address written in the same cycle
// gives the word before the write (read-first); a caller that needs the new
// word forwards it. The array has no reset: a word never written reads as
// unknown. Synthesis keeps it as one memory (Yosys infers a $mem with one
// synchronous read port), which a macro can take the place of.
`default_nettype none

module rt_ram_1r1w #(
  parameter int unsigned Words = 4,
  parameter int unsigned Width = 8,
  localparam int unsigned AddrW = (Words > 1) ? $clog2(Words) : 1
) (
  input  logic             clk_i,
  input  logic             we_i,
  input  logic [AddrW-1:0] waddr_i,
  input  logic [Width-1:0] wdata_i,
  input  logic             re_i,
  input  logic [AddrW-1:0] raddr_i,
  output logic [Width-1:0] rdata_o
);

  logic [Width-1:0] sram_q [Words];
  logic [Width-1:0] rdata_q;

  always_ff @(posedge clk_i) begin
    if (we_i) sram_q[waddr_i] <= wdata_i;
  end

  always_ff @(posedge clk_i) begin
    if (re_i) rdata_q <= sram_q[raddr_i];
  end

  assign rdata_o = rdata_q;

endmodule

`default_nettype wire
