// rt_hit_out: rt_core's hit record register. It takes a finished ray's
// closest hit in the datapath format (E, M) and holds its record in fp32 bits
// until hit_ready_i: on a hit the triangle id, t in world units and u, v; on
// a miss id 0xFFFFFFFF, t = +inf and u = v = 0. t, u, v are widened exactly to
// fp32 (fp_to_f32); t then goes back from the image's frame to world units,
// t = ldexp(t, k) in fp32 (fp_ldexp) with the ray's distance scale k from
// rt_ray_setup, exactly the model's DistanceToWorld (sw/trace/frame.h,
// docs/dataflow.md step 0): exact unless it leaves fp32's normal range
// (then a signed zero or an infinity). A new record is taken in the cycle
// the held one leaves (in_ready_o = !hit_valid_o || hit_ready_i). The input
// may change while not taken (the core offers whichever finished ray its
// arbiter picks); the output stream follows picorv32's rule (checked).
// The ray id, u and v are not taken from the input: rt_core keeps them in
// memories with an SRAM's registered read, read at the ray taken in the cycle
// it is taken (in_valid_i && in_ready_o) and shown from the next cycle until
// the next read (rd_ray_id_i, rd_u_i, rd_v_i): the memories' read registers
// are the record's ray id, u and v.
`default_nettype none

module rt_hit_out #(
  parameter int unsigned E = 8,
  parameter int unsigned M = 23,
  parameter int unsigned RayIdWidth = 32,
  parameter int unsigned PrimWidth = 24,
  localparam int unsigned W = E + M + 1
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic                  in_valid_i,
  output logic                  in_ready_o,
  input  logic                  in_hit_i,
  input  logic [PrimWidth-1:0]  in_prim_i,
  input  logic [W-1:0]          in_t_i,      // along the framed ray
  input  logic signed [kdrt_pkg::TScaleWidth-1:0] in_t_scale_i,  // k: world t = t * 2^k
  input  logic                  in_overflow_i,
  input  logic [RayIdWidth-1:0] rd_ray_id_i,  // the ray id, u, v read at the last record taken
  input  logic [W-1:0]          rd_u_i,
  input  logic [W-1:0]          rd_v_i,
  output logic                  hit_valid_o,
  input  logic                  hit_ready_i,
  output logic [RayIdWidth-1:0] hit_ray_id_o,
  output logic                  hit_o,
  output logic [31:0]           hit_prim_o,
  output logic [31:0]           hit_t_o,
  output logic [31:0]           hit_u_o,
  output logic [31:0]           hit_v_o,
  output logic                  hit_overflow_o
);

  logic        in_fire;
  logic [31:0] wide_t, world_t, wide_u, wide_v;
  assign in_ready_o = !hit_valid_o || hit_ready_i;
  assign in_fire = in_valid_i && in_ready_o;
  fp_to_f32 #(.E(E), .M(M)) u_wide_t (.a_i(in_t_i), .f32_o(wide_t));
  fp_ldexp #(.E(8), .M(23), .NW(kdrt_pkg::TScaleWidth)) u_world_t (
    .a_i(wide_t), .n_i(in_t_scale_i), .y_o(world_t)
  );
  fp_to_f32 #(.E(E), .M(M)) u_wide_u (.a_i(rd_u_i), .f32_o(wide_u));
  fp_to_f32 #(.E(E), .M(M)) u_wide_v (.a_i(rd_v_i), .f32_o(wide_v));
  assign hit_ray_id_o = rd_ray_id_i;
  assign hit_u_o = hit_o ? wide_u : 32'h0;
  assign hit_v_o = hit_o ? wide_v : 32'h0;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      hit_valid_o <= 1'b0;
    end else begin
      if (hit_valid_o && hit_ready_i) hit_valid_o <= 1'b0;
      if (in_fire) hit_valid_o <= 1'b1;
    end
  end

  always_ff @(posedge clk_i) begin
    if (in_fire) begin
      hit_o <= in_hit_i;
      hit_prim_o <= in_hit_i ? 32'(in_prim_i) : 32'hFFFF_FFFF;
      hit_t_o <= in_hit_i ? world_t : 32'h7F80_0000;
      hit_overflow_o <= in_overflow_i;
    end
  end

  rt_stream_check #(.Width(RayIdWidth + 1 + 4 * 32 + 1), .Name("rt_hit_out")) u_out_check (
    .clk_i, .rst_ni, .valid_i(hit_valid_o), .ready_i(hit_ready_i),
    .payload_i({hit_ray_id_o, hit_o, hit_prim_o, hit_t_o, hit_u_o, hit_v_o, hit_overflow_o})
  );

endmodule

`default_nettype wire
