// rt_mem_arb: shares the core's one memory port among its caches.
//
// Round-robin over the requesting caches. A request's tag is the cache's
// number (2 bits) above the cache's own id of the request (IdW bits: its miss
// register and the beat within the line, see rt_cache), zero-extended to 8
// bits; the response is routed back by it, so responses may come back in any
// order. Responses are never refused. Needs N <= 4 and IdW <= 6.
`default_nettype none

module rt_mem_arb #(
  parameter int unsigned N = 3,
  parameter int unsigned AddrWidth = 32,
  parameter int unsigned IdW = 4
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  // cache side
  input  logic [N-1:0]           req_valid_i,
  output logic [N-1:0]           req_ready_o,
  input  logic [N*AddrWidth-1:0] req_addr_i,
  input  logic [N*IdW-1:0]       req_id_i,
  output logic [N-1:0]           resp_valid_o,
  output logic [IdW-1:0]         resp_id_o,
  output logic [127:0]           resp_data_o,
  // memory side
  output logic                   mem_req_valid_o,
  input  logic                   mem_req_ready_i,
  output logic [AddrWidth-1:0]   mem_req_addr_o,
  output logic [15:0]            mem_req_tag_o,
  input  logic                   mem_resp_valid_i,
  input  logic [15:0]            mem_resp_tag_i,
  input  logic [127:0]           mem_resp_data_i
);

  localparam int unsigned GntW = (N > 1) ? $clog2(N) : 1;

  logic            gnt_valid;
  logic [GntW-1:0] gnt;

  // A request offered and not taken stays granted until it is taken, so the
  // memory port keeps valid and payload stable (the valid/ready rule).
  logic            held_q;
  logic [GntW-1:0] held_gnt_q, sel;
  logic            sel_valid, rr_valid;
  logic [GntW-1:0] rr_gnt;

  rt_rr_arb #(.N(N)) u_arb (
    .clk_i,
    .rst_ni,
    .req_i  (req_valid_i),
    .ack_i  (mem_req_ready_i && !held_q),
    .valid_o(rr_valid),
    .idx_o  (rr_gnt)
  );
  assign sel = held_q ? held_gnt_q : rr_gnt;
  assign sel_valid = held_q ? req_valid_i[held_gnt_q] : rr_valid;
  assign gnt = sel;
  assign gnt_valid = sel_valid;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      held_q <= 1'b0;
      held_gnt_q <= '0;
    end else begin
      held_q <= sel_valid && !mem_req_ready_i;
      held_gnt_q <= sel;
    end
  end

  assign mem_req_valid_o = gnt_valid;
  assign mem_req_addr_o = req_addr_i[AddrWidth*gnt +: AddrWidth];
  assign mem_req_tag_o = 16'({2'(gnt), req_id_i[IdW*gnt +: IdW]});

  logic [1:0] resp_cache;
  assign resp_cache = mem_resp_tag_i[IdW +: 2];
  always_comb begin
    req_ready_o = '0;
    resp_valid_o = '0;
    if (gnt_valid) req_ready_o[gnt] = mem_req_ready_i;
    if (mem_resp_valid_i && 32'(resp_cache) < N) resp_valid_o[resp_cache] = 1'b1;
  end
  assign resp_id_o = mem_resp_tag_i[IdW-1:0];
  /* verilator lint_off UNUSEDSIGNAL */
  logic unused_tag;
  assign unused_tag = ^mem_resp_tag_i;
  /* verilator lint_on UNUSEDSIGNAL */
  assign resp_data_o = mem_resp_data_i;

endmodule

`default_nettype wire
