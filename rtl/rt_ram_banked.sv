// rt_ram_banked: rt_ram_1r1w's memory and ports (one write port, one read
// port whose data is registered), made of ceil(Words / BankWords) memories
// of BankWords words each (the last one of what is left), the bank chosen by
// the address's bits above BankWords. An SRAM
// macro's access time grows with its words (docs/physical.md, "SRAM
// macros"), so a memory larger than a fast macro is built of several side by
// side, as a compiler's banked memories are; the read's bank is registered
// with it and picks the bank whose word is on rdata_o.
//
// The same behaviour as rt_ram_1r1w, cycle for cycle: a read gives the word
// from the next cycle on, held until the next read (only the addressed bank
// reads, and the registered bank changes only with a read); a read of the
// address written in the same cycle gives the word before the write. With
// Words <= BankWords it is one rt_ram_1r1w.
`default_nettype none

module rt_ram_banked #(
  parameter int unsigned Words = 4,
  parameter int unsigned Width = 8,
  parameter int unsigned BankWords = 256,
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

  if (Words > BankWords) begin : g_banks
    localparam int unsigned Banks = (Words + BankWords - 1) / BankWords;
    localparam int unsigned BankAw = $clog2(BankWords);
    localparam int unsigned SelW = (Banks > 1) ? $clog2(Banks) : 1;
    if (BankWords < 2 || (BankWords & (BankWords - 1)) != 0) begin : g_bad
      $error("rt_ram_banked: BankWords must be a power of two, at least 2");
    end

    logic [Width-1:0] bank_rdata [Banks];
    logic [SelW-1:0]  rsel_q;
    for (genvar b = 0; b < Banks; b++) begin : g_bank
      // The last bank holds what is left of Words.
      localparam int unsigned BW = (b == Banks - 1) ? Words - b * BankWords : BankWords;
      localparam int unsigned BAw = (BW > 1) ? $clog2(BW) : 1;
      rt_ram_1r1w #(.Words(BW), .Width(Width)) u_ram (
        .clk_i,
        .we_i(we_i && waddr_i[AddrW-1:BankAw] == (AddrW - BankAw)'(b)), .waddr_i(waddr_i[BAw-1:0]), .wdata_i,
        .re_i(re_i && raddr_i[AddrW-1:BankAw] == (AddrW - BankAw)'(b)), .raddr_i(raddr_i[BAw-1:0]),
        .rdata_o(bank_rdata[b])
      );
    end
    always_ff @(posedge clk_i) begin
      if (re_i) rsel_q <= SelW'(raddr_i[AddrW-1:BankAw]);
    end
    assign rdata_o = bank_rdata[rsel_q];
  end else begin : g_one
    rt_ram_1r1w #(.Words(Words), .Width(Width)) u_ram (
      .clk_i, .we_i, .waddr_i, .wdata_i, .re_i, .raddr_i, .rdata_o
    );
  end

endmodule

`default_nettype wire
