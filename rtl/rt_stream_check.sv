// rt_stream_check: simulation-only check of picorv32's valid/ready rule on
// one stream: once valid is high without ready, valid stays high and the
// payload stays the same until the cycle ready is high. Instantiate one per
// stream, on the producer's side or the consumer's; synthesis sees an empty
// module. Verilator needs --assert for the checks to fire.
`default_nettype none

module rt_stream_check #(
  parameter int unsigned Width = 1,
  /* verilator lint_off UNUSEDPARAM */
  parameter Name = "stream"  // unused when SYNTHESIS is defined
  /* verilator lint_on UNUSEDPARAM */
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             valid_i,
  input logic             ready_i,
  input logic [Width-1:0] payload_i
);

`ifndef SYNTHESIS
  logic             wait_q;
  logic [Width-1:0] payload_q;
  always_ff @(posedge clk_i) payload_q <= payload_i;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wait_q <= 1'b0;
    end else begin
      if (wait_q) begin
        assert (valid_i) else $error("%s: valid fell before ready", Name);
        assert (payload_i == payload_q) else $error("%s: payload changed before ready", Name);
      end
      wait_q <= valid_i && !ready_i;
    end
  end
`else
  /* verilator lint_off UNUSEDSIGNAL */
  logic unused;
  assign unused = ^{clk_i, rst_ni, valid_i, ready_i, payload_i};
  /* verilator lint_on UNUSEDSIGNAL */
`endif

endmodule

`default_nettype wire
