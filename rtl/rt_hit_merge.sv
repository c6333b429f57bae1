// rt_hit_merge: the closest hit of each thread of rt_core and the merge of
// the triangle tests' results into it (docs/core-interface.md).
//
// A new ray (init_i) sets its thread's closest hit to "nothing closer than
// init_t_i": no hit, t = init_t_i (the ray's tmax), u = v = 0, the triangle
// id all ones. A test result that hit (cand_valid_i && cand_hit_i) then
// replaces its thread's closest hit when it is closer, with TraceRay's rule
// (sw/trace/traversal.h, the model's comparisons fp::Lt, fp::Eq):
//   take it if t < best.t, or t == best.t and (no hit yet or id < best.id)
// decided in the cycle it arrives (one fp_cmp without stages against the
// thread's best t) and seen from the next cycle on. An init and a result for
// the same thread in one cycle: the init wins (rt_core never has both). Three
// read ports give a thread's closest hit: its t (the tmax of a leaf that
// starts) and its hit and t (the leaf exit's rule), combinational, and the
// whole record (the hit output): hit, id and t combinational, u and v from a
// memory with an SRAM's ports (rt_ram_1r1w), read at out_idx_i when out_re_i
// and shown from the next cycle on until the next read. u and v are written
// only by a result that is taken (an init leaves them: they mean something
// only while the thread has a hit); a read of a thread that a result updates
// in the same cycle would give the old u and v, which rt_core never does (the
// hit output reads a thread that has finished its tests; asserted below).
`default_nettype none
// Unused outputs of fp_cmp are left open on purpose.
/* verilator lint_off PINCONNECTEMPTY */

module rt_hit_merge #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23,
  parameter int unsigned Threads = 32,
  parameter int unsigned PrimWidth = 24,
  localparam int unsigned W = E + M + 1,
  localparam int unsigned ThW = (Threads > 1) ? $clog2(Threads) : 1
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  // a new ray
  input  logic                 init_i,
  input  logic [ThW-1:0]       init_idx_i,
  input  logic [W-1:0]         init_t_i,
  // a triangle test's result (rt_isect_unit)
  input  logic                 cand_valid_i,
  input  logic [ThW-1:0]       cand_idx_i,
  input  logic                 cand_hit_i,
  input  logic [PrimWidth-1:0] cand_prim_i,
  input  logic [W-1:0]         cand_t_i,
  input  logic [W-1:0]         cand_u_i,
  input  logic [W-1:0]         cand_v_i,
  output logic                 cand_take_o,  // the result becomes its thread's closest hit
  // read ports: leaf_idx_i's t; exit_idx_i's hit and t; out_idx_i's record
  input  logic [ThW-1:0]       leaf_idx_i,
  output logic [W-1:0]         leaf_t_o,
  input  logic [ThW-1:0]       exit_idx_i,
  output logic                 exit_hit_o,
  output logic [W-1:0]         exit_t_o,
  input  logic [ThW-1:0]       out_idx_i,
  output logic                 out_hit_o,
  output logic [PrimWidth-1:0] out_prim_o,
  output logic [W-1:0]         out_t_o,
  input  logic                 out_re_i,  // read out_idx_i's u and v
  output logic [W-1:0]         out_u_o,   // of the last read, from the next cycle on
  output logic [W-1:0]         out_v_o
);

  logic [Threads-1:0]   hit_q;
  logic [W-1:0]         t_q [Threads];
  logic [PrimWidth-1:0] prim_q [Threads];

  logic t_lt_best, t_eq_best;
  fp_cmp #(.E(E), .M(M), .Stages(0)) u_cmp_best (
    .clk_i, .rst_ni, .en_i(1'b1), .valid_i(1'b1), .a_i(cand_t_i), .b_i(t_q[cand_idx_i]),
    .valid_o(), .lt_o(t_lt_best), .le_o(), .eq_o(t_eq_best), .min_o(), .max_o()
  );
  assign cand_take_o = cand_valid_i && cand_hit_i &&
                       (t_lt_best || (t_eq_best && (!hit_q[cand_idx_i] || cand_prim_i < prim_q[cand_idx_i])));

  // One write port for the init, one for the result (never the init's thread).
  logic cand_write;
  assign cand_write = cand_take_o && !(init_i && init_idx_i == cand_idx_i);
  always_ff @(posedge clk_i) begin
    if (init_i) begin
      hit_q[init_idx_i] <= 1'b0;
      t_q[init_idx_i] <= init_t_i;
      prim_q[init_idx_i] <= '1;
    end
    if (cand_write) begin
      hit_q[cand_idx_i] <= 1'b1;
      t_q[cand_idx_i] <= cand_t_i;
      prim_q[cand_idx_i] <= cand_prim_i;
    end
  end

  assign leaf_t_o = t_q[leaf_idx_i];
  assign {exit_hit_o, exit_t_o} = {hit_q[exit_idx_i], t_q[exit_idx_i]};
  assign {out_hit_o, out_prim_o, out_t_o} = {hit_q[out_idx_i], prim_q[out_idx_i], t_q[out_idx_i]};

  rt_ram_1r1w #(.Words(Threads), .Width(2 * W)) u_uv (
    .clk_i, .we_i(cand_write), .waddr_i(cand_idx_i), .wdata_i({cand_u_i, cand_v_i}),
    .re_i(out_re_i), .raddr_i(out_idx_i), .rdata_o({out_u_o, out_v_o})
  );

`ifndef SYNTHESIS
  always_ff @(posedge clk_i) begin
    if (rst_ni && out_re_i && cand_write) begin
      assert (cand_idx_i != out_idx_i)
      else $error("rt_hit_merge: thread %0d's u, v read in the cycle a result updates them", out_idx_i);
    end
  end
`endif

endmodule

`default_nettype wire
