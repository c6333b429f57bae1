// rt_list_unit: the leaf-list walker of rt_core.
//
// A leaf job (thread tag, first list entry, entry count > 0) waits in a FIFO
// of Jobs entries; the walker takes the oldest job when it is idle and then
// issues one list-cache request per cycle with the byte address of the next
// entry (list_base_i + ListEntryBytes * entry), the job's tag and a count,
// until all of the job's entries are requested. With ListStream 0 a request
// is one entry (count 1); with ListStream 1 it is every entry of the job
// left in the entry's list line of LineBytes (1 .. LineBytes /
// ListEntryBytes), which rt_mem_system then hands on one a cycle (list_base_i
// must then be a multiple of ListEntryBytes, as the image's list section
// is, so that no entry straddles two lines). Both streams are valid/ready
// with picorv32's rule.
//
// With ListPrefetch = N > 0 a prefetcher walks the jobs waiting in the FIFO
// (not the one being requested), oldest first and at most N of them: one
// line a cycle (pf_addr_o, the line's first byte) of the job it is at, from
// its first entry's line to its last's. A job the walker takes before the
// prefetcher is done with it is left (the prefetcher restarts at the new
// oldest job). rt_mem_system sends these to the list cache's prefetch port
// (rt_cache PrefetchPort), so a job's lines are fetched while the jobs
// before it are requested.
//
// The queue (rt_fifo in a memory, Ram = 1) and the prefetcher's copy of the
// jobs (rt_ram_1r1w) are memories with an SRAM's ports, and no arithmetic
// follows their reads. The queue holds a job's first entry's byte address
// (list_base_i + ListEntryBytes * first, made as the job is pushed:
// list_base_i is stable while busy) and its count; the prefetcher's copy its
// first entry's line and the job's entries after that line, read a cycle
// ahead for the job after the prefetcher's (forwarding a job pushed in the
// cycle it is read), and the prefetcher's own job is in registers.
// With ListPrefetch, as with ListStream, list_base_i must be a multiple of
// ListEntryBytes (checked in simulation).
`default_nettype none

module rt_list_unit #(
  parameter int unsigned TagWidth = 5,
  parameter int unsigned Jobs = 32,
  parameter int unsigned CountWidth = 25,
  parameter int unsigned AddrWidth = 28,
  parameter int unsigned ListStream = 1,
  parameter int unsigned LineBytes = 32,
  parameter int unsigned ListPrefetch = 0,  // jobs the prefetcher looks ahead (0: none)
  localparam int unsigned ReqCountW = kdrt_pkg::list_count_bits(LineBytes)
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  input  logic [AddrWidth-1:0]  list_base_i,  // stable while busy
  // leaf jobs
  input  logic                  job_valid_i,
  output logic                  job_ready_o,
  input  logic [TagWidth-1:0]   job_tag_i,
  input  logic [31:0]           job_first_i,  // index of the first list entry
  input  logic [CountWidth-1:0] job_count_i,  // entries, at least 1
  // list entry requests
  output logic                  req_valid_o,
  input  logic                  req_ready_i,
  output logic [TagWidth-1:0]   req_tag_o,
  output logic [AddrWidth-1:0]  req_addr_o,
  output logic [ReqCountW-1:0]  req_count_o,  // entries from req_addr_o on (1 without ListStream)
  // list line prefetches (ListPrefetch > 0; else never valid)
  output logic                  pf_valid_o,
  input  logic                  pf_ready_i,
  output logic [AddrWidth-1:0]  pf_addr_o
);

  localparam int unsigned EntryShift = $clog2(kdrt_pkg::ListEntryBytes);
  localparam int unsigned LineOffW = $clog2(LineBytes);

  // ------------------------------------------------------------ job queue
  // A job is queued with its first entry's address (list_base_i is stable
  // while busy), so a job read from the queue needs no addition.
  logic                  queued_valid, queued_pop;
  logic [TagWidth-1:0]   queued_tag;
  logic [AddrWidth-1:0]  queued_addr, job_addr;
  logic [CountWidth-1:0] queued_count;
  assign job_addr = list_base_i + (AddrWidth'(job_first_i) << EntryShift);
  rt_fifo #(.Width(TagWidth + AddrWidth + CountWidth), .Depth(Jobs), .Ram(1)) u_jobs (
    .clk_i, .rst_ni,
    .in_valid_i (job_valid_i),
    .in_ready_o (job_ready_o),
    .in_data_i  ({job_tag_i, job_addr, job_count_i}),
    .out_valid_o(queued_valid),
    .out_ready_i(!req_valid_o),
    .out_data_o ({queued_tag, queued_addr, queued_count})
  );
  assign queued_pop = queued_valid && !req_valid_o;

  // ------------------------------------------------------------ walker
  logic [CountWidth-1:0] left_q;  // entries still to request
  logic                  req_fire;
  assign req_fire = req_valid_o && req_ready_i;

  // The entries this request covers: one, or (ListStream) those left of the
  // job in the entry's line.
  if (ListStream != 0) begin : g_stream
    logic [LineOffW-EntryShift:0] in_line;  // entries from the address to the line's end
    assign in_line = (LineOffW - EntryShift + 1)'((LineBytes - 32'(req_addr_o[LineOffW-1:0])) >> EntryShift);
    assign req_count_o = left_q < CountWidth'(in_line) ? ReqCountW'(left_q) : ReqCountW'(in_line);
  end else begin : g_single
    assign req_count_o = ReqCountW'(1);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      req_valid_o <= 1'b0;
    end else if (queued_pop) begin
      req_valid_o <= 1'b1;
    end else if (req_fire && left_q == CountWidth'(req_count_o)) begin
      req_valid_o <= 1'b0;
    end
  end

  always_ff @(posedge clk_i) begin
    if (queued_pop) begin
      req_tag_o <= queued_tag;
      req_addr_o <= queued_addr;
      left_q <= queued_count;
    end else if (req_fire) begin
      req_addr_o <= req_addr_o + (AddrWidth'(req_count_o) << EntryShift);
      left_q <= left_q - CountWidth'(req_count_o);
    end
  end

  // ------------------------------------------------------------ prefetcher
  if (ListPrefetch > 0) begin : g_prefetch
    // The FIFO's jobs again, at the FIFO's own positions (rt_fifo pushes and
    // pops in order: its write and read positions are counted here too),
    // each as the prefetcher walks it: its first entry's line and the
    // entries after that line (made as the job is pushed), so that nothing
    // but a choice follows the memory's read.
    localparam int unsigned JobW = (Jobs > 1) ? $clog2(Jobs) : 1;
    localparam int unsigned NumW = $clog2(Jobs + 1);
    localparam int unsigned LineW = AddrWidth - LineOffW;
    localparam int unsigned MaxInLine = LineBytes >> EntryShift;
    logic [LineOffW-EntryShift:0] push_in_line;  // the job's entries its first line can hold
    logic [LineW-1:0]      push_line;
    logic [CountWidth-1:0] push_rest;
    assign push_in_line =
        (LineOffW - EntryShift + 1)'((LineBytes - 32'(job_addr[LineOffW-1:0])) >> EntryShift);
    assign push_line = job_addr[AddrWidth-1:LineOffW];
    assign push_rest = job_count_i > CountWidth'(push_in_line) ? job_count_i - CountWidth'(push_in_line) : '0;

    logic [JobW-1:0]       wr_q, rd_q, rd_d;
    logic [NumW-1:0]       queued_q;  // jobs in the FIFO
    logic [NumW-1:0]       pf_off_q, pf_off_d, pf_off_base;  // the prefetcher's job: rd_q + pf_off_q
    logic [LineW-1:0]      line_q;    // the line it asks for
    logic [CountWidth-1:0] rest_q;    // its job's entries after that line
    logic [LineW-1:0]      next_line; // the job after it: read a cycle ahead
    logic [CountWidth-1:0] next_rest;
    logic                  push, pf_fire, pf_job_done, pf_keep, pf_adv, pf_move, pf_step, load_push;
    logic [JobW-1:0]       pf_idx_stay, pf_idx_adv, pf_idx_after;
    function automatic logic [JobW-1:0] wrap_inc(input logic [JobW-1:0] p);
      wrap_inc = (32'(p) == Jobs - 1) ? '0 : p + 1'b1;
    endfunction
    assign push = job_valid_i && job_ready_o;
    assign pf_valid_o = pf_off_q < queued_q && 32'(pf_off_q) < ListPrefetch;
    assign pf_addr_o = {line_q, {LineOffW{1'b0}}};
    assign pf_fire = pf_valid_o && pf_ready_i;
    assign pf_job_done = rest_q == '0;
    // The walker taking the prefetcher's job moves it on to the next oldest,
    // as does the prefetcher's own last line of a job.
    assign rd_d = queued_pop ? wrap_inc(rd_q) : rd_q;
    assign pf_keep = queued_pop && pf_off_q == '0;
    assign pf_off_base = pf_keep ? pf_off_q : pf_off_q - NumW'(queued_pop);
    assign pf_adv = !pf_keep && pf_fire && pf_job_done;
    assign pf_off_d = pf_off_base + NumW'(pf_adv);
    assign pf_move = pf_keep || pf_adv;
    assign pf_step = !pf_move && pf_fire;
    // The next cycle's job and the one after it, for both outcomes of pf_adv.
    assign pf_idx_stay = JobW'((32'(rd_d) + 32'(pf_off_base)) % Jobs);
    assign pf_idx_adv = wrap_inc(pf_idx_stay);
    assign pf_idx_after = wrap_inc(pf_idx_adv);
    // The job pushed in this cycle is the prefetcher's next one when the
    // prefetcher is past the last queued job.
    assign load_push = push && (pf_adv ? wr_q == pf_idx_adv : wr_q == pf_idx_stay);
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        wr_q <= '0;
        rd_q <= '0;
        queued_q <= '0;
        pf_off_q <= '0;
      end else begin
        if (push) wr_q <= wrap_inc(wr_q);
        if (queued_pop) rd_q <= wrap_inc(rd_q);
        queued_q <= queued_q + NumW'(push) - NumW'(queued_pop);
        pf_off_q <= pf_off_d;
      end
    end
    always_ff @(posedge clk_i) begin
      if (load_push) begin
        line_q <= push_line;
        rest_q <= push_rest;
      end else if (pf_move) begin
        line_q <= next_line;
        rest_q <= next_rest;
      end else if (pf_step) begin
        line_q <= line_q + 1'b1;
        rest_q <= rest_q > CountWidth'(MaxInLine) ? rest_q - CountWidth'(MaxInLine) : '0;
      end
    end
    // The job after the next cycle's, read a cycle ahead; a job pushed to
    // that position in this cycle is forwarded.
    logic                       pf_fwd_q;
    logic [LineW+CountWidth-1:0] pf_fwd_data_q, pf_rdata;
    rt_ram_1r1w #(.Words(Jobs), .Width(LineW + CountWidth)) u_pf_jobs (
      .clk_i, .we_i(push), .waddr_i(wr_q), .wdata_i({push_line, push_rest}),
      .re_i(1'b1), .raddr_i(pf_adv ? pf_idx_after : pf_idx_adv), .rdata_o(pf_rdata)
    );
    always_ff @(posedge clk_i) begin
      pf_fwd_q <= push && (pf_adv ? wr_q == pf_idx_after : wr_q == pf_idx_adv);
      if (push) pf_fwd_data_q <= {push_line, push_rest};
    end
    assign {next_line, next_rest} = pf_fwd_q ? pf_fwd_data_q : pf_rdata;
  end else begin : g_no_prefetch
    assign pf_valid_o = 1'b0;
    assign pf_addr_o = '0;
    /* verilator lint_off UNUSEDSIGNAL */
    logic unused_pf;
    assign unused_pf = pf_ready_i;
    /* verilator lint_on UNUSEDSIGNAL */
  end

`ifndef SYNTHESIS
  always_ff @(posedge clk_i) begin
    if (rst_ni && job_valid_i && (ListStream != 0 || ListPrefetch > 0)) begin
      assert (list_base_i[EntryShift-1:0] == '0)
      else $error("rt_list_unit: list_base_i 0x%0h is not a multiple of the list entry's bytes", list_base_i);
    end
  end
`endif

  rt_stream_check #(.Width(TagWidth + 32 + CountWidth), .Name("rt_list_unit job")) u_job_check (
    .clk_i, .rst_ni, .valid_i(job_valid_i), .ready_i(job_ready_o),
    .payload_i({job_tag_i, job_first_i, job_count_i})
  );
  rt_stream_check #(.Width(TagWidth + AddrWidth + ReqCountW), .Name("rt_list_unit request")) u_req_check (
    .clk_i, .rst_ni, .valid_i(req_valid_o), .ready_i(req_ready_i), .payload_i({req_tag_o, req_addr_o, req_count_o})
  );

endmodule

`default_nettype wire
