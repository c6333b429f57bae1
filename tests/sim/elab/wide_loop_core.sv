// Fixture for the test core_elaboration_unrolls_like_models: a delayed
// assignment to an unpacked array in a loop of 128 iterations, as rt_core's
// per-thread loops have with 128 threads. Verilator 5.006 elaborates it only
// when it unrolls the loop (--unroll-count above 64, as the model builds do).
`default_nettype none
module rt_core (
  input  wire       clk_i,
  input  wire       rst_ni,
  input  wire [6:0] idx_i,
  output wire [3:0] count_o
);
  logic [3:0] count_q [128];
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int i = 0; i < 128; i++) count_q[i] <= '0;
    end else begin
      count_q[idx_i] <= count_q[idx_i] + 4'd1;
    end
  end
  assign count_o = count_q[idx_i];
endmodule
`default_nettype wire
