// rt_cache: direct-mapped, read-only, non-blocking cache of whole lines.
//
// A request names a line by `key_i` (any number that identifies the line: a
// line address, or a triangle id) and gives the byte address of the line's
// first 16-byte beat. A hit answers the next cycle, one request per cycle,
// also while misses are being served (hit under miss). A miss takes one of
// Mshrs miss registers, which fetches LineBeats consecutive beats from memory
// (any order, any latency) into its own line buffer; when all beats are in,
// the line is written into the cache and answered. Several misses are thus in
// flight at once, and responses come back OUT OF ORDER, each with its
// request's tag.
//
// The request stalls (req_ready_o low) while the response register is full,
// while a completed miss is being answered, when it misses on a line that a
// miss register is already fetching (it then hits after the fill: no merging,
// never stale data), or when it misses and no miss register is free.
//
// Memory requests carry {miss register, beat} in mem_req_id_o; the
// surrounding arbiter routes responses back with it (mem_resp_id_i).
`default_nettype none

module rt_cache #(
  parameter int unsigned Lines = 64,
  parameter int unsigned LineBeats = 2,
  parameter int unsigned KeyWidth = 24,
  parameter int unsigned AddrWidth = 32,
  parameter int unsigned TagWidth = 8,
  parameter int unsigned Mshrs = 4,
  localparam int unsigned LineBits = LineBeats * 128,
  localparam int unsigned IdxW = (Lines > 1) ? $clog2(Lines) : 1,
  localparam int unsigned BeatW = 2,
  localparam int unsigned MshrW = (Mshrs > 1) ? $clog2(Mshrs) : 1,
  localparam int unsigned MemIdW = MshrW + BeatW
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
  // memory side: id = {miss register, beat}
  output logic                 mem_req_valid_o,
  input  logic                 mem_req_ready_i,
  output logic [AddrWidth-1:0] mem_req_addr_o,
  output logic [MemIdW-1:0]    mem_req_id_o,
  input  logic                 mem_resp_valid_i,
  input  logic [MemIdW-1:0]    mem_resp_id_i,
  input  logic [127:0]         mem_resp_data_i,
  // performance events
  output logic                 hit_o,
  output logic                 miss_o,
  output logic                 filling_o   // some miss is being served
);

  localparam int unsigned CntW = BeatW + 1;

  logic [LineBits-1:0] data_q [Lines];
  logic [KeyWidth-1:0] key_q [Lines];
  logic [Lines-1:0]    valid_q;

  // Miss registers (MSHRs), flat vectors indexed by the register number.
  logic [Mshrs-1:0]           mshr_valid_q;
  logic [Mshrs*KeyWidth-1:0]  mshr_key_q;
  logic [Mshrs*AddrWidth-1:0] mshr_addr_q;
  logic [Mshrs*TagWidth-1:0]  mshr_tag_q;
  logic [Mshrs*CntW-1:0]      mshr_sent_q;   // beats requested so far
  logic [Mshrs*LineBeats-1:0] mshr_got_q;    // beats received
  logic [Mshrs*LineBits-1:0]  mshr_data_q;

  logic                resp_valid_q;
  logic [LineBits-1:0] resp_data_q;
  logic [TagWidth-1:0] resp_tag_q;

  // Per-register conditions and the lowest-numbered register of each kind.
  logic [Mshrs-1:0] key_match, done, sending;
  logic             free_valid, done_valid, send_valid, pick_valid;
  logic [MshrW-1:0] free_idx, done_idx, send_idx, pick_idx;
  for (genvar m = 0; m < Mshrs; m++) begin : g_mshr
    assign key_match[m] = mshr_valid_q[m] && mshr_key_q[KeyWidth*m +: KeyWidth] == req_key_i;
    assign done[m] = mshr_valid_q[m] && (&mshr_got_q[LineBeats*m +: LineBeats]);
    assign sending[m] = mshr_valid_q[m] && mshr_sent_q[CntW*m +: CntW] < CntW'(LineBeats);
  end
  always_comb begin
    free_valid = 1'b0;
    free_idx = '0;
    done_valid = 1'b0;
    done_idx = '0;
    pick_valid = 1'b0;
    pick_idx = '0;
    for (int m = Mshrs - 1; m >= 0; m--) begin
      if (!mshr_valid_q[m]) begin
        free_valid = 1'b1;
        free_idx = MshrW'(m);
      end
      if (done[m]) begin
        done_valid = 1'b1;
        done_idx = MshrW'(m);
      end
      if (sending[m]) begin
        pick_valid = 1'b1;
        pick_idx = MshrW'(m);
      end
    end
  end

  logic [IdxW-1:0]     req_idx, done_line;
  logic [KeyWidth-1:0] done_key;
  logic [LineBits-1:0] done_data;
  logic [TagWidth-1:0] done_tag;
  logic                lookup_hit, accept, out_free, deliver;

  // Lines is a power of two: the index is the key's low bits.
  assign req_idx = req_key_i[IdxW-1:0];
  assign done_key = mshr_key_q[KeyWidth*done_idx +: KeyWidth];
  assign done_line = done_key[IdxW-1:0];
  assign done_data = mshr_data_q[LineBits*done_idx +: LineBits];
  assign done_tag = mshr_tag_q[TagWidth*done_idx +: TagWidth];

  assign lookup_hit = valid_q[req_idx] && key_q[req_idx] == req_key_i;
  assign out_free = !resp_valid_q || resp_ready_i;
  // Completed misses go first: they free their register.
  assign deliver = done_valid && out_free;
  assign req_ready_o = out_free && !done_valid && (lookup_hit || (free_valid && !(|key_match)));
  assign accept = req_valid_i && req_ready_o;

  assign filling_o = |mshr_valid_q;
  assign hit_o = accept && lookup_hit;
  assign miss_o = accept && !lookup_hit;

  // A beat offered to memory and not taken stays offered (the valid/ready
  // rule), even if a lower-numbered miss register starts sending meanwhile.
  logic             send_held_q;
  logic [MshrW-1:0] send_held_idx_q;
  assign send_idx = send_held_q ? send_held_idx_q : pick_idx;
  assign send_valid = send_held_q || pick_valid;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      send_held_q <= 1'b0;
      send_held_idx_q <= '0;
    end else begin
      send_held_q <= send_valid && !mem_req_ready_i;
      send_held_idx_q <= send_idx;
    end
  end
  rt_stream_check #(.Width(AddrWidth + MshrW + BeatW), .Name("rt_cache memory request")) u_mem_check (
    .clk_i, .rst_ni, .valid_i(mem_req_valid_o), .ready_i(mem_req_ready_i),
    .payload_i({mem_req_addr_o, mem_req_id_o})
  );

  logic [CntW-1:0] send_beat;
  assign send_beat = mshr_sent_q[CntW*send_idx +: CntW];
  assign mem_req_valid_o = send_valid;
  assign mem_req_addr_o = mshr_addr_q[AddrWidth*send_idx +: AddrWidth] +
                          AddrWidth'(send_beat) * AddrWidth'(16);
  assign mem_req_id_o = {send_idx, send_beat[BeatW-1:0]};

  logic [MshrW-1:0] resp_mshr;
  logic [BeatW-1:0] resp_beat;
  assign {resp_mshr, resp_beat} = mem_resp_id_i;

  assign resp_valid_o = resp_valid_q;
  assign resp_data_o = resp_data_q;
  assign resp_tag_o = resp_tag_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= '0;
      mshr_valid_q <= '0;
      mshr_sent_q <= '0;
      mshr_got_q <= '0;
      resp_valid_q <= 1'b0;
    end else begin
      if (resp_valid_q && resp_ready_i) resp_valid_q <= 1'b0;
      if (accept) begin
        if (lookup_hit) begin
          resp_valid_q <= 1'b1;
        end else begin
          mshr_valid_q[free_idx] <= 1'b1;
          mshr_sent_q[CntW*free_idx +: CntW] <= '0;
          mshr_got_q[LineBeats*free_idx +: LineBeats] <= '0;
        end
      end
      if (mem_req_valid_o && mem_req_ready_i) begin
        mshr_sent_q[CntW*send_idx +: CntW] <= send_beat + 1'b1;
      end
      if (mem_resp_valid_i) begin
        mshr_got_q[LineBeats*resp_mshr +: LineBeats] <=
            mshr_got_q[LineBeats*resp_mshr +: LineBeats] | LineBeats'(1 << resp_beat);
      end
      if (deliver) begin
        mshr_valid_q[done_idx] <= 1'b0;
        valid_q[done_line] <= 1'b1;
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
        mshr_key_q[KeyWidth*free_idx +: KeyWidth] <= req_key_i;
        mshr_addr_q[AddrWidth*free_idx +: AddrWidth] <= req_addr_i;
        mshr_tag_q[TagWidth*free_idx +: TagWidth] <= req_tag_i;
      end
    end
    if (mem_resp_valid_i) begin
      mshr_data_q[LineBits*resp_mshr + 128*resp_beat +: 128] <= mem_resp_data_i;
    end
    if (deliver) begin
      data_q[done_line] <= done_data;
      key_q[done_line] <= done_key;
      resp_data_q <= done_data;
      resp_tag_q <= done_tag;
    end
  end

endmodule

`default_nettype wire
