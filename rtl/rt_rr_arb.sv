// rt_rr_arb: round-robin choice of one requester among N.
//
// gnt_o is one-hot among req_i (or zero), starting the search just after the
// last requester that was granted and accepted (ack_i), so every requester is
// served within N acknowledged grants. Combinational grant, registered pointer.
`default_nettype none

module rt_rr_arb #(
  parameter int unsigned N = 4,
  parameter int unsigned IdxW = (N > 1) ? $clog2(N) : 1
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic [N-1:0]    req_i,
  input  logic            ack_i,    // the granted requester was served this cycle
  output logic            valid_o,  // some requester is granted
  output logic [IdxW-1:0] idx_o
);

  logic [IdxW-1:0] last_q;

  always_comb begin
    valid_o = 1'b0;
    idx_o = '0;
    // Highest priority: the requester after last_q, wrapping around.
    for (int unsigned k = N; k >= 1; k--) begin
      logic [IdxW-1:0] i;
      i = IdxW'((32'(last_q) + k) % N);
      if (req_i[i]) begin
        valid_o = 1'b1;
        idx_o = i;
      end
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      last_q <= IdxW'(N - 1);
    end else if (ack_i && valid_o) begin
      last_q <= idx_o;
    end
  end

endmodule

`default_nettype wire
