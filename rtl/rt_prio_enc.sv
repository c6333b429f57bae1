// rt_prio_enc: the lowest set bit of a vector of N bits.
//
// valid_o says whether any bit of req_i is set, idx_o is the lowest set bit's
// index (0 when none is set).
//
// Two descriptions of this function, chosen by Words:
// - Words = 0, the hardware: a binary tree of 2-input encoders over the bits
//   padded to a power of two. Each node is valid when either child is, and
//   takes the lower child's index when that child is valid, else the upper
//   child's; the root's index is zeroed when no bit is set. Logic depth
//   grows with log2(N), area with N.
// - Words = 1, for simulation: the lowest set bit isolated as
//   req & (~req + 1), bit k of the index the OR over the positions whose bit
//   k is one. A simulator evaluates these as a few operations on whole
//   words, where the tree takes one per node (evaluated as trees, the
//   default core's encoders halve its simulation speed). As hardware the
//   add is a carry chain, which is why synthesis takes the tree.
// Words defaults to 1 under Verilator and 0 elsewhere (Yosys); the bench
// (tests/rtl/prio_enc_bench.cpp) checks both against one C++ model at every
// width it runs.
`default_nettype none

module rt_prio_enc #(
  parameter int unsigned N = 4,
`ifdef VERILATOR
  parameter bit Words = 1'b1,
`else
  parameter bit Words = 1'b0,
`endif
  localparam int unsigned IdxW = (N > 1) ? $clog2(N) : 1
) (
  input  logic [N-1:0]    req_i,
  output logic            valid_o,
  output logic [IdxW-1:0] idx_o
);

  if (N < 1) begin : g_bad_n
    $error("rt_prio_enc: N must be at least 1");
  end

  // The positions whose index has bit k set.
  function automatic logic [N-1:0] index_mask(input int unsigned k);
    int unsigned i;
    index_mask = '0;
    for (i = 0; i < N; i++) index_mask[i] = ((i >> k) & 1) == 1;
  endfunction

  if (Words) begin : g_words
    logic [N-1:0] lowest;
    assign lowest = req_i & (~req_i + N'(1));
    assign valid_o = |req_i;
    for (genvar k = 0; k < IdxW; k++) begin : g_idx_bit
      localparam logic [N-1:0] IndexMask = index_mask(k);
      assign idx_o[k] = |(lowest & IndexMask);
    end
  end else begin : g_tree
    // The tree as a heap: node 0 is the root, node n's children are 2n+1
    // (the lower indices) and 2n+2; leaf i is node Leaves-1+i.
    localparam int unsigned Levels = (N > 1) ? $clog2(N) : 0;
    localparam int unsigned Leaves = 1 << Levels;
    localparam int unsigned Nodes = 2 * Leaves - 1;
    localparam int Inner = Leaves - 1;  // the nodes above the leaves
    logic [Leaves-1:0]     req_pad;
    logic [Nodes-1:0]      node_valid;
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
  end

endmodule

`default_nettype wire
