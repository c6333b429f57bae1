// rt_cache: set-associative (Ways = 1: direct-mapped), read-only,
// non-blocking cache of whole lines.
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
// A miss on a line that a miss register is already fetching joins that
// register (a secondary miss: merged, no second fetch); a register answers up
// to Targets requests, one per cycle, once its line is in. With Targets = 1
// nothing merges: such a request waits until the line is in the cache.
// Hits and completed misses have a response register each, so a hit is
// taken while a miss is being answered; the port shows a completed miss
// first. A hit stalls (req_ready_o low) while its register is full. A miss
// stalls when it would join a register that is full or already answering
// (wait_inflight_o), or needs a register and none is free (wait_mshr_o).
// Data is never stale: the cache is read-only.
//
// Lines / Ways sets of Ways lines; a key's set is its low bits. A completed
// miss fills the way that already holds its line (a register answering
// several requests fills once per answer), else the lowest invalid way,
// else the tree pseudo-LRU victim. The tree's Ways - 1 bits per set (node n
// at level l: bit 2^l - 1 + n; 0 = the victim lies in the lower half) point
// away from every way touched: by a hit taken, then by a fill, in one cycle.
//
// With MissPort = 1 a second request port takes misses only: a request there
// that misses is taken (it joins or gets a miss register) in a cycle in which
// the first port takes no miss; a request that would hit is not taken there
// (it comes again on the first port). So a miss does not cost the first
// port, whose hits are the cache's answers, a cycle. Unused when MissPort = 0.
//
// With PrefetchPort = 1 (and MissPort = 0) the second port takes prefetches:
// a request there whose line is present or being fetched is taken and
// dropped; one that misses takes a free miss register, in a cycle in which
// the first port takes no miss, with no request to answer (count 0). Requests
// on the first port may join it as any other. A completed register with
// count 0 writes its line in the completed misses' slot (one a cycle, under
// the same conditions) and is freed without a response. req2_tag_i is unused
// then, and miss_o counts the first port's misses only.
//
// Memory requests carry {miss register, beat} in mem_req_id_o; the
// surrounding arbiter routes responses back with it (mem_resp_id_i).
`default_nettype none

module rt_cache #(
  parameter int unsigned Lines = 64,
  parameter int unsigned Ways = 1,     // a power of two, at most Lines
  parameter int unsigned LineBeats = 2,
  parameter int unsigned KeyWidth = 24,
  parameter int unsigned AddrWidth = 32,
  parameter int unsigned TagWidth = 8,
  parameter int unsigned Mshrs = 4,
  parameter int unsigned Targets = 1,  // requests a miss register answers (the first and merged ones)
  parameter bit MissPort = 1'b0,       // the second, miss-only request port
  parameter bit PrefetchPort = 1'b0,   // the second port takes prefetches (MissPort = 0)
  // a line's byte address is its key times its bytes (req_addr_i and
  // req2_addr_i are unused): the miss registers keep no address
  parameter bit KeyIsLine = 1'b0,
  // the words of one SRAM macro: the line array and the merged requests are
  // banked so that their access time is a small macro's (rt_ram_banked;
  // up to 256 words a macro's access barely grows, docs/physical.md)
  parameter int unsigned BankWords = 256,
  localparam int unsigned LineBits = LineBeats * 128,
  localparam int unsigned IdxW = (Lines > 1) ? $clog2(Lines) : 1,
  localparam int unsigned Sets = Lines / Ways,
  localparam int unsigned SetW = (Sets > 1) ? $clog2(Sets) : 1,
  // a line keeps its key but the set's bits, which its place gives
  localparam int unsigned SetBits = $clog2(Sets),
  localparam int unsigned LineTagW = (KeyWidth > SetBits) ? KeyWidth - SetBits : 1,
  localparam int unsigned WayW = (Ways > 1) ? $clog2(Ways) : 1,
  localparam int unsigned PlruW = (Ways > 1) ? Ways - 1 : 1,
  localparam int unsigned BeatW = 2,
  localparam int unsigned MshrW = (Mshrs > 1) ? $clog2(Mshrs) : 1,
  localparam int unsigned MemIdW = MshrW + BeatW,
  localparam int unsigned TgtW = $clog2(Targets + 1)  // 0 .. Targets
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  // requests
  input  logic                 req_valid_i,
  output logic                 req_ready_o,
  input  logic [KeyWidth-1:0]  req_key_i,
  input  logic [AddrWidth-1:0] req_addr_i,
  input  logic [TagWidth-1:0]  req_tag_i,
  // the miss-only request port (MissPort)
  input  logic                 req2_valid_i,
  output logic                 req2_ready_o,
  input  logic [KeyWidth-1:0]  req2_key_i,
  input  logic [AddrWidth-1:0] req2_addr_i,
  input  logic [TagWidth-1:0]  req2_tag_i,
  // responses
  output logic                 resp_valid_o,
  input  logic                 resp_ready_i,
  output logic [LineBits-1:0]  resp_data_o,
  output logic [TagWidth-1:0]  resp_tag_o,
  // the tag resp_tag_o shows in the next cycle (whenever resp_valid_o is
  // then high): a memory of the requester's, read at it, answers with a
  // registered read in the cycle the response is shown
  output logic [TagWidth-1:0]  resp_tag_next_o,
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
  output logic                 miss_o,          // a request taken that missed (merged or not)
  output logic                 merge_o,         // ... and joined a miss register already fetching its line
  output logic                 wait_inflight_o, // a miss waits: its line's register is full or answering
  output logic                 wait_mshr_o,     // a miss waits: no miss register is free
  output logic                 prefetch_o,      // a prefetch took a miss register (its line fetched ahead)
  output logic                 filling_o        // some miss is being served
);

  localparam int unsigned CntW = BeatW + 1;

  logic [LineTagW-1:0] key_q [Lines];  // a line's key above its set's bits
  logic [Lines-1:0]    valid_q;
  function automatic logic [LineTagW-1:0] line_tag(input logic [KeyWidth-1:0] key);
    line_tag = LineTagW'(key >> SetBits);
  endfunction

  // Miss registers (MSHRs): the conditions every register is matched or
  // picked by are vectors of a bit per register (valid, beats received,
  // beats left to request, no room for another request), so that they are
  // updated and combined a whole vector at a time; the rest is read at one
  // register's index. The counters and addresses need no reset: they are
  // read only while their register is valid, and set when it is taken.
  logic [Mshrs-1:0]           mshr_valid_q;
  logic [LineBeats*Mshrs-1:0] mshr_got_q;     // beat b received: bits Mshrs b up
  logic [Mshrs-1:0]           mshr_unsent_q;  // beats left to request
  logic [Mshrs-1:0]           mshr_full_q;    // Targets requests joined
  logic [KeyWidth-1:0]        mshr_key_q [Mshrs];
  logic [TgtW-1:0]            mshr_cnt_q [Mshrs];   // requests joined
  logic [TgtW-1:0]            mshr_out_q [Mshrs];   // requests answered
  logic [CntW-1:0]            mshr_sent_q [Mshrs];  // beats requested so far

  // Two response registers, one for hits and one for completed misses, so a
  // hit is taken while a miss is being answered; the response port shows the
  // completed miss first.
  logic                hit_valid_q, del_valid_q;
  logic [LineBits-1:0] hit_data, del_data_q;
  logic [TagWidth-1:0] hit_tag_q, del_tag_q;

  // Per-register conditions and the lowest-numbered register of each kind
  // (key_match2, joinable2: for the miss-only port's key).
  logic [Mshrs-1:0] key_match, done, sending, joinable, key_match2, joinable2, all_got;
  logic             free_valid, done_valid, send_valid, pick_valid, join_valid, join2_valid;
  logic [MshrW-1:0] free_idx, done_idx, send_idx, pick_idx, join_idx, join2_idx;
  logic [MshrW-1:0] done_idx_next, done_idx_q;
  always_comb begin
    for (int unsigned m = 0; m < Mshrs; m++) begin
      key_match[m] = mshr_key_q[m] == req_key_i;
      key_match2[m] = mshr_key_q[m] == req2_key_i;
    end
    key_match &= mshr_valid_q;
    key_match2 &= mshr_valid_q;
    all_got = '1;
    for (int unsigned b = 0; b < LineBeats; b++) all_got &= mshr_got_q[Mshrs*b +: Mshrs];
  end
  assign done = mshr_valid_q & all_got;
  assign sending = mshr_valid_q & mshr_unsent_q;
  assign joinable = key_match & ~done & ~mshr_full_q;
  assign joinable2 = key_match2 & ~done & ~mshr_full_q;
  // Log-depth priority encoders (rtl/rt_prio_enc.sv), one per kind. The
  // completed register is the lowest of `done`, encoded a cycle ahead from
  // the registers' next state (done_idx_next below) into done_idx_q.
  rt_prio_enc #(.N(Mshrs)) u_free_enc (.req_i(~mshr_valid_q), .valid_o(free_valid), .idx_o(free_idx));
  rt_prio_enc #(.N(Mshrs)) u_join_enc (.req_i(joinable), .valid_o(join_valid), .idx_o(join_idx));
  rt_prio_enc #(.N(Mshrs)) u_join2_enc (.req_i(joinable2), .valid_o(join2_valid), .idx_o(join2_idx));
  rt_prio_enc #(.N(Mshrs)) u_pick_enc (.req_i(sending), .valid_o(pick_valid), .idx_o(pick_idx));
  assign done_valid = |done;
  assign done_idx = done_idx_q;

  logic [IdxW-1:0]     hit_line, done_line;
  logic [KeyWidth-1:0] done_key;
  logic [LineBits-1:0] done_data;
  logic [TagWidth-1:0] done_tag;
  logic                lookup_hit, lookup2_hit, accept, deliver, done_last, hit_ok, join_ok, alloc_ok;
  logic                out_take, hit_free, del_free, join2_ok, alloc2_ok, accept2;
  logic [TgtW-1:0]     done_out, done_cnt;
  // The miss taken this cycle (from the first port, else the miss-only one).
  logic                m_take, m_join, m_port2, m_count0;
  logic [MshrW-1:0]    m_join_idx;
  logic [TgtW-1:0]     m_join_cnt;
  logic [KeyWidth-1:0] m_key;
  logic [AddrWidth-1:0] m_addr;
  logic [TagWidth-1:0] m_tag;

  // The completed register's key, read a cycle ahead at done_idx_next as the
  // memories are (a register taken in a cycle is not completed in the next:
  // its beats are still to come).
  logic [KeyWidth-1:0] done_key_q;
  always_ff @(posedge clk_i) done_key_q <= mshr_key_q[done_idx_next];
  assign done_key = done_key_q;
  logic [MshrW-1:0]    resp_mshr;
  logic [BeatW-1:0]    resp_beat;
  assign {resp_mshr, resp_beat} = mem_resp_id_i;
  // A miss taken this cycle is a free register's first request or joins
  // after the requests of the register it joins.
  logic [MshrW-1:0] tgt_wr_mshr;
  logic [TgtW-1:0]  tgt_wr_slot;
  assign tgt_wr_mshr = m_join ? m_join_idx : free_idx;
  assign tgt_wr_slot = m_join ? m_join_cnt : '0;

  // The miss registers' line buffers and merged requests are memories with
  // the ports an SRAM compiler gives (rt_ram_1r1w: one write port, one read
  // port with a registered read): one memory per beat (a word per
  // register) and one of the merged requests, each written once a cycle at
  // most. They are read at the register that is the completed one in the next cycle
  // (done_idx_next: the registers' next state, as the updates below give
  // it), so the registered read gives the completed register's line and
  // requests in the cycle it is answered, as a read of flip-flops at
  // done_idx would. A word written in the cycle it is read (the beat that
  // completes the line, a request joining it) is forwarded.
  // The registers' valid and received-beat vectors take exactly this next
  // state, so done_idx_q is always the lowest completed register.
  //
  // A register taken this cycle is not completed in the next (its beats are
  // still to come, and no beat answers a register that has not asked), so
  // the completed registers of the next cycle do not depend on this cycle's
  // lookup: they are the valid registers with every beat in (`done_stay`),
  // less the completed register if this cycle's answer frees it. Both
  // candidates are encoded in parallel and the answer only chooses between
  // them, so the path from the requester's ready (resp_ready_i) through
  // `deliver` to the memories' read address is a multiplexer, not an
  // encoder over every register.
  logic [Mshrs-1:0] alloc_oh, resp_oh, beat_resp, valid_next, got_all_now, done_stay, done_oh_q;
  logic [LineBeats*Mshrs-1:0] got_next;
  logic             freeing, unused_keep_valid, unused_free_valid;
  logic [MshrW-1:0] done_keep_idx, done_free_idx;
  always_comb begin
    alloc_oh = (m_take && !m_join) ? Mshrs'(1) << free_idx : '0;
    resp_oh = mem_resp_valid_i ? Mshrs'(1) << resp_mshr : '0;
    got_all_now = '1;
    beat_resp = '0;
    for (int unsigned b = 0; b < LineBeats; b++) begin
      beat_resp = resp_beat == BeatW'(b) ? resp_oh : '0;
      got_next[Mshrs*b +: Mshrs] = (mshr_got_q[Mshrs*b +: Mshrs] & ~alloc_oh) | beat_resp;
      got_all_now &= mshr_got_q[Mshrs*b +: Mshrs] | beat_resp;
    end
  end
  assign freeing = deliver && (done_last || done_cnt == '0);
  assign valid_next = (mshr_valid_q | alloc_oh) & ~(freeing ? done_oh_q : '0);
  assign done_stay = mshr_valid_q & got_all_now;
  rt_prio_enc #(.N(Mshrs)) u_done_keep_enc (.req_i(done_stay), .valid_o(unused_keep_valid),
                                            .idx_o(done_keep_idx));
  rt_prio_enc #(.N(Mshrs)) u_done_free_enc (.req_i(done_stay & ~done_oh_q), .valid_o(unused_free_valid),
                                            .idx_o(done_free_idx));
  assign done_idx_next = freeing ? done_free_idx : done_keep_idx;

  for (genvar b = 0; b < LineBeats; b++) begin : g_beat_ram
    logic         we, fwd_q;
    logic [127:0] rdata, fwd_data_q;
    assign we = mem_resp_valid_i && resp_beat == BeatW'(b);
    rt_ram_1r1w #(.Words(Mshrs), .Width(128)) u_ram (
      .clk_i, .we_i(we), .waddr_i(resp_mshr), .wdata_i(mem_resp_data_i), .re_i(1'b1),
      .raddr_i(done_idx_next), .rdata_o(rdata)
    );
    always_ff @(posedge clk_i) begin
      fwd_q <= we && resp_mshr == done_idx_next;
      fwd_data_q <= mem_resp_data_i;
    end
    assign done_data[128*b +: 128] = fwd_q ? fwd_data_q : rdata;
  end

  // The lines: a memory with the ports an SRAM compiler gives, read at a
  // hit (held on resp_data_o until the next hit's read) and written by the
  // completed line.
  rt_ram_banked #(.Words(Lines), .Width(LineBits), .BankWords(BankWords)) u_data (
    .clk_i, .we_i(deliver), .waddr_i(done_line), .wdata_i(done_data),
    .re_i(accept && lookup_hit), .raddr_i(hit_line), .rdata_o(hit_data)
  );

  // The merged requests: one memory of a word per target slot, register m's
  // slot k at m * Targets + k, read at the next cycle's completed register
  // and the slot it answers then.
  localparam int unsigned TgtWords = Mshrs * Targets;
  localparam int unsigned TgtIdxW = (TgtWords > 1) ? $clog2(TgtWords) : 1;
  logic [TgtW-1:0]     out_next_at_done;
  logic [TgtIdxW-1:0]  tgt_waddr, tgt_raddr;
  logic                tgt_fwd_q;
  logic [TagWidth-1:0] tgt_rdata, tgt_fwd_data_q;
  // The slot each candidate register answers next: its count of answers,
  // one more if it is the one answered now and stays (the register freed
  // now is never the next one). The request written now goes to the next
  // answer's slot only when it joins the next completed register (a
  // register taken now is not completed next): the test is made for both
  // candidates and chosen by `freeing`, as the register itself is. A
  // register that joins is never the completed one (`joinable`), so the
  // answer's increment does not enter the join's test.
  logic [TgtW-1:0] keep_out, out_keep, out_free;
  logic            keep_is_done, fwd_keep, fwd_free;
  assign keep_is_done = done_keep_idx == done_idx;
  assign keep_out = mshr_out_q[done_keep_idx];
  assign out_keep = (deliver && keep_is_done) ? done_out + 1'b1 : keep_out;
  assign out_free = mshr_out_q[done_free_idx];
  assign out_next_at_done = freeing ? out_free : out_keep;
  assign fwd_keep = m_join_idx == done_keep_idx && m_join_cnt == keep_out;
  assign fwd_free = m_join_idx == done_free_idx && m_join_cnt == out_free;
  assign tgt_waddr = TgtIdxW'(32'(tgt_wr_mshr) * Targets + 32'(tgt_wr_slot));
  assign tgt_raddr = TgtIdxW'(32'(done_idx_next) * Targets + 32'(out_next_at_done));
  rt_ram_banked #(.Words(TgtWords), .Width(TagWidth), .BankWords(BankWords)) u_tgt_ram (
    .clk_i, .we_i(m_take), .waddr_i(tgt_waddr), .wdata_i(m_tag), .re_i(1'b1), .raddr_i(tgt_raddr),
    .rdata_o(tgt_rdata)
  );
  always_ff @(posedge clk_i) begin
    tgt_fwd_q <= m_take && m_join && (freeing ? fwd_free : fwd_keep);
    tgt_fwd_data_q <= m_tag;
  end
`ifndef SYNTHESIS
  // What the restructured paths rely on: a register taken now is not the
  // next completed one, no beat answers a free register, a join never
  // targets the completed register, and the forward agrees with the
  // addresses whenever a register is completed next (else nothing reads
  // them).
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      assert (!(m_take && !m_join && free_idx == done_idx_next && done_stay[free_idx]))
        else $error("rt_cache: a register taken now is the next completed one");
      assert (!(mem_resp_valid_i && !mshr_valid_q[resp_mshr]))
        else $error("rt_cache: a memory beat for a free miss register");
      assert (!(m_take && m_join && done_valid && m_join_idx == done_idx))
        else $error("rt_cache: a request joins the completed register");
      assert (!(|(done_stay & ~(freeing ? done_oh_q : '0))) ||
              (m_take && m_join && (freeing ? fwd_free : fwd_keep)) == (m_take && tgt_waddr == tgt_raddr))
        else $error("rt_cache: the merged requests' forward disagrees with the addresses");
    end
  end
`endif
  assign done_tag = tgt_fwd_q ? tgt_fwd_data_q : tgt_rdata;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      done_idx_q <= '0;
      done_oh_q <= Mshrs'(1);
    end else begin
      done_idx_q <= done_idx_next;
      done_oh_q <= Mshrs'(1) << done_idx_next;
    end
  end
`ifndef SYNTHESIS
  // The memories were read at the completed register: the lowest of `done`.
  always_ff @(posedge clk_i) begin
    if (rst_ni && done_valid) begin
      assert (done[done_idx] && (done & ((Mshrs'(1) << done_idx) - 1'b1)) == '0)
        else $error("rt_cache: the memories were read at another register");
    end
  end
`endif
  assign done_cnt = mshr_cnt_q[done_idx];
  assign done_out = mshr_out_q[done_idx];
  assign done_last = done_out + 1'b1 == done_cnt;

  // Sets is a power of two: a key's set is its low bits. Line set * Ways + w
  // is way w of the set.
  logic [SetW-1:0]  req_set, req2_set, done_set;
  logic [Ways-1:0]  hit_ways, hit2_ways, done_ways, free_ways, points;
  logic [WayW-1:0]  hit_way, fill_way, free_way, victim;
  assign req_set = req_key_i[SetW-1:0] & SetW'(Sets - 1);
  assign req2_set = req2_key_i[SetW-1:0] & SetW'(Sets - 1);
  assign done_set = done_key[SetW-1:0] & SetW'(Sets - 1);
  for (genvar w = 0; w < Ways; w++) begin : g_way
    logic [IdxW-1:0] l1, l2, ld;
    assign l1 = IdxW'(32'(req_set) * Ways + w);
    assign l2 = IdxW'(32'(req2_set) * Ways + w);
    assign ld = IdxW'(32'(done_set) * Ways + w);
    assign hit_ways[w] = valid_q[l1] && key_q[l1] == line_tag(req_key_i);
    assign hit2_ways[w] = valid_q[l2] && key_q[l2] == line_tag(req2_key_i);
    assign done_ways[w] = valid_q[ld] && key_q[ld] == line_tag(done_key);
    assign free_ways[w] = !valid_q[ld];
  end
  // The lowest way of each kind; exactly one way is the one the tree points
  // at (`points` is one-hot).
  logic hit_any, done_any, free_any, unused_points_any;
  logic [WayW-1:0] done_way;
  rt_prio_enc #(.N(Ways)) u_hit_way_enc (.req_i(hit_ways), .valid_o(hit_any), .idx_o(hit_way));
  rt_prio_enc #(.N(Ways)) u_done_way_enc (.req_i(done_ways), .valid_o(done_any), .idx_o(done_way));
  rt_prio_enc #(.N(Ways)) u_free_way_enc (.req_i(free_ways), .valid_o(free_any), .idx_o(free_way));
  rt_prio_enc #(.N(Ways)) u_victim_enc (.req_i(points), .valid_o(unused_points_any), .idx_o(victim));
  assign fill_way = done_any ? done_way : free_any ? free_way : victim;
  assign hit_line = IdxW'(32'(req_set) * Ways + 32'(hit_way));
  assign done_line = IdxW'(32'(done_set) * Ways + 32'(fill_way));
  assign lookup_hit = hit_any;
  assign lookup2_hit = |hit2_ways;

  // The pseudo-LRU tree of each set, one word per set: read at the
  // request's and the completed miss's sets and written there (a hit taken,
  // then a fill, which sees the hit's bits when both are in one set). Node n
  // at level l of way w's path is w >> (WayW - l); the way the bits point at
  // is the one whose every path node agrees with its bit of the way number.
  // (Per-set words, not one vector with per-bit logic for every set: the
  // simulation then updates two words a cycle, not every set's bits.)
  if (Ways > 1) begin : g_plru
    logic [PlruW-1:0] plru_q [Sets];
    logic [PlruW-1:0] hit_plru, hit_new, fill_base, fill_new, done_plru;
    logic             hit_taken;
    assign hit_taken = accept && lookup_hit;
    assign hit_plru = plru_q[req_set];
    assign done_plru = plru_q[done_set];
    assign fill_base = (hit_taken && req_set == done_set) ? hit_new : done_plru;
    for (genvar w = 0; w < Ways; w++) begin : g_points
      logic [WayW-1:0] agree;
      for (genvar l = 0; l < WayW; l++) begin : g_level
        assign agree[l] = done_plru[(1 << l) - 1 + (w >> (WayW - l))] == 1'((w >> (WayW - 1 - l)) & 1);
      end
      assign points[w] = &agree;
    end
    for (genvar l = 0; l < WayW; l++) begin : g_level
      for (genvar n = 0; n < (1 << l); n++) begin : g_node
        localparam int unsigned Bit = (1 << l) - 1 + n;
        assign hit_new[Bit] = (32'(hit_way) >> (WayW - l)) == n ? !hit_way[WayW - 1 - l] : hit_plru[Bit];
        assign fill_new[Bit] = (32'(fill_way) >> (WayW - l)) == n ? !fill_way[WayW - 1 - l] : fill_base[Bit];
      end
    end
    // No reset, like the lines and keys: a set's bits choose a victim only
    // once every way of the set is valid, and by then each way's fill has
    // written every node on its path, so no bit of the reset state is left.
    // (A reset loop over Sets also stopped Verilator, which does not unroll
    // a delayed array assignment past 64 iterations by default.)
    always_ff @(posedge clk_i) begin
      if (hit_taken) plru_q[req_set] <= hit_new;
      if (deliver) plru_q[done_set] <= fill_new;
    end
  end else begin : g_direct
    assign points = 1'b1;
  end
  assign out_take = resp_valid_o && resp_ready_i;
  assign hit_free = !hit_valid_q || (out_take && !del_valid_q);
  assign del_free = !del_valid_q || out_take;
  // A completed miss is answered when its register is free, but never takes
  // the port from a hit that is shown and not yet taken (the stream's payload
  // stays until ready). Misses need neither register.
  assign deliver = done_valid && del_free && !(hit_valid_q && !del_valid_q && !resp_ready_i);
  assign hit_ok = lookup_hit && hit_free;
  assign join_ok = !lookup_hit && join_valid;
  assign alloc_ok = !lookup_hit && !(|key_match) && free_valid;
  assign req_ready_o = hit_ok || join_ok || alloc_ok;
  assign accept = req_valid_i && req_ready_o;
  // The miss-only port: a miss, in a cycle in which the first port takes none.
  assign join2_ok = !lookup2_hit && join2_valid;
  assign alloc2_ok = !lookup2_hit && !(|key_match2) && free_valid;
  // The prefetch port: present or in flight, dropped; else a free register.
  if (PrefetchPort && !MissPort) begin : g_prefetch_port
    assign req2_ready_o = lookup2_hit || (|key_match2) || (alloc2_ok && !(accept && !lookup_hit));
    assign m_port2 = accept2 && alloc2_ok;
    assign m_count0 = m_port2;
  end else begin : g_miss_port
    assign req2_ready_o = MissPort && !(accept && !lookup_hit) && (join2_ok || alloc2_ok);
    assign m_port2 = accept2;
    assign m_count0 = 1'b0;
  end
  assign accept2 = req2_valid_i && req2_ready_o;

  assign m_take = (accept && !lookup_hit) || m_port2;
  assign m_join = m_port2 ? join2_ok : join_ok;
  assign m_join_idx = m_port2 ? join2_idx : join_idx;
  assign m_join_cnt = mshr_cnt_q[m_join_idx];
  assign m_key = m_port2 ? req2_key_i : req_key_i;
  assign m_addr = m_port2 ? req2_addr_i : req_addr_i;
  assign m_tag = m_port2 ? req2_tag_i : req_tag_i;

  assign filling_o = |mshr_valid_q;
  assign hit_o = accept && lookup_hit;
  assign miss_o = m_take && !m_count0;
  assign prefetch_o = m_count0;
  assign merge_o = m_take && m_join;
  assign wait_inflight_o = req_valid_i && !lookup_hit && (|key_match) && !join_valid;
  assign wait_mshr_o = req_valid_i && !lookup_hit && !(|key_match) && !free_valid;

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
  assign send_beat = mshr_sent_q[send_idx];
  assign mem_req_valid_o = send_valid;
  // The line's address: from the key, or kept per miss register.
  logic [AddrWidth-1:0] send_line_addr;
  if (KeyIsLine) begin : g_key_addr
    assign send_line_addr = AddrWidth'(mshr_key_q[send_idx]) * AddrWidth'(LineBeats * 16);
    /* verilator lint_off UNUSEDSIGNAL */
    logic unused_addr;
    assign unused_addr = ^{m_addr};
    /* verilator lint_on UNUSEDSIGNAL */
  end else begin : g_mshr_addr
    logic [AddrWidth-1:0] mshr_addr_q [Mshrs];
    always_ff @(posedge clk_i) begin
      if (m_take && !m_join) mshr_addr_q[free_idx] <= m_addr;
    end
    assign send_line_addr = mshr_addr_q[send_idx];
  end
  assign mem_req_addr_o = send_line_addr + AddrWidth'(send_beat) * AddrWidth'(16);
  assign mem_req_id_o = {send_idx, send_beat[BeatW-1:0]};

  // The response registers' next state, as the updates below give it.
  logic del_valid_next;
  assign del_valid_next = (deliver && done_cnt != '0) || (del_valid_q && !out_take);
  assign resp_tag_next_o = del_valid_next ? (deliver ? done_tag : del_tag_q)
                                          : ((accept && lookup_hit) ? req_tag_i : hit_tag_q);

  assign resp_valid_o = hit_valid_q || del_valid_q;
  assign resp_data_o = del_valid_q ? del_data_q : hit_data;
  assign resp_tag_o = del_valid_q ? del_tag_q : hit_tag_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= '0;
      mshr_valid_q <= '0;
      mshr_got_q <= '0;
      hit_valid_q <= 1'b0;
      del_valid_q <= 1'b0;
    end else begin
      if (out_take && del_valid_q) del_valid_q <= 1'b0;
      if (out_take && !del_valid_q) hit_valid_q <= 1'b0;
      if (accept && lookup_hit) hit_valid_q <= 1'b1;
      // Taken, freed (a prefetch nobody joined, count 0, with its line
      // alone), beats received: the next state the completed register is
      // encoded from.
      mshr_valid_q <= valid_next;
      mshr_got_q <= got_next;
      if (deliver) begin
        valid_q[done_line] <= 1'b1;
        if (done_cnt != '0) del_valid_q <= 1'b1;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (accept && lookup_hit) hit_tag_q <= req_tag_i;
    if (m_take) begin
      if (m_join) begin
        mshr_cnt_q[m_join_idx] <= m_join_cnt + 1'b1;
        mshr_full_q[m_join_idx] <= 32'(m_join_cnt) + 1 >= Targets;
      end else begin
        mshr_key_q[free_idx] <= m_key;
        mshr_sent_q[free_idx] <= '0;
        mshr_unsent_q[free_idx] <= 1'b1;
        mshr_cnt_q[free_idx] <= m_count0 ? '0 : TgtW'(1);
        mshr_full_q[free_idx] <= !m_count0 && Targets == 1;
        mshr_out_q[free_idx] <= '0;
      end
    end
    if (mem_req_valid_o && mem_req_ready_i) begin
      mshr_sent_q[send_idx] <= send_beat + 1'b1;
      mshr_unsent_q[send_idx] <= 32'(send_beat) + 1 < LineBeats;
    end
    if (deliver) begin
      mshr_out_q[done_idx] <= done_out + 1'b1;
      key_q[done_line] <= line_tag(done_key);
      del_data_q <= done_data;
      del_tag_q <= done_tag;
    end
  end

endmodule

`default_nettype wire
