// rt_delay: Depth register stages of Width bits with a shared clock enable,
// to carry side data beside a fixed-latency arithmetic pipeline. Depth 0 is a
// wire. Data registers are not reset (valid bits travel in the fp units).
`default_nettype none

module rt_delay #(
  parameter int unsigned Width = 1,
  parameter int unsigned Depth = 1
) (
  input  logic             clk_i,
  input  logic             en_i,
  input  logic [Width-1:0] d_i,
  output logic [Width-1:0] q_o
);

  if (Depth == 0) begin : g_wire
    assign q_o = d_i;
    /* verilator lint_off UNUSEDSIGNAL */
    logic unused_clk;
    assign unused_clk = clk_i ^ en_i;
    /* verilator lint_on UNUSEDSIGNAL */
  end else begin : g_regs
    logic [Width-1:0] stage_q [Depth];
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        stage_q[0] <= d_i;
        for (int unsigned i = 1; i < Depth; i++) stage_q[i] <= stage_q[i-1];
      end
    end
    assign q_o = stage_q[Depth-1];
  end

endmodule

`default_nettype wire
