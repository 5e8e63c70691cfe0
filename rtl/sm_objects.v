`default_nettype none
`include "sm_defs.vh"
// Object separation (docs/algorithm.md, section 8): one-pass streaming labelling of the
// near pixels of the disparity stream with a flat equivalence table, per-label
// statistics, and at the end of each frame a scan that lists up to MAX_OBJECTS objects.
//
// Stream side (advances on ce): stage 1 registers the entering beat, reads the row
// buffer (labels of the row above) and compares the pixel with its left neighbour and
// the threshold; stage 1b registers all of that once more, so the row buffer's block
// RAM (5.8 ns from the clock to its data on ECP5) does not start the labelling path
// (placed and routed, it set the block's clock: docs/synthesis.md); stage 2 labels the
// pixel and merges in the equivalence table; stage 3
// updates the statistics on the clk right after stage 2's ce (not on the next ce), so
// the read-modify-write of a run of one label needs no forwarding and the frame's last
// update is done before the scan reads the bank. The statistics are double-banked by
// frame: the scan of frame f (on clk, not ce) reads one bank while frame f+1 is
// labelled into the other; it needs at most LABEL_SLOTS + MAX_OBJECTS * (DW + 1) + 2
// clocks, less than the 256 beats of the smallest frame (checked below).
module sm_objects #(
    parameter MAX_WIDTH   = 320,  // widest active line
    parameter MAX_HEIGHT  = 240,  // tallest active frame
    parameter DISP        = 128,  // disparity levels 0..DISP-1
    parameter MAX_OBJECTS = 8,    // objects listed per frame (K)
    parameter LABEL_SLOTS = 64    // labels per frame = entries of the equivalence table
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          out_rst_n,   // the packet stream's reset (the sink's: aresetn);
                                      // a soft reset lets a packet in progress finish
    input  wire          ce,
    input  wire [XW-1:0] width,       // active width
    input  wire [YW-1:0] height,      // its frame's height (latched at sof): the frame
                                      // ends at (W-1, H-1)
    input  wire [7:0]    near_thr,    // near: valid and d >= near_thr
    input  wire [7:0]    tol,         // neighbours merge when |d1 - d2| <= tol
    input  wire [15:0]   min_pixels,  // smaller components are not listed
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [15:0]   s_disp,      // bit 15 valid, low bits disparity
    // the list of the last complete frame (for the register file)
    output reg           list_ready,  // one clk when a new list is published
    output reg  [7:0]    obj_count,   // objects in the list
    output reg           too_many,    // more qualifying components than MAX_OBJECTS
    output reg           table_full,  // a component found no free label: its pixels dropped
    output reg           pkt_lost,    // a list was published while its predecessor's
                                      // packet was still being sent; cleared by the next
                                      // packet that starts
    input  wire [IW-1:0] rd_index,    // object to read (0..obj_count-1)
    output wire [15:0]   rd_x0,
    output wire [15:0]   rd_y0,
    output wire [15:0]   rd_x1,
    output wire [15:0]   rd_y1,
    output wire [31:0]   rd_count,
    output wire [31:0]   rd_sum,
    output wire [7:0]    rd_mean,
    output wire [7:0]    rd_max,
    // one AXI4-Stream packet per list: header + 5 words per object
    output wire [31:0]   m_axis_obj_tdata,
    output wire          m_axis_obj_tvalid,
    input  wire          m_axis_obj_tready,
    output wire          m_axis_obj_tlast
);
  localparam XW   = `SM_COUNT_W(MAX_WIDTH);
  localparam YW   = `SM_COUNT_W(MAX_HEIGHT);
  localparam DW   = $clog2(DISP);
  localparam LW   = (LABEL_SLOTS > 1) ? $clog2(LABEL_SLOTS) : 1;  // label
  localparam NW   = $clog2(LABEL_SLOTS + 1);                      // label counter
  localparam CNTW = $clog2(MAX_WIDTH * MAX_HEIGHT + 1);           // pixel count
  localparam SUMW = CNTW + DW;                                    // disparity sum
  localparam IW   = (MAX_OBJECTS > 1) ? $clog2(MAX_OBJECTS) : 1;  // object index
  localparam OW   = $clog2(MAX_OBJECTS + 1);                      // object counter
  localparam RBW  = 1 + DW + LW;                                  // row buffer word
  localparam ENW  = 2 * XW + 2 * YW + CNTW + SUMW + DW;           // list entry but its mean
  localparam SCAN_CLKS = LABEL_SLOTS + MAX_OBJECTS * (DW + 1) + 2;

  generate
    `SM_BAD_PARAM(g_bad_disp, DISP < `SM_DISP_MIN || DISP > `SM_DISP_MAX || DISP % 2 != 0,
                  ("sm_objects: DISP (%0d) must be even, %0d..%0d", DISP, `SM_DISP_MIN, `SM_DISP_MAX))
    `SM_BAD_PARAM(g_bad_k, MAX_OBJECTS < 1 || MAX_OBJECTS > 64 || LABEL_SLOTS < MAX_OBJECTS,
                  ("sm_objects: need 1 <= MAX_OBJECTS (%0d) <= 64 and <= LABEL_SLOTS (%0d)", MAX_OBJECTS, LABEL_SLOTS))
    // sm_lowest_set searches up to 512 labels; one label leaves nothing to merge
    `SM_BAD_PARAM(g_bad_slots, LABEL_SLOTS < 2 || LABEL_SLOTS > 512,
                  ("sm_objects: LABEL_SLOTS (%0d) must be 2..512", LABEL_SLOTS))
    `SM_BAD_PARAM(g_bad_scan, SCAN_CLKS > 256 || SUMW > 32 || MAX_WIDTH > 65535 || MAX_HEIGHT > 65535,
                  ("sm_objects: the end-of-frame scan (%0d clocks) must fit a 16x16 frame", SCAN_CLKS))
  endgenerate

  // ---- stage 1: entering beat, row buffer read ---------------------------------------
  wire [XW-1:0] s_x;
  wire [`SM_SIDE_W-1:0] c_side;
  wire [XW-1:0] c_x;
  wire [1:0]    row_ok;  // bit 0: the row above is in the frame
  wire [1:0]    col_ok;  // bit 0: the column left is in the frame
  sm_win_ctrl #(
      .MAX_WIDTH(MAX_WIDTH), .D_ROWS(0), .D_COLS(0), .R_UP(1), .R_DN(0), .R_L(1), .R_R(0)
  ) u_ctrl (
      .clk(clk), .rst_n(rst_n), .ce(ce), .width(width), .s_side(s_side),
      .s_x(s_x), .c_side(c_side), .c_x(c_x), .row_ok(row_ok), .col_ok(col_ok)
  );
  wire unused_ok = row_ok[1] & col_ok[1];
  // For a power-of-two MAX_WIDTH the row buffer's index needs one bit less than a column
  // count; that top bit is 0 for every column in the frame.
  wire unused_sx_top = s_x[XW-1];

  reg  [YW-1:0] y_q;  // row of the last entering real beat
  wire [YW-1:0] c_y = c_side[`SM_SIDE_SOF] ? {YW{1'b0}} : (c_side[`SM_SIDE_SOL] ? y_q + 1'b1 : y_q);
  // The frame's last row, latched at its sof; the sof beat itself is never the last
  // (H >= 16), so the compare needs no bypass of the latch.
  reg  [YW-1:0] hm1_q;
  wire          c_eof = c_side[`SM_SIDE_REAL] && !c_side[`SM_SIDE_SOF] && (c_x == width - 1'b1) && (c_y == hm1_q);

  // Row buffer: {near, d, label} of the row above, one word per column (block RAM).
  reg [RBW-1:0] rb [0:MAX_WIDTH-1];
  reg [RBW-1:0] rb_q;
  reg [XW-1:0]  x_q;
  reg [DW-1:0]  pix_q;      // d (its valid bit is in near_q)
  reg           up_in_q;    // row above is in the frame
  reg           left_in_q;  // column left is in the frame
  reg           eof_q;
  reg [`SM_SIDE_W-1:0] side_q;

  // per-frame parameters, taken with the frame's first pixel
  reg [7:0]     thr_q, tol_q;
  reg [15:0]    minpix_q;

  // Neighbour tests of the entering pixel, done here to keep them off stage 2's
  // labelling path: the parameters stage 2 would use (latched at this ce on sof), the
  // left neighbour is the pixel now in stage 2, and the pixel above must lie in
  // [d - tol, d + tol], which needs only the entering d.
  wire [DW-1:0] s_d = s_disp[DW-1:0];
  wire [7:0]    thr_e = c_side[`SM_SIDE_SOF] ? near_thr : thr_q;
  wire [7:0]    tol_e = c_side[`SM_SIDE_SOF] ? tol : tol_q;
  wire [8:0]    s_hi = {{(9-DW){1'b0}}, s_d} + {1'b0, tol_e};
  wire [8:0]    s_lo = {{(9-DW){1'b0}}, s_d} - {1'b0, tol_e};  // bit 8: below 0
  wire [8:0]    p_hi = {{(9-DW){1'b0}}, pix_q} + {1'b0, tol_e};
  wire [8:0]    p_lo = {{(9-DW){1'b0}}, pix_q} - {1'b0, tol_e};
  reg           near_q;                       // valid and d >= threshold
  reg           l_close_q;                    // |d - left d| <= tol
  reg  [8:0]    u_hi_q;                       // d + tol
  reg  [DW-1:0] u_lo_q;                       // max(d - tol, 0)

  // ---- stage 1b: stage 1's results, one ce later ------------------------------------
  // The left-neighbour test of stage 1 compares consecutive beats, so it holds here too.
  // min_pixels moves with the beats: stage 2 and the recycling read the value latched
  // by the beat after theirs, as they did when stage 2 followed stage 1 directly.
  reg [RBW-1:0] rb_s2;
  reg [XW-1:0]  x_s2;
  reg [YW-1:0]  y_s2;
  reg [DW-1:0]  pix_s2;
  reg           up_in_s2, left_in_s2, near_s2, l_close_s2;
  reg [8:0]     u_hi_s2;
  reg [DW-1:0]  u_lo_s2;
  reg [15:0]    minpix_s2;
  reg           eof_s2;
  reg [`SM_SIDE_W-1:0] side_s2;
  always @(posedge clk) begin
    if (ce) begin
      rb_s2      <= rb_q;
      x_s2       <= x_q;
      y_s2       <= y_q;
      pix_s2     <= pix_q;
      up_in_s2   <= up_in_q;
      left_in_s2 <= left_in_q;
      near_s2    <= near_q;
      l_close_s2 <= l_close_q;
      u_hi_s2    <= u_hi_q;
      u_lo_s2    <= u_lo_q;
      minpix_s2  <= minpix_q;
    end
  end

  // ---- stage 2: label -------------------------------------------------------------
  wire          real_q = side_s2[`SM_SIDE_REAL];
  wire          fresh = side_s2[`SM_SIDE_REAL] & side_s2[`SM_SIDE_SOF];  // first pixel: tables start empty
  wire          sol_q = side_s2[`SM_SIDE_SOL];
  reg           bank_q;
  reg  [NW-1:0] next_q;                         // labels 0..next_q-1 were allocated in this frame
  reg           tf_q;                           // table full seen in this frame
  reg           l_near_q;
  reg  [LW-1:0] l_lab_q;
  // Toggle coverage counts the logic, not the words a memory holds (the usual default of
  // simulators' toggle coverage for arrays); its address and data signals are counted.
  /* verilator coverage_off */
  reg  [LW-1:0] parent [0:LABEL_SLOTS-1];       // flat: every busy entry names its root
  /* verilator coverage_on */
  // Label recycling: a label is busy from its allocation until it is freed. Labels written
  // into the row buffer on this row (before the pixel now in stage 2, which is l_lab_q)
  // or on the row above may still be read by a pixel to come; any other busy label that
  // a merge absorbed, or that is the root of a component that has ended (no pixel on this
  // row or the row above) below min_pixels, is freed. big_q lags the statistics by two
  // clocks, and the last update of a label that is not referenced is over a row old.
  reg  [LABEL_SLOTS-1:0] busy_q, ucur_q, uprev_q, big_q;
  reg  [LW-1:0] cand_q;   // the label a new component gets: not busy
  reg           cok_q;    // ... exists

  wire          bank = fresh ? ~bank_q : bank_q;
  wire [NW-1:0] next_eff = fresh ? {NW{1'b0}} : next_q;
  wire [DW-1:0] d = pix_s2;
  wire          near = near_s2;
  wire          u_near = rb_s2[RBW-1];
  wire [DW-1:0] u_d = rb_s2[LW +: DW];
  wire [LW-1:0] u_lab = rb_s2[LW-1:0];
  wire          up_ok = near && up_in_s2 && u_near && (u_d >= u_lo_s2) &&
                        ({{(9-DW){1'b0}}, u_d} <= u_hi_s2);
  wire          left_ok = near && left_in_s2 && l_near_q && l_close_s2;
  /* verilator lint_off WIDTH */  // labels index a table of LABEL_SLOTS (not 2^LW) entries
  wire [LW-1:0] ur = parent[u_lab];
  /* verilator lint_on WIDTH */
  wire [LW-1:0] lr = l_lab_q;
  wire          merge = up_ok && left_ok && (ur != lr);
  wire [LW-1:0] m_s = (ur < lr) ? ur : lr;  // survivor: the older label
  wire [LW-1:0] m_a = (ur < lr) ? lr : ur;  // absorbed
  wire [LW-1:0] cand = fresh ? {LW{1'b0}} : cand_q;
  wire          room = fresh | cok_q;
  wire          alloc = near && !up_ok && !left_ok && room;
  wire          drop = near && !up_ok && !left_ok && !room;
  wire          near_eff = near && !drop;
  wire [LW-1:0] lab = merge ? m_s : up_ok ? ur : left_ok ? lr : cand;
  // the allocated label is never above the count (the lowest free one is taken)
  wire [NW-1:0] next_new = next_eff + {{(NW-1){1'b0}}, alloc && ({{(NW-LW){1'b0}}, cand} == next_eff)};
  wire          tf_new = (fresh ? 1'b0 : tf_q) | drop;

  // Frees and the next candidate, from registers only (the state before this pixel).
  reg  [LABEL_SLOTS-1:0] free_v, last_v, cand_v, avail_v;
  integer j;
  always @* begin
    for (j = 0; j < LABEL_SLOTS; j = j + 1) begin
      /* verilator lint_off WIDTH */
      last_v[j]  = l_near_q && (l_lab_q == j);
      cand_v[j]  = cok_q && (cand_q == j);
      free_v[j]  = busy_q[j] && !ucur_q[j] && !uprev_q[j] && !last_v[j] && ((parent[j] != j) || !big_q[j]);
      /* verilator lint_on WIDTH */
      avail_v[j] = !busy_q[j] && !cand_v[j];
    end
  end
  wire [LW-1:0] low_i;
  wire          low_any;
  sm_lowest_set #(.N(LABEL_SLOTS), .IW(LW)) u_low (.v(avail_v), .any(low_any), .idx(low_i));
  wire          take = alloc || !cok_q;  // the candidate is used up or there was none
  reg  [LABEL_SLOTS-1:0] busy_n, ucur_n, uprev_n;
  reg                    alloc_j;
  always @* begin
    for (j = 0; j < LABEL_SLOTS; j = j + 1) begin
      /* verilator lint_off WIDTH */
      alloc_j    = alloc && (cand == j);
      /* verilator lint_on WIDTH */
      busy_n[j]  = fresh ? alloc_j : (busy_q[j] && !free_v[j]) || alloc_j;
      ucur_n[j]  = !(fresh || sol_q) && (ucur_q[j] || last_v[j]);
      uprev_n[j] = !fresh && (sol_q ? (ucur_q[j] || last_v[j]) : uprev_q[j]);
    end
  end
  wire [LW-1:0] cand_n = fresh ? {{(LW-1){1'b0}}, alloc} : take ? low_i : cand_q;
  wire          cok_n = fresh ? (!alloc || LABEL_SLOTS > 1) : take ? low_any : 1'b1;

  // statistics, banked by frame parity: address {bank, label}; combinational reads
  // (distributed RAM) so a label's update is visible to the very next pixel
  localparam NS = 2 * LABEL_SLOTS;
  /* verilator coverage_off */  // memory words, as parent above
  reg [XW-1:0]   st_x0  [0:NS-1];
  reg [YW-1:0]   st_y0  [0:NS-1];
  reg [XW-1:0]   st_x1  [0:NS-1];
  reg [YW-1:0]   st_y1  [0:NS-1];
  reg [CNTW-1:0] st_cnt [0:NS-1];
  reg [SUMW-1:0] st_sum [0:NS-1];
  reg [DW-1:0]   st_max [0:NS-1];
  /* verilator coverage_on */
  reg [NS-1:0]   st_alive;

  // banks at {0, label} and {1, label}: LABEL_SLOTS need not be a power of two, so the
  // bank bit selects the upper half by offset (a plain bit when it is one)
  localparam POW2 = (LABEL_SLOTS == (1 << LW));
  wire [LW:0] a_lab = POW2 ? {bank, lab}
                    : bank ? {1'b0, lab} + LABEL_SLOTS[LW:0] : {1'b0, lab};
  wire [LW:0] a_abs = POW2 ? {bank, m_a}
                    : bank ? {1'b0, m_a} + LABEL_SLOTS[LW:0] : {1'b0, m_a};
  wire        upd = ce && real_q && near_eff;

  // ---- stage 3: statistics update, on the clk after stage 2's ce ---------------------
  reg            s3_v;       // an update is pending
  reg  [LW:0]    s3_lab, s3_abs;
  reg            s3_merge, s3_alloc;
  reg  [DW-1:0]  s3_d;
  reg  [XW-1:0]  s3_x;
  reg  [YW-1:0]  s3_y;
  reg  [LW-1:0]  s3_l;       // the label, without the bank
  // stage 4: the label's size against min_pixels, for the recycling (big_q)
  reg            s4_v;
  reg  [LW-1:0]  s4_l;
  reg  [CNTW-1:0] s4_cnt;

  // The pixel joins the survivor's statistics, merged with the absorbed one's. Bounds:
  // the compares (absorbed vs survivor, pixel vs each) run in parallel and one select
  // follows, instead of a compare on the result of a compare. Raster order makes some of
  // them constant, so they are left out: every label pixel so far lies on this row or
  // above (y1 is this row's y), a label's y0 is at most the pixel's y (only the survivor's
  // and the absorbed label's are compared: with recycled labels the survivor need not be
  // the older), and each label the pixel joins holds its left (x - 1) or upper (x)
  // neighbour, so no x0 is right of the pixel and an absorbed x1 beyond the survivor's
  // (>= x - 1) is at least x.
  wire [XW-1:0]   r_x0a = st_x0[s3_abs];
  wire [XW-1:0]   r_x0  = st_x0[s3_lab];
  wire [YW-1:0]   r_y0a = st_y0[s3_abs];
  wire [YW-1:0]   r_y0  = st_y0[s3_lab];
  wire [XW-1:0]   r_x1a = st_x1[s3_abs];
  wire [XW-1:0]   r_x1  = st_x1[s3_lab];
  wire [DW-1:0]   r_mxa = st_max[s3_abs];
  wire [DW-1:0]   r_mx  = st_max[s3_lab];
  wire            m_x0 = s3_merge && r_x0a < r_x0;
  wire            m_y0 = s3_merge && r_y0a < r_y0;  // recycled labels: the survivor may be younger
  wire            m_x1 = s3_merge && r_x1a > r_x1;
  wire            m_mx = s3_merge && r_mxa > r_mx;
  wire [XW-1:0]   n_x0 = s3_alloc ? s3_x : m_x0 ? r_x0a : r_x0;
  wire [YW-1:0]   n_y0 = s3_alloc ? s3_y : m_y0 ? r_y0a : r_y0;
  wire [XW-1:0]   n_x1 = s3_alloc ? s3_x : m_x1 ? r_x1a : (s3_x > r_x1 ? s3_x : r_x1);
  wire [YW-1:0]   n_y1 = s3_y;
  wire [DW-1:0]   n_max = s3_alloc ? s3_d : m_mx ? (s3_d > r_mxa ? s3_d : r_mxa)
                                            : (s3_d > r_mx ? s3_d : r_mx);
  wire [CNTW-1:0] b_cnt = st_cnt[s3_lab] + (s3_merge ? st_cnt[s3_abs] : {CNTW{1'b0}});
  wire [SUMW-1:0] b_sum = st_sum[s3_lab] + (s3_merge ? st_sum[s3_abs] : {SUMW{1'b0}});
  wire [CNTW-1:0] n_cnt = (s3_alloc ? {CNTW{1'b0}} : b_cnt) + 1'b1;
  wire [SUMW-1:0] n_sum = (s3_alloc ? {SUMW{1'b0}} : b_sum) + {{(SUMW-DW){1'b0}}, s3_d};
  // only {valid, d} of the stream word and the real/sof/sol bits of the sideband matter
  /* verilator coverage_off */  // lint sinks: no logic
  wire            unused_in = &{s_disp[14:DW], side_s2[`SM_SIDE_TAG], side_q[`SM_SIDE_TAG], s_lo[8:DW], p_lo[8:DW]};
  /* verilator coverage_on */

  // The equivalence table's update, one process per entry: Verilator 5.006 (Debian 12)
  // rejects a delayed assignment to an array element inside a for loop it does not
  // unroll (BLKLOOPINIT), which it does not beyond 64 entries.
  genvar gp;
  generate
    for (gp = 0; gp < LABEL_SLOTS; gp = gp + 1) begin : g_parent
      /* verilator lint_off WIDTH */  // the entry's own label, in the label's width
      localparam [LW-1:0] SELF = gp;
      /* verilator lint_on WIDTH */
      always @(posedge clk) begin
        if (ce && real_q) begin
          if (alloc && cand == SELF) parent[gp] <= SELF;
          else if (merge && parent[gp] == m_a) parent[gp] <= m_s;
        end
      end
    end
  endgenerate

  always @(posedge clk) begin
    if (ce) begin
      // stage 1
      /* verilator lint_off WIDTH */  // column index is 1 bit wider for MAX_WIDTH = 2^n
      rb_q      <= rb[s_x];
      /* verilator lint_on WIDTH */
      x_q       <= c_x;
      pix_q     <= s_d;
      up_in_q   <= row_ok[0];
      left_in_q <= col_ok[0];
      if (c_side[`SM_SIDE_REAL]) y_q <= c_y;
      near_q    <= s_disp[15] && ({{(8-DW){1'b0}}, s_d} >= thr_e);
      l_close_q <= (p_lo[8] || s_d >= p_lo[DW-1:0]) && ({{(9-DW){1'b0}}, s_d} <= p_hi);
      u_hi_q    <= s_hi;
      u_lo_q    <= s_lo[8] ? {DW{1'b0}} : s_lo[DW-1:0];
      // stage 2: the row above's entry for this column is read; write this row's
      /* verilator lint_off WIDTH */  // as above
      rb[x_s2] <= {real_q & near_eff, d, lab};
      /* verilator lint_on WIDTH */
      l_near_q <= real_q & near_eff;
      l_lab_q  <= lab;
      s3_lab   <= a_lab;
      s3_l     <= lab;
      s3_abs   <= a_abs;
      s3_merge <= merge;
      s3_alloc <= alloc;
      s3_d     <= d;
      s3_x     <= x_s2;
      s3_y     <= y_s2;
    end
    // stage 3
    s4_l   <= s3_l;
    s4_cnt <= n_cnt;
    if (s3_v) begin
      st_x0[s3_lab]  <= n_x0;
      st_y0[s3_lab]  <= n_y0;
      st_x1[s3_lab]  <= n_x1;
      st_y1[s3_lab]  <= n_y1;
      st_cnt[s3_lab] <= n_cnt;
      st_sum[s3_lab] <= n_sum;
      st_max[s3_lab] <= n_max;
    end
  end

  // stage 4: big_q, the size against the frame's min_pixels
  always @(posedge clk) begin
    if (s4_v) big_q[s4_l] <= ({{(32-CNTW){1'b0}}, s4_cnt} >= {16'd0, minpix_s2});
  end

  // alive: set when a label is allocated, cleared when it is absorbed (two writes)
  always @(posedge clk) begin
    if (s3_v) begin
      if (s3_alloc) st_alive[s3_lab] <= 1'b1;
      if (s3_merge) st_alive[s3_abs] <= 1'b0;
    end
  end

  // stream control state
  reg           scan_go;  // one clk: the frame's last pixel has been labelled
  reg           sc_bank;
  reg  [NW-1:0] sc_n;
  reg           sc_tf;
  reg  [15:0]   sc_min;
  always @(posedge clk) begin
    if (!rst_n) begin
      side_q  <= {`SM_SIDE_W{1'b0}};
      eof_q   <= 1'b0;
      side_s2 <= {`SM_SIDE_W{1'b0}};
      eof_s2  <= 1'b0;
      s3_v    <= 1'b0;
      s4_v    <= 1'b0;
      busy_q  <= {LABEL_SLOTS{1'b0}};
      ucur_q  <= {LABEL_SLOTS{1'b0}};
      uprev_q <= {LABEL_SLOTS{1'b0}};
      cand_q  <= {LW{1'b0}};
      cok_q   <= 1'b1;
      bank_q  <= 1'b0;
      next_q  <= {NW{1'b0}};
      tf_q    <= 1'b0;
      scan_go <= 1'b0;
      thr_q   <= 8'd0;
      tol_q   <= 8'd0;
      minpix_q <= 16'd0;
      hm1_q   <= {YW{1'b0}};
      sc_bank <= 1'b0;
      sc_n    <= {NW{1'b0}};
      sc_tf   <= 1'b0;
      sc_min  <= 16'd0;
    end else begin
      scan_go <= 1'b0;
      s3_v    <= upd;
      s4_v    <= s3_v;
      if (ce) begin
        side_q  <= c_side;
        eof_q   <= c_eof;
        side_s2 <= side_q;
        eof_s2  <= eof_q;
        if (c_side[`SM_SIDE_SOF]) begin
          thr_q    <= near_thr;
          tol_q    <= tol;
          minpix_q <= min_pixels;
          hm1_q    <= height - 1'b1;
        end
        if (real_q) begin
          bank_q  <= bank;
          next_q  <= next_new;
          tf_q    <= tf_new;
          busy_q  <= busy_n;
          ucur_q  <= ucur_n;
          uprev_q <= uprev_n;
          cand_q  <= cand_n;
          cok_q   <= cok_n;
        end
        if (real_q && eof_s2) begin
          scan_go <= 1'b1;
          sc_bank <= bank;
          sc_n    <= next_new;
          sc_tf   <= tf_new;
          sc_min  <= minpix_s2;
        end
      end
    end
  end

  // ---- end-of-frame scan (on clk): list the live labels, divide for the mean ---------
  localparam S_IDLE = 2'd0, S_SCAN = 2'd1, S_DIV = 2'd2, S_PUB = 2'd3;
  reg  [1:0]      sc_state;
  reg  [NW-1:0]   sc_i;
  reg  [OW-1:0]   sc_nobj;
  reg             sc_many;
  reg  [SUMW-1:0] dv_rem;
  reg  [CNTW-1:0] dv_cnt;
  reg  [DW-1:0]   dv_q;
  localparam BW = $clog2(DW + 1);
  /* verilator lint_off WIDTH */  // DW - 1 < 2^BW
  localparam [BW-1:0] DV_TOP = DW - 1;
  /* verilator lint_on WIDTH */
  reg  [BW-1:0]   dv_bit;

  // The list: three banks of one LUT RAM. The scan fills the work bank while the register
  // file reads the published bank and the packet the bank it snapshotted, so publishing
  // and snapshotting move a pointer instead of copying the list (two copies of
  // MAX_OBJECTS entries were 2,100 flip-flops at the defaults). Entry {bank, object}:
  // {max, sum, count, y1, x1, y0, x0}, the mean in a RAM of its own (written when the
  // division ends). Invariants: wb_q != pb_q, and wb_q != kb_q while a packet is sent.
  localparam LD = 4 << IW;
  /* verilator coverage_off */  // memory words, as parent above
  reg  [ENW-1:0]  lst_e [0:LD-1];
  reg  [DW-1:0]   lst_m [0:LD-1];
  /* verilator coverage_on */
  reg  [1:0]      wb_q;  // bank the scan writes
  reg  [1:0]      pb_q;  // bank the register file reads (the published list)
  reg  [1:0]      kb_q;  // bank the packet reads (its snapshot)

  wire [LW:0] a_sc = sc_bank ? {1'b0, sc_i[LW-1:0]} + LABEL_SLOTS[LW:0] : {1'b0, sc_i[LW-1:0]};
  wire        sc_ok = st_alive[a_sc] && ({{(32-CNTW){1'b0}}, st_cnt[a_sc]} >= {16'd0, sc_min});
  /* verilator lint_off WIDTH */
  wire        sc_room = sc_nobj < MAX_OBJECTS;
  /* verilator lint_on WIDTH */
  wire [SUMW-1:0] dv_try = {{DW{1'b0}}, dv_cnt} << dv_bit;
  wire [OW-1:0]   pkt_n_w;
  wire            pkt_busy;
  wire            pkt_load = (sc_state == S_PUB) && !pkt_busy;
  wire [IW+1:0]   wa = {wb_q, sc_nobj[IW-1:0]};
  // A bank that is neither a nor b (a == b: the one after a): where the scan may write
  // next without touching a bank a reader holds.
  function [1:0] free_bank(input [1:0] a, input [1:0] b);
    free_bank = (a != b) ? 2'd3 - a - b : (a == 2'd2) ? 2'd0 : a + 2'd1;
  endfunction
  // The banks a reset leaves the scan and the register file differ from the packet's
  // bank as it is after this clock (a soft reset lets a packet in progress finish, and
  // one may start in the reset's first clock), so they do not depend on the reset's length.
  wire [1:0]      kb_n = !out_rst_n ? 2'd2 : pkt_load ? wb_q : kb_q;
  wire [1:0]      wb_rst = free_bank(kb_n, kb_n);
  wire [1:0]      pb_rst = free_bank(wb_rst, kb_n);
  always @(posedge clk) kb_q <= kb_n;  // its reset is out_rst_n's (kb_n)

  always @(posedge clk) begin
    if (!rst_n) begin
      sc_state   <= S_IDLE;
      sc_i       <= {NW{1'b0}};
      sc_nobj    <= {OW{1'b0}};
      sc_many    <= 1'b0;
      list_ready <= 1'b0;
      obj_count  <= 8'd0;
      too_many   <= 1'b0;
      table_full <= 1'b0;
      dv_bit     <= 0;
      wb_q       <= wb_rst;
      pb_q       <= pb_rst;
    end else begin
      list_ready <= 1'b0;
      case (sc_state)
        S_IDLE: if (scan_go) begin
          sc_state <= S_SCAN;
          sc_i     <= {NW{1'b0}};
          sc_nobj  <= {OW{1'b0}};
          sc_many  <= 1'b0;
        end
        S_SCAN: begin
          if (sc_i == sc_n) begin
            sc_state <= S_PUB;
          end else begin
            sc_i <= sc_i + 1'b1;
            if (sc_ok && sc_room) begin  // the entry now, its mean when the division ends
              lst_e[wa] <= {st_max[a_sc], st_sum[a_sc], st_cnt[a_sc], st_y1[a_sc], st_x1[a_sc],
                            st_y0[a_sc], st_x0[a_sc]};
              dv_rem   <= st_sum[a_sc];
              dv_cnt   <= st_cnt[a_sc];
              dv_q     <= {DW{1'b0}};
              dv_bit   <= DV_TOP;
              sc_state <= S_DIV;
            end else if (sc_ok) begin
              sc_many <= 1'b1;
            end
          end
        end
        S_DIV: begin
          // restoring division, one quotient bit per clk: mean < DISP needs DW bits
          if (dv_rem >= dv_try) begin
            dv_rem <= dv_rem - dv_try;
          end
          if (dv_bit == 0) begin
            lst_m[wa] <= dv_q | {{(DW-1){1'b0}}, dv_rem >= dv_try};
            sc_nobj  <= sc_nobj + 1'b1;
            sc_state <= S_SCAN;
          end else begin
            /* verilator lint_off WIDTH */  // bit counter is 1 bit wider for DW = 2^n
            dv_q[dv_bit] <= dv_rem >= dv_try;
            /* verilator lint_on WIDTH */
            dv_bit <= dv_bit - 1'b1;
          end
        end
        default: begin  // S_PUB
          // publish the work bank; the next list goes to a bank neither the register
          // file nor a packet still being sent reads (a packet that starts now
          // snapshots the published bank itself)
          pb_q       <= wb_q;
          wb_q       <= free_bank(wb_q, pkt_busy ? kb_q : wb_q);
          obj_count  <= {{(8-OW){1'b0}}, sc_nobj};
          too_many   <= sc_many;
          table_full <= sc_tf;
          list_ready <= 1'b1;
          sc_state   <= S_IDLE;
        end
      endcase
    end
  end

  // An entry as the register file and the packet show it:
  // {max, mean, 16'd0, sum, count, y1, x1, y0, x0} in 8, 8, 16 and 32 or 16-bit fields.
  function [159:0] entry_fields(input [ENW-1:0] e, input [DW-1:0] mean);
    entry_fields = {{(8-DW){1'b0}}, e[ENW-1 -: DW], {(8-DW){1'b0}}, mean, 16'd0,
                    {(32-SUMW){1'b0}}, e[2*XW+2*YW+CNTW +: SUMW],
                    {(32-CNTW){1'b0}}, e[2*XW+2*YW +: CNTW],
                    {(16-YW){1'b0}}, e[2*XW+YW +: YW], {(16-XW){1'b0}}, e[XW+YW +: XW],
                    {(16-YW){1'b0}}, e[XW +: YW], {(16-XW){1'b0}}, e[0 +: XW]};
  endfunction
  wire [IW+1:0] ra = {pb_q, rd_index};
  wire [159:0]  rd_e = entry_fields(lst_e[ra], lst_m[ra]);
  assign rd_x0    = rd_e[15:0];
  assign rd_y0    = rd_e[31:16];
  assign rd_x1    = rd_e[47:32];
  assign rd_y1    = rd_e[63:48];
  assign rd_count = rd_e[95:64];
  assign rd_sum   = rd_e[127:96];
  assign rd_mean  = rd_e[151:144];
  assign rd_max   = rd_e[159:152];

  // ---- object packet: header, then 5 words per object, from its own bank -------------
  reg          pk_busy_q;
  reg [OW-1:0] pk_n;
  reg [2:0]    pk_flags;  // {lost, table_full, too_many}
  reg [OW-1:0] pk_obj;    // object of the current word
  reg [2:0]    pk_w;      // 0..4 within the object, or header when pk_hdr
  reg          pk_hdr;
  assign pkt_busy = pk_busy_q;
  assign pkt_n_w  = pk_n;

  wire [IW+1:0] ka = {kb_q, pk_obj[IW-1:0]};
  wire [159:0]  pk_e = entry_fields(lst_e[ka], lst_m[ka]);
  reg  [31:0]    pk_word;
  always @* begin
    case (pk_w)
      3'd0:    pk_word = pk_e[31:0];
      3'd1:    pk_word = pk_e[63:32];
      3'd2:    pk_word = pk_e[95:64];
      3'd3:    pk_word = pk_e[127:96];
      default: pk_word = {16'd0, pk_e[159:144]};
    endcase
  end
  assign m_axis_obj_tvalid = pk_busy_q;
  assign m_axis_obj_tdata  = pk_hdr ? {8'hA5, 13'd0, pk_flags, {(8-OW){1'b0}}, pk_n} : pk_word;
  assign m_axis_obj_tlast  = pk_busy_q && (pk_hdr ? (pk_n == {OW{1'b0}})
                                                 : (pk_w == 3'd4 && pk_obj == pk_n - 1'b1));
  /* verilator coverage_off */  // lint sink
  wire unused_pk = &{pkt_n_w, pk_e[143:128], rd_e[143:128]};
  /* verilator coverage_on */

  always @(posedge clk) begin
    if (!out_rst_n) begin
      pk_busy_q <= 1'b0;
      pk_n      <= {OW{1'b0}};
      pk_flags  <= 3'd0;
      pk_obj    <= {OW{1'b0}};
      pk_w      <= 3'd0;
      pk_hdr    <= 1'b0;
      pkt_lost  <= 1'b0;
    end else begin
      if (pkt_load) begin
        pk_busy_q <= 1'b1;
        pk_n      <= sc_nobj;
        pk_flags  <= {pkt_lost, sc_tf, sc_many};
        pk_obj    <= {OW{1'b0}};
        pk_w      <= 3'd0;
        pk_hdr    <= 1'b1;
        pkt_lost  <= 1'b0;
      end else begin
        if (sc_state == S_PUB) pkt_lost <= 1'b1;  // busy: this list's packet is dropped
        if (pk_busy_q && m_axis_obj_tready) begin
          if (m_axis_obj_tlast) begin
            pk_busy_q <= 1'b0;
          end else if (pk_hdr) begin
            pk_hdr <= 1'b0;
          end else if (pk_w == 3'd4) begin
            pk_w   <= 3'd0;
            pk_obj <= pk_obj + 1'b1;
          end else begin
            pk_w <= pk_w + 1'b1;
          end
        end
      end
    end
  end

`ifndef SYNTHESIS
  // Simulation-only invariants (Verilator --assert builds): the scan never writes the bank
  // the read port shows, nor the bank of a packet being sent.
  always @(posedge clk) begin
    if (rst_n && wb_q == pb_q) $error("sm_objects: the scan's bank %0d is the published list's", wb_q);
    if (rst_n && out_rst_n && pk_busy_q && wb_q == kb_q)
      $error("sm_objects: the scan's bank %0d is the packet's", wb_q);
  end
`endif
endmodule
`default_nettype wire
