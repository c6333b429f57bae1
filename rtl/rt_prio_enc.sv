// rt_prio_enc: the lowest set bit of a vector of N bits.
//
// valid_o says whether any bit of req_i is set, idx_o is the lowest set bit's
// index (0 when none is set). A binary tree of 2-input encoders over the bits
// padded to a power of two: each node is valid when either child is, and
// takes the lower child's index when that child is valid, else the upper
// child's; the root's index is zeroed when no bit is set. Logic depth grows
// with log2(N), not N.
`default_nettype none

module rt_prio_enc #(
  parameter int unsigned N = 4,
  localparam int unsigned IdxW = (N > 1) ? $clog2(N) : 1
) (
  input  logic [N-1:0]    req_i,
  output logic            valid_o,
  output logic [IdxW-1:0] idx_o
);

  // The tree as a heap: node 0 is the root, node n's children are 2n+1 (the
  // lower indices) and 2n+2; leaf i is node Leaves-1+i.
  localparam int unsigned Levels = (N > 1) ? $clog2(N) : 0;
  localparam int unsigned Leaves = 1 << Levels;
  localparam int unsigned Nodes = 2 * Leaves - 1;
  localparam int Inner = Leaves - 1;  // the nodes above the leaves

  if (N < 1) begin : g_bad_n
    $error("rt_prio_enc: N must be at least 1");
  end

  logic [Leaves-1:0]    req_pad;
  logic [Nodes-1:0]     node_valid;
  logic [Nodes*IdxW-1:0] node_idx;
  assign req_pad = Leaves'(req_i);
  always_comb begin
    node_valid = '0;
    node_idx = '0;
    for (int unsigned i = 0; i < Leaves; i++) begin
      node_valid[Leaves - 1 + i] = req_pad[i];
      node_idx[IdxW*(Leaves - 1 + i) +: IdxW] = IdxW'(i);
    end
    for (int n = Inner - 1; n >= 0; n--) begin
      node_valid[n] = node_valid[2*n + 1] || node_valid[2*n + 2];
      node_idx[IdxW*n +: IdxW] = node_valid[2*n + 1] ? node_idx[IdxW*(2*n + 1) +: IdxW]
                                                     : node_idx[IdxW*(2*n + 2) +: IdxW];
    end
  end
  assign valid_o = node_valid[0];
  assign idx_o = node_valid[0] ? node_idx[IdxW-1:0] : '0;

endmodule

`default_nettype wire
