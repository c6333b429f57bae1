// rt_rr_arb: round-robin choice of one requester among N.
//
// gnt_o is one-hot among req_i (or zero), starting the search just after the
// last requester that was granted and accepted (ack_i), so every requester is
// served within N acknowledged grants. Combinational grant (logic depth
// growing with log2(N)), registered pointer.
`default_nettype none

module rt_rr_arb #(
  parameter int unsigned N = 4,
  parameter int unsigned IdxW = (N > 1) ? $clog2(N) : 1,
  localparam int unsigned EncW = (N > 1) ? $clog2(N) : 1  // rt_prio_enc's index
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic [N-1:0]    req_i,
  input  logic            ack_i,    // the granted requester was served this cycle
  output logic            valid_o,  // some requester is granted
  output logic [IdxW-1:0] idx_o
);

  logic [IdxW-1:0] last_q;

  // The requesters strictly after last_q come first (their lowest index),
  // else the lowest of all, which wraps around to last_q itself last: two
  // log-depth priority encoders and a multiplexer.
  logic [N-1:0]       after;
  logic               after_valid;
  logic [EncW-1:0]    after_idx, all_idx;
  // The requesters above the last grant (a shifted mask, not a comparison
  // per requester).
  assign after = ({N{1'b1}} << last_q) << 1;
  if (N == 1) begin : g_single  // one requester: the pointer chooses nothing
    logic unused_last;
    assign unused_last = ^last_q;
  end
  rt_prio_enc #(.N(N)) u_after_enc (.req_i(req_i & after), .valid_o(after_valid), .idx_o(after_idx));
  rt_prio_enc #(.N(N)) u_all_enc (.req_i(req_i), .valid_o(valid_o), .idx_o(all_idx));
  assign idx_o = IdxW'(after_valid ? after_idx : all_idx);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      last_q <= IdxW'(N - 1);
    end else if (ack_i && valid_o) begin
      last_q <= idx_o;
    end
  end

endmodule

`default_nettype wire
