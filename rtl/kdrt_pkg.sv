// Constants of the kdrt memory image, version 5: a mirror of
// sw/common/image_format.h (the C++ header is the source of truth, and
// docs/memory-image.md its prose). Every value is little-endian in memory;
// offsets are in bytes. Also the types shared by the core's units: the
// traversal action and the performance event struct.
`default_nettype none

package kdrt_pkg;

  // A unit uses only some of these.
  /* verilator lint_off UNUSEDPARAM */

  localparam int unsigned ImgVersion      = 4;
  localparam int unsigned HeaderBytes     = 128;
  localparam int unsigned SectionAlign    = 64;
  localparam int unsigned NodeBytes       = 8;
  localparam int unsigned ListEntryBytes  = 4;
  localparam int unsigned TriangleBytes   = 48;

  // "KDRTIMG\0" as the two little-endian words at offsets 0 and 4.
  localparam logic [31:0] MagicWord0 = 32'h5452_444B;  // 'K' 'D' 'R' 'T'
  localparam logic [31:0] MagicWord1 = 32'h0047_4D49;  // 'I' 'M' 'G' '\0'

  // Header field offsets (img::Header).
  localparam int unsigned HdrMagic        = 0;
  localparam int unsigned HdrVersion      = 8;
  localparam int unsigned HdrTotalBytes   = 12;
  localparam int unsigned HdrNodeOffset   = 16;
  localparam int unsigned HdrNodeCount    = 20;
  localparam int unsigned HdrListOffset   = 24;
  localparam int unsigned HdrListCount    = 28;
  localparam int unsigned HdrTriOffset    = 32;
  localparam int unsigned HdrTriCount     = 36;
  localparam int unsigned HdrMaxDepth     = 40;
  localparam int unsigned HdrMaxLeafPrims = 44;
  localparam int unsigned HdrBoundsMin    = 48;  // 3 x fp32: x, y, z
  localparam int unsigned HdrBoundsMax    = 60;
  localparam int unsigned HdrFrameOrigin  = 72;  // 3 x fp32 (sw/trace/frame.h)
  localparam int unsigned HdrFrameScale   = 84;  // int32: log2 of the frame's scale
  localparam int unsigned HdrFormatE      = 88;  // the image's number format: a core
  localparam int unsigned HdrFormatM      = 92;  //   reads the image of its own (E, M)
  localparam int unsigned HdrReserved     = 96;  // 8 zero words

  // The frame's scale s (HdrFrameScale) as the core takes it: signed, and a
  // valid image has |s| <= 160 (kMaxFrameScaleLog2, sw/trace/frame.h), so 9
  // bits hold it. A ray's distance scale k = m - s (docs/dataflow.md, step 0)
  // has m = 127 - (a biased exponent) in [-128, 127], so |k| <= 128 + 256 =
  // 384 for any 9-bit s: 10 bits hold it (and -k).
  localparam int unsigned FrameScaleWidth = 9;
  localparam int unsigned TScaleWidth     = 10;

  // The layout of an image in a W-bit format (img::ImageLayout in
  // sw/common/image_format.h; docs/memory-image.md, "Packed formats"): nodes
  // per 16-byte beat, bits per node, index bits naming the slot in a beat,
  // bits of a leaf's first list entry, triangle records per triangle line
  // (1, or 2 at 15 <= W <= 21), beats per line, and the bits of a record's
  // slot in its line. For W = 32 they give the fp32 records below.
  function automatic int unsigned img_nodes_per_beat(input int unsigned w);
    if (w <= 16) img_nodes_per_beat = 3;
    else img_nodes_per_beat = 2;
  endfunction
  function automatic int unsigned img_node_bits(input int unsigned w);
    if (w <= 16) img_node_bits = 42;
    else img_node_bits = 64;
  endfunction
  function automatic int unsigned img_slot_bits(input int unsigned w);
    if (w <= 16) img_slot_bits = 2;
    else img_slot_bits = 1;
  endfunction
  function automatic int unsigned img_first_bits(input int unsigned w);
    if (w <= 16) img_first_bits = 24;
    else img_first_bits = 32;
  endfunction
  function automatic int unsigned img_tris_per_line(input int unsigned w);
    if (9 * w > 128 && 9 * w <= 192) img_tris_per_line = 2;
    else img_tris_per_line = 1;
  endfunction
  function automatic int unsigned img_tri_line_beats(input int unsigned w);
    if (img_tris_per_line(w) == 2) img_tri_line_beats = 3;
    else img_tri_line_beats = (9 * w + 127) / 128;
  endfunction
  function automatic int unsigned img_tri_slot_bits(input int unsigned w);
    if (img_tris_per_line(w) == 2) img_tri_slot_bits = 192;
    else img_tri_slot_bits = 128 * img_tri_line_beats(w);
  endfunction
  // Bits of a count of list entries in a list line of `line_bytes` (0 ..
  // line_bytes / ListEntryBytes): a streaming list request's (rt_list_unit,
  // rt_mem_system with ListStream).
  function automatic int unsigned list_count_bits(input int unsigned line_bytes);
    list_count_bits = $clog2(line_bytes / ListEntryBytes + 1);
  endfunction

  // Node word 1, bits [1:0]: split axis 0/1/2 or NodeLeaf; bits [31:2]: the
  // triangle count (leaf), or (inner node) bits [29:2] the above child's
  // index and bits 30, 31 the marks of an empty below and above child.
  // Inner node word 0: split position (fp32); leaf word 0: first list entry.
  localparam logic [1:0] NodeLeaf = 2'd3;

  // Triangle record (img::TriangleRecord): v0, v1, v2 as 3 x fp32 each
  // (x, y, z), then the triangle id and two padding words.
  localparam int unsigned TriV0  = 0;
  localparam int unsigned TriV1  = 12;
  localparam int unsigned TriV2  = 24;
  localparam int unsigned TriId  = 36;
  // The vertex words the intersection unit reads: bytes [0, 36) of a record.
  localparam int unsigned TriVertexBits = 288;

  // The traversal step's decision (sw/trace/traversal.h TraversalAction):
  // go to the first (near) child only, the second (far) child only, or push
  // the far child and go to the near one.
  typedef enum logic [1:0] {
    TravFirst  = 2'd0,
    TravSecond = 2'd1,
    TravPush   = 2'd2
  } trav_action_e;

  // rt_core's perf_o: one bit per event in this cycle, MSB first (bit 32 ..
  // bit 0); the harness counts them (sim/sim_report.cpp). One field per line,
  // each with a comment saying what it counts: cmake/perf_layout.cmake
  // generates the C++ view (<build>/generated/sim/perf_layout.h) from this
  // text, so names and bit positions are defined here only.
  typedef struct packed {
    logic list_prefetch;       // a list line prefetch took a miss register (the line fetched ahead of its job)
    logic busy;                // rays in flight (some thread is not free)
    logic node_wait;           // a thread's node fetch waits: the node cache does not take it
    logic list_wait;           // a list entry request waits: the list cache does not take it
    logic tri_wait;            // a list entry waits: the triangle cache does not take it
    logic node_wait_inflight;  // a node fetch misses on a line being fetched and cannot join it
    logic list_wait_inflight;  // a list entry misses on a line being fetched and cannot join it
    logic tri_wait_inflight;   // a triangle misses on a line being fetched and cannot join it
    logic node_wait_mshr;      // a node fetch misses and no node cache miss register is free
    logic list_wait_mshr;      // a list entry misses and no list cache miss register is free
    logic tri_wait_mshr;       // a triangle misses and no triangle cache miss register is free
    logic node_merge;          // a node miss joined the fetch of its line (no second fetch)
    logic list_merge;          // a list miss joined the fetch of its line
    logic tri_merge;           // a triangle miss joined the fetch of its line
    logic trav_stall;          // a node response waits for the traversal unit
    logic isect_stall;         // a triangle waits for the intersection unit
    logic hit_stall;           // a hit record waits on hit_ready_i
    logic trav_leaf;           // a node response was a leaf
    logic overflow;            // a traversal stack overflowed (the ray's record is invalid)
    logic ray_out;             // a hit record was delivered (hit_valid_o and hit_ready_i)
    logic ray_in;              // a ray was accepted (ray_valid_i and ray_ready_o)
    logic stall_backpressure;  // a hit waits on hit_ready_i, or the traversal or intersection unit stalls its input
    logic stall_stack;         // a thread waits for the leaf-exit (stack) port
    logic stall_mem;           // rays in flight, no unit made progress, and a cache waits for memory
    logic tri_miss;            // a triangle cache miss
    logic tri_hit;             // a triangle cache hit
    logic list_miss;           // a list cache miss
    logic list_hit;            // a list cache hit
    logic node_miss;           // a node cache miss
    logic node_hit;            // a node cache hit
    logic isect_busy;          // the intersection unit took a test
    logic list_busy;           // the list unit issued a list entry or triangle fetch
    logic trav_busy;           // the traversal unit took a node
  } perf_t;

  /* verilator lint_on UNUSEDPARAM */

endpackage

`default_nettype wire
