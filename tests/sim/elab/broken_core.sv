// Fixture for the test core_elaboration_rejects_a_broken_core: rt_core
// instantiates a module that does not exist.
`default_nettype none
module rt_core (
  input  wire clk_i,
  output wire bit_o
);
  rt_no_such_unit u_missing (.clk_i(clk_i), .bit_o(bit_o));
endmodule
`default_nettype wire
