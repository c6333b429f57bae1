// rt_cache: direct-mapped, read-only, blocking cache of whole lines.
//
// A request names a line by `key_i` (any number that identifies the line: a
// line address, or a triangle id) and gives the byte address of the line's
// first 16-byte beat. A hit answers the next cycle, one request per cycle; a
// miss fetches LineBeats consecutive beats from memory (any order, any
// latency), fills the line and answers; the cache takes no request while it
// misses. Responses come back in request order with the request's tag.
//
// Memory requests carry the beat number in mem_req_beat_o; the surrounding
// arbiter routes responses back with it.
`default_nettype none

module rt_cache #(
  parameter int unsigned Lines = 64,
  parameter int unsigned LineBeats = 2,
  parameter int unsigned KeyWidth = 24,
  parameter int unsigned AddrWidth = 32,
  parameter int unsigned TagWidth = 8,
  localparam int unsigned LineBits = LineBeats * 128,
  localparam int unsigned IdxW = (Lines > 1) ? $clog2(Lines) : 1,
  localparam int unsigned BeatW = 2
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  // requests
  input  logic                 req_valid_i,
  output logic                 req_ready_o,
  input  logic [KeyWidth-1:0]  req_key_i,
  input  logic [AddrWidth-1:0] req_addr_i,
  input  logic [TagWidth-1:0]  req_tag_i,
  // responses
  output logic                 resp_valid_o,
  input  logic                 resp_ready_i,
  output logic [LineBits-1:0]  resp_data_o,
  output logic [TagWidth-1:0]  resp_tag_o,
  // memory side
  output logic                 mem_req_valid_o,
  input  logic                 mem_req_ready_i,
  output logic [AddrWidth-1:0] mem_req_addr_o,
  output logic [BeatW-1:0]     mem_req_beat_o,
  input  logic                 mem_resp_valid_i,
  input  logic [BeatW-1:0]     mem_resp_beat_i,
  input  logic [127:0]         mem_resp_data_i,
  // performance events
  output logic                 hit_o,
  output logic                 miss_o,
  output logic                 filling_o   // a miss is being served
);

  logic [LineBits-1:0] data_q [Lines];
  logic [KeyWidth-1:0] key_q [Lines];
  logic [Lines-1:0]    valid_q;

  logic                 filling_q;
  logic [KeyWidth-1:0]  fill_key_q;
  logic [AddrWidth-1:0] fill_addr_q;
  logic [TagWidth-1:0]  fill_tag_q;
  logic [BeatW:0]       sent_q;      // beats requested so far
  logic [LineBeats-1:0] got_q;       // beats received
  logic [LineBits-1:0]  fill_data_q;

  logic                resp_valid_q;
  logic [LineBits-1:0] resp_data_q;
  logic [TagWidth-1:0] resp_tag_q;

  logic [IdxW-1:0] req_idx, fill_idx;
  logic            lookup_hit, accept, out_free, fill_done;

  // Lines is a power of two: the index is the key's low bits.
  assign req_idx = req_key_i[IdxW-1:0];
  assign fill_idx = fill_key_q[IdxW-1:0];
  assign lookup_hit = valid_q[req_idx] && key_q[req_idx] == req_key_i;
  assign out_free = !resp_valid_q || resp_ready_i;
  assign req_ready_o = !filling_q && out_free;
  assign accept = req_valid_i && req_ready_o;
  assign fill_done = filling_q && (&got_q) && out_free;

  assign filling_o = filling_q;
  assign hit_o = accept && lookup_hit;
  assign miss_o = accept && !lookup_hit;

  assign mem_req_valid_o = filling_q && (sent_q < (BeatW + 1)'(LineBeats));
  assign mem_req_addr_o = fill_addr_q + AddrWidth'(sent_q) * AddrWidth'(16);
  assign mem_req_beat_o = sent_q[BeatW-1:0];

  assign resp_valid_o = resp_valid_q;
  assign resp_data_o = resp_data_q;
  assign resp_tag_o = resp_tag_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= '0;
      filling_q <= 1'b0;
      resp_valid_q <= 1'b0;
      sent_q <= '0;
      got_q <= '0;
    end else begin
      if (resp_valid_q && resp_ready_i) resp_valid_q <= 1'b0;
      if (accept) begin
        if (lookup_hit) begin
          resp_valid_q <= 1'b1;
        end else begin
          filling_q <= 1'b1;
          sent_q <= '0;
          got_q <= '0;
        end
      end
      if (mem_req_valid_o && mem_req_ready_i) sent_q <= sent_q + 1'b1;
      if (filling_q && mem_resp_valid_i) got_q <= got_q | LineBeats'(1 << mem_resp_beat_i);
      if (fill_done) begin
        filling_q <= 1'b0;
        valid_q[fill_idx] <= 1'b1;
        resp_valid_q <= 1'b1;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (accept) begin
      if (lookup_hit) begin
        resp_data_q <= data_q[req_idx];
        resp_tag_q <= req_tag_i;
      end else begin
        fill_key_q <= req_key_i;
        fill_addr_q <= req_addr_i;
        fill_tag_q <= req_tag_i;
      end
    end
    if (filling_q && mem_resp_valid_i) begin
      fill_data_q[128*mem_resp_beat_i +: 128] <= mem_resp_data_i;
    end
    if (fill_done) begin
      data_q[fill_idx] <= fill_data_q;
      key_q[fill_idx] <= fill_key_q;
      resp_data_q <= fill_data_q;
      resp_tag_q <= fill_tag_q;
    end
  end

endmodule

`default_nettype wire
