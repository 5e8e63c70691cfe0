`default_nettype none
`include "sm_defs.vh"
// The speckle stage (docs/algorithm.md 9.8, model/speckle.cpp): a connected region of
// valid pixels whose 4-neighbours' Q.4 values differ by at most diff, of at most size
// pixels, is a mismatch island; its pixels leave invalid, {0, 1, 6'b0, 24'b0}. Scanline
// matching leaves such islands where a row's path locks onto a wrong level; the rules that
// judge a pixel alone cannot see them, a region's size can.
//
// Every word waits ROWS rows in u_words beside its label, so a pixel's region is known
// ROWS rows below it. Labelling (sequential, on the clocks between ces): a valid pixel
// joins its left and upper neighbours that are valid and within diff; it takes the root
// of the region it joins, a new label when none, and on joining two regions the root of
// higher rank survives (union by rank bounds a find to log2(LABELS) pointers). Each label
// counts the undecided pixels holding it and the labels pointing to it; the verdict walk
// of a pixel counts its label down and frees the labels that reach zero, up the pointers,
// into u_fifo. With no label free a pixel is KEEP: kept, and so is what joins it.
//
// Verdict, after the entering pixel is labelled: the pixel ROWS rows above leaves kept if
// its root was reached on the entering row or the one above (the region may still grow)
// unless its frame has ended (virtual or next frame's beat entering), or if its region
// holds more than size pixels, or if it holds more than trust pixels of which fewer than
// 1/16 fail the left-right check (confidence bit 7 clear): a small object both views
// agree on, which a robot must not lose, rather than a mismatch island.
//
// Timing: a beat takes 10 clocks plus the pointers its two finds follow (4 at most on the
// 14 scenes at 1,024 labels), so the block suits the folded configurations (16 clocks a
// beat) on average, not beat by beat. The entering beats wait in a queue and the decided
// ones in another, SLACK beats in all: a run of slow beats borrows from the fast ones
// around it, and the stream keeps its pace (ce every F clocks) unless the labeller falls
// SLACK beats behind, when `ready` holds ce off until it catches up. Latency: the output
// beat after the ce of input beat n is the leaving pixel of beat n - SLACK (the pixel of
// beat n - SLACK - ROWS * width); the first SLACK output beats have an empty sideband.
module sm_speckle #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter ROWS      = 32,   // rows a word waits for its verdict (look-ahead)
    parameter LABELS    = 1024, // label-table entries (regions awaiting a verdict)
    parameter SLACK     = 16    // beats the labeller may fall behind the stream (queue depth)
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    output wire                  ready,   // the output beat of the next ce is decided: ce may come
    input  wire                  en,      // en, size, diff, trust: latched at a frame's first
    input  wire [11:0]           size,    // beat; en 0 passes every word (ROWS rows later)
    input  wire [7:0]            diff,
    input  wire [11:0]           trust,
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [31:0]           s_word,  // {1, 7'b0, confidence, Q.4} or {0, 0, fails, 24'b0}
    output reg  [`SM_SIDE_W-1:0] m_side,
    output reg  [31:0]           m_word
);
  localparam XW    = `SM_COUNT_W(MAX_WIDTH);      // x, 0..MAX_WIDTH
  localparam NSLOT = ROWS + 1;                     // rows held
  localparam DEPTH = NSLOT * MAX_WIDTH;
  localparam AW    = $clog2(DEPTH);
  localparam SLW   = $clog2(NSLOT);
  localparam LB    = $clog2(LABELS);               // a label
  localparam LW    = LB + 1;                       // a code: {0, label}, NONE or KEEP
  localparam RW    = $clog2(ROWS + 2);             // row and frame numbers modulo 2^RW > ROWS + 1
  localparam RKW   = 4;                            // rank, saturating (bounds a find, never decides)
  localparam SZW   = 13;                           // region size and its pixels failing left-right,
                                                   // saturating at 8191
  localparam RFW   = $clog2(DEPTH + LABELS + 1);   // references: pixels held and labels pointing
  // table entry {parent, rank, size, bad, last, refs}: the fields' lsbs
  localparam LA_L  = RFW;
  localparam BD_L  = LA_L + RW;
  localparam SZ_L  = BD_L + SZW;
  localparam RK_L  = SZ_L + SZW;
  localparam EW    = RK_L + RKW + LB;
  localparam MW    = 1 + 1 + 2 + RW + 12 + 12;     // row meta {sof, en, tag, fid, trust, size}
  localparam [LW-1:0] NONE = LABELS[LW-1:0];
  localparam [LW-1:0] KEEP = NONE + 1'b1;
  localparam [SZW-1:0] SZ_MAX = {SZW{1'b1}};
  localparam [RKW-1:0] RK_MAX = {RKW{1'b1}};
  localparam [31:0] SPECKLE_WORD = 32'h4000_0000;
  localparam [SLW-1:0] SLOT1 = 1;
  localparam [RW-1:0] AGE1 = 1;

  generate
    `SM_BAD_PARAM(g_bad_rows, ROWS < 1 || ROWS > 62, ("sm_speckle: ROWS (%0d) must be 1..62", ROWS))
    `SM_BAD_PARAM(g_bad_labels, LABELS < 2 || LABELS > 4094, ("sm_speckle: LABELS (%0d) must be 2..4094", LABELS))
    `SM_BAD_PARAM(g_bad_width, MAX_WIDTH < 2, ("sm_speckle: MAX_WIDTH (%0d) must be >= 2", MAX_WIDTH))
    `SM_BAD_PARAM(g_bad_slack, SLACK < 2 || SLACK > 64 || (SLACK & (SLACK - 1)) != 0,
                  ("sm_speckle: SLACK (%0d) must be a power of two, 2..64", SLACK))
  endgenerate

  localparam [3:0] S_IDLE = 4'd0, S_UP = 4'd1, S_DEC = 4'd2, S_LAB = 4'd3, S_FINDU = 4'd4, S_GOTL = 4'd5,
                   S_ADD = 4'd6, S_NEW = 4'd7, S_POP = 4'd8, S_STORE = 4'd9, S_WALK = 4'd10;
  reg [3:0] state_q;
  wire pop;  // the labeller takes the oldest queued beat
  reg  [`SM_SIDE_W-1:0] res_side_q;  // the beat the labeller decided last
  reg  [31:0]           res_word_q;

  // ---- the queues: beats entering (at ce) and decided (taken at ce), SLACK in all ----
  // Entering + being labelled + decided + prefill = SLACK at every ce, so neither queue
  // overflows; the prefill stands for the beats the labeller is ahead of at reset.
  localparam QW = $clog2(SLACK);
  reg  [33+`SM_SIDE_W+31:0] q_in [0:SLACK-1];  // {en, trust, size, diff, side, word}
  reg  [`SM_SIDE_W+31:0] q_out [0:SLACK-1];
  reg  [QW-1:0] in_wp_q, in_rp_q, out_wp_q, out_rp_q;
  reg  [QW:0]   in_n_q, out_n_q, fill_q;
  reg           done_q;  // the beat just decided waits in res_*_q for the output queue
  assign ready = fill_q != {(QW + 1){1'b0}} || out_n_q != {(QW + 1){1'b0}};
  wire take = ce && ready;
  wire [33+`SM_SIDE_W+31:0] q_head = q_in[in_rp_q];
  wire [`SM_SIDE_W-1:0] q_side = q_head[`SM_SIDE_W+31:32];
  wire [31:0]           q_word = q_head[31:0];
  wire                  en_in = q_head[32+`SM_SIDE_W+32];
  wire [11:0]           trust_in = q_head[20+`SM_SIDE_W+32 +: 12];
  wire [11:0]           size_in = q_head[8+`SM_SIDE_W+32 +: 12];
  wire [7:0]            diff_in = q_head[`SM_SIDE_W+32 +: 8];
  assign pop = state_q == S_IDLE && in_n_q != {(QW + 1){1'b0}};
  always @(posedge clk) begin
    if (take) q_in[in_wp_q] <= {en, trust, size, diff, s_side, s_word};
    if (done_q) q_out[out_wp_q] <= {res_side_q, res_word_q};
  end
  always @(posedge clk) begin
    if (!rst_n) begin
      in_wp_q  <= {QW{1'b0}};
      in_rp_q  <= {QW{1'b0}};
      out_wp_q <= {QW{1'b0}};
      out_rp_q <= {QW{1'b0}};
      in_n_q   <= {(QW + 1){1'b0}};
      out_n_q  <= {(QW + 1){1'b0}};
      fill_q   <= SLACK[QW:0];
      m_side   <= {`SM_SIDE_W{1'b0}};
    end else begin
      if (take) in_wp_q <= in_wp_q + 1'b1;
      if (pop) in_rp_q <= in_rp_q + 1'b1;
      in_n_q <= in_n_q + {{QW{1'b0}}, take} - {{QW{1'b0}}, pop};
      if (done_q) out_wp_q <= out_wp_q + 1'b1;
      if (take && fill_q == {(QW + 1){1'b0}}) out_rp_q <= out_rp_q + 1'b1;
      out_n_q <= out_n_q + {{QW{1'b0}}, done_q} - {{QW{1'b0}}, take && fill_q == {(QW + 1){1'b0}}};
      if (take && fill_q != {(QW + 1){1'b0}}) fill_q <= fill_q - 1'b1;
      if (take) m_side <= fill_q != {(QW + 1){1'b0}} ? {`SM_SIDE_W{1'b0}} : q_out[out_rp_q][`SM_SIDE_W+31:32];
    end
    if (take) m_word <= q_out[out_rp_q][31:0];
  end

  // Whether a neighbour's word is valid with its Q.4 value b within diff of the entering
  // pixel's: |a - b| <= diff as lo_q <= b <= hi_q, bounds registered from a and diff on
  // the clock before, so a block RAM read meets two compares, not a subtract, an absolute
  // value and a compare (placed and routed at zynq, the upper word's read into up_j_q
  // was the block's slowest path at every placer seed).
  reg  [15:0] lo_q;  // max(a - diff, 0)
  reg  [16:0] hi_q;  // a + diff
  function automatic in_band(input vb, input [15:0] b, input [15:0] lo, input [16:0] hi);
    begin
      in_band = vb && b >= lo && {1'b0, b} <= hi;
    end
  endfunction

  // ---- position: the entering row's slot and column, the decided row's slot ----
  reg           in_real_q;
  reg  [31:0]   in_word_q;
  reg           started_q;    // a row has begun since reset
  reg  [XW-1:0] x_q;
  reg  [AW-1:0] base_cur_q, base_up_q, base_dec_q;  // slot * MAX_WIDTH of the three rows
  reg  [SLW-1:0] slot_cur_q, slot_dec_q;
  reg  [RW-1:0] row_q, fid_q;
  reg           en_q, cur_sof_q;
  reg  [11:0]   size_q, trust_q;
  reg  [7:0]    diff_q;
  reg  [NSLOT-1:0] real_q;    // the held rows that belong to a frame
  reg  [MW-1:0] meta [0:NSLOT-1];
  wire sol = q_side[`SM_SIDE_SOL], sof = q_side[`SM_SIDE_SOF];

  // x widened to an address (the widths may be equal: no zero-width replication)
  function automatic [AW-1:0] addr_of(input [XW-1:0] x);
    begin
      addr_of = {AW{1'b0}};
      addr_of[XW-1:0] = x;
    end
  endfunction

  function automatic [AW-1:0] next_base(input [AW-1:0] b);
    begin
      next_base = (b >= DEPTH[AW-1:0] - MAX_WIDTH[AW-1:0]) ? b - (DEPTH[AW-1:0] - MAX_WIDTH[AW-1:0])
                                                           : b + MAX_WIDTH[AW-1:0];
    end
  endfunction
  function automatic [SLW-1:0] next_slot(input [SLW-1:0] s);
    begin
      next_slot = (s == ROWS[SLW-1:0]) ? {SLW{1'b0}} : s + 1'b1;
    end
  endfunction

  always @(posedge clk) begin
    if (!rst_n) begin
      started_q  <= 1'b0;
      x_q        <= {XW{1'b0}};
      base_cur_q <= {AW{1'b0}};
      base_up_q  <= ROWS[AW-1:0] * MAX_WIDTH[AW-1:0];
      base_dec_q <= MAX_WIDTH[AW-1:0];
      slot_cur_q <= {SLW{1'b0}};
      slot_dec_q <= SLOT1;
      row_q      <= {RW{1'b0}};
      fid_q      <= {RW{1'b0}};
      real_q     <= {NSLOT{1'b0}};
    end else if (pop) begin
      if (sol) begin
        started_q  <= 1'b1;
        x_q        <= {XW{1'b0}};
        base_cur_q <= next_base(base_cur_q);
        base_up_q  <= base_cur_q;
        base_dec_q <= next_base(base_dec_q);
        slot_cur_q <= next_slot(slot_cur_q);
        slot_dec_q <= next_slot(slot_dec_q);
        row_q      <= row_q + 1'b1;
        if (sof) fid_q <= fid_q + 1'b1;
        real_q[next_slot(slot_cur_q)] <= q_side[`SM_SIDE_REAL];
      end else if (started_q && x_q != MAX_WIDTH[XW-1:0]) begin
        x_q <= x_q + 1'b1;
      end
    end
  end

  // per-frame settings and the row meta: data only
  always @(posedge clk) begin
    if (pop) begin
      in_real_q <= q_side[`SM_SIDE_REAL];
      in_word_q <= q_word;
      if (sol) cur_sof_q <= sof;
      if (sol && sof) begin
        en_q   <= en_in;
        size_q  <= size_in;
        trust_q <= trust_in;
        diff_q  <= diff_in;
      end
      if (sol)
        meta[next_slot(slot_cur_q)] <= sof ? {sof, en_in, q_side[`SM_SIDE_TAG], fid_q + 1'b1, trust_in, size_in}
                                           : {1'b0, en_q, q_side[`SM_SIDE_TAG], fid_q, trust_q, size_q};
    end
  end

  // ---- the beat's work: labels, words and entries it carries from state to state ----
  reg  [LW-1:0]  code_q, up_code_q, dec_code_q, left_code_q;
  reg  [31:0]    dec_word_q;
  reg  [16:0]    left_word_q;  // {valid, Q.4} of the entering row's last beat
  reg            up_j_q, left_j_q, keep_q, both_q, ended_q, den_q, rel_q;
  reg  [11:0]    dsize_q, dtrust_q;
  reg  [LB-1:0]  node_q, ru_q;
  reg  [EW-1:0]  ent_u_q, ent_r_q;  // the upper root's entry; the survivor's, merged

  // ---- memories ----
  reg              w_we, w_re;
  reg  [AW-1:0]    w_raddr;
  wire [31+LW:0]   w_rdata;
  sm_sdp_ram #(.DATA_W(32 + LW), .DEPTH(DEPTH)) u_words (
      .clk(clk), .we(w_we), .waddr(base_cur_q + addr_of(x_q)), .wdata({code_q, in_word_q}),
      .re(w_re), .raddr(w_raddr), .rdata(w_rdata)
  );
  reg              t_we, t_re;
  reg  [LB-1:0]    t_waddr, t_raddr;
  reg  [EW-1:0]    t_wdata;
  wire [EW-1:0]    t_rdata;
  sm_sdp_ram #(.DATA_W(EW), .DEPTH(LABELS)) u_table (
      .clk(clk), .we(t_we), .waddr(t_waddr), .wdata(t_wdata), .re(t_re), .raddr(t_raddr), .rdata(t_rdata)
  );
  reg              f_we, f_re;
  wire [LB-1:0]    f_rdata;
  reg  [LB-1:0]    f_head_q, f_tail_q;
  reg  [LW-1:0]    f_count_q, fresh_q;  // 0..LABELS
  sm_sdp_ram #(.DATA_W(LB), .DEPTH(LABELS)) u_fifo (
      .clk(clk), .we(f_we), .waddr(f_tail_q), .wdata(node_q), .re(f_re), .raddr(f_head_q), .rdata(f_rdata)
  );
  function automatic [LB-1:0] next_label(input [LB-1:0] l);
    begin
      next_label = (l == LABELS[LB-1:0] - 1'b1) ? {LB{1'b0}} : l + 1'b1;
    end
  endfunction

  // the entry read last, in fields
  wire [LB-1:0]  e_parent = t_rdata[EW-1 -: LB];
  wire [RKW-1:0] e_rank   = t_rdata[RK_L +: RKW];
  wire [SZW-1:0] e_size   = t_rdata[SZ_L +: SZW];
  wire [SZW-1:0] e_bad    = t_rdata[BD_L +: SZW];
  wire [RW-1:0]  e_last   = t_rdata[LA_L +: RW];
  wire [RFW-1:0] e_refs   = t_rdata[0 +: RFW];

  // ---- the beat's work ----
  wire           in_ok = started_q && x_q != MAX_WIDTH[XW-1:0];
  wire           in_lab = in_ok && in_real_q && in_word_q[31];
  wire [MW-1:0]  dmeta = meta[slot_dec_q];
  wire           dmeta_real = real_q[slot_dec_q];
  wire           up_lab = up_j_q && up_code_q < NONE;
  wire           left_lab = left_j_q && left_code_q < NONE;
  // merge of the upper root (ent_u_q, ru_q) and the left one (t_rdata, left_code_q)
  wire           left_wins = e_rank > ent_u_q[RK_L +: RKW];
  wire [EW-1:0]  ent_a = left_wins ? t_rdata : ent_u_q;
  wire [EW-1:0]  ent_b = left_wins ? ent_u_q : t_rdata;
  wire [LB-1:0]  lab_a = left_wins ? left_code_q[LB-1:0] : ru_q;
  wire [RKW-1:0] rank_a = ent_a[RK_L +: RKW], rank_b = ent_b[RK_L +: RKW];
  // the survivor's parent is itself and its last row the entering one: not read
  wire unused_ent = ^{ent_a[EW-1 -: LB], ent_b[EW-1 -: LB], ent_r_q[LA_L +: RW]};
  wire [SZW:0]   size_ab = {1'b0, ent_a[SZ_L +: SZW]} + {1'b0, ent_b[SZ_L +: SZW]};
  wire [SZW:0]   bad_ab = {1'b0, ent_a[BD_L +: SZW]} + {1'b0, ent_b[BD_L +: SZW]};
  // the survivor's entry and the new pixel's (lr_bad: it fails the left-right check)
  wire           lr_bad = !in_word_q[23];
  wire [SZW-1:0] r_size = ent_r_q[SZ_L +: SZW];
  wire [SZW-1:0] r_size1 = keep_q || r_size == SZ_MAX ? SZ_MAX : r_size + 1'b1;
  wire [SZW-1:0] r_bad = ent_r_q[BD_L +: SZW];
  wire [SZW-1:0] r_bad1 = r_bad == SZ_MAX ? SZ_MAX : r_bad + {{(SZW - 1){1'b0}}, lr_bad};
  wire [RFW-1:0] e_refs1 = e_refs - 1'b1;
  wire [RW-1:0]  age = row_q - e_last;
  // trusted: more than trust pixels, fewer than 1/16 of them failing left-right
  wire           trusted = {1'b0, e_size} > {2'b0, dtrust_q} && {e_bad, 4'b0} < {4'b0, e_size};
  wire           kept = (!ended_q && age <= AGE1) || {1'b0, e_size} > {2'b0, dsize_q} || trusted;

  always @(*) begin
    w_we = 1'b0; w_re = 1'b0; w_raddr = base_up_q + addr_of(x_q);
    t_we = 1'b0; t_re = 1'b0; t_waddr = node_q; t_raddr = node_q; t_wdata = t_rdata;
    f_we = 1'b0; f_re = 1'b0;
    case (state_q)
      S_UP: w_re = 1'b1;
      S_DEC: begin
        w_re = 1'b1;
        w_raddr = base_dec_q + addr_of(x_q);
      end
      S_LAB: begin
        t_re = in_lab && (up_lab || left_lab);
        t_raddr = up_lab ? up_code_q[LB-1:0] : left_code_q[LB-1:0];
      end
      S_FINDU: begin
        t_re = 1'b1;
        t_raddr = e_parent == node_q ? left_code_q[LB-1:0] : e_parent;
      end
      S_GOTL: if (both_q) begin  // the loser points to the survivor
        t_we = 1'b1;
        t_waddr = left_wins ? ru_q : left_code_q[LB-1:0];
        t_wdata = {lab_a, ent_b[EW-LB-1:0]};
      end
      S_ADD: begin
        t_we = 1'b1;
        t_waddr = code_q[LB-1:0];
        t_wdata = {ent_r_q[EW-1 -: LB + RKW], r_size1, r_bad1, row_q, ent_r_q[0 +: RFW] + 1'b1};
      end
      S_NEW: f_re = 1'b1;
      S_POP: ;
      S_STORE: begin
        w_we = 1'b1;
        t_re = 1'b1;
        t_raddr = dec_code_q[LB-1:0];
      end
      S_WALK: begin
        t_we = rel_q;
        t_wdata = {t_rdata[EW-1:RFW], e_refs1};
        f_we = rel_q && e_refs1 == {RFW{1'b0}};
        t_re = 1'b1;
        t_raddr = e_parent;
      end
      default: ;
    endcase
    // a new label's entry: its own root, rank 0, one pixel, held once
    if (state_q == S_NEW || state_q == S_POP) begin
      t_waddr = state_q == S_POP ? f_rdata : fresh_q[LB-1:0];
      t_wdata = {t_waddr, {RKW{1'b0}}, {{(SZW - 1){1'b0}}, 1'b1}, {{(SZW - 1){1'b0}}, lr_bad}, row_q,
                 {{(RFW - 1){1'b0}}, 1'b1}};
      t_we = state_q == S_POP || (!keep_q && fresh_q != NONE);
    end
  end

  always @(posedge clk) begin
    if (!rst_n) begin
      state_q   <= S_IDLE;
      done_q    <= 1'b0;
      fresh_q   <= {LW{1'b0}};
      f_head_q  <= {LB{1'b0}};
      f_tail_q  <= {LB{1'b0}};
      f_count_q <= {LW{1'b0}};
    end else begin
      case (state_q)
        S_IDLE: if (pop) state_q <= S_UP;
        S_UP: state_q <= S_DEC;
        S_DEC: state_q <= S_LAB;
        S_LAB:
          if (!in_ok) state_q <= S_IDLE;
          else if (!in_lab) state_q <= S_STORE;
          else if (up_lab) state_q <= S_FINDU;
          else if (left_lab) state_q <= S_GOTL;
          else state_q <= S_NEW;
        S_FINDU:
          if (e_parent == node_q) state_q <= left_lab && left_code_q[LB-1:0] != node_q ? S_GOTL : S_ADD;
        S_GOTL: state_q <= S_ADD;
        S_ADD: state_q <= S_STORE;
        S_NEW:
          if (keep_q || fresh_q != NONE) begin
            state_q <= S_STORE;
            if (!keep_q) fresh_q <= fresh_q + 1'b1;
          end else if (f_count_q != {LW{1'b0}}) begin
            state_q <= S_POP;
          end else begin
            state_q <= S_STORE;  // no label free: KEEP
          end
        S_POP: begin
          state_q  <= S_STORE;
          f_head_q <= next_label(f_head_q);
        end
        S_STORE: state_q <= dmeta_real && dec_code_q < NONE ? S_WALK : S_IDLE;
        S_WALK: if (e_parent == node_q) state_q <= S_IDLE;
        default: state_q <= S_IDLE;
      endcase
      done_q <= (state_q == S_LAB && !in_ok) || (state_q == S_STORE && !(dmeta_real && dec_code_q < NONE)) ||
                (state_q == S_WALK && e_parent == node_q);
      // the FIFO's count: a pop in S_POP, a push in S_WALK (never both in one clock)
      if (f_we) f_tail_q <= next_label(f_tail_q);
      if (f_we) f_count_q <= f_count_q + 1'b1;
      else if (state_q == S_POP) f_count_q <= f_count_q - 1'b1;
    end
  end

  // data registers of the beat's work
  always @(posedge clk) begin
    case (state_q)
      S_UP: begin
        lo_q <= in_word_q[15:0] > {8'd0, diff_q} ? in_word_q[15:0] - {8'd0, diff_q} : 16'd0;
        hi_q <= {1'b0, in_word_q[15:0]} + {9'd0, diff_q};
      end
      S_DEC: begin
        up_j_q      <= !cur_sof_q && in_word_q[31] && in_band(w_rdata[31], w_rdata[15:0], lo_q, hi_q);
        up_code_q   <= w_rdata[31+LW:32];
        left_j_q    <= x_q != {XW{1'b0}} && in_word_q[31]
                       && in_band(left_word_q[16], left_word_q[15:0], lo_q, hi_q);
      end
      S_LAB: begin
        dec_word_q <= w_rdata[31:0];
        dec_code_q <= w_rdata[31+LW:32];
        keep_q     <= (up_j_q && up_code_q == KEEP) || (left_j_q && left_code_q == KEEP);
        both_q     <= 1'b0;
        node_q     <= up_code_q[LB-1:0];
        code_q     <= NONE;
        if (!in_ok) begin
          res_word_q <= 32'd0;
        end
        if (in_lab && !up_lab && left_lab) begin  // the left root alone: its entry arrives in S_GOTL
          code_q <= left_code_q;
        end
      end
      S_FINDU:
        if (e_parent == node_q) begin
          ru_q    <= node_q;
          ent_u_q <= t_rdata;
          code_q  <= {1'b0, node_q};
          ent_r_q <= t_rdata;
          both_q  <= left_lab && left_code_q[LB-1:0] != node_q;
        end else begin
          node_q <= e_parent;
        end
      S_GOTL:
        if (both_q) begin
          code_q  <= {1'b0, lab_a};
          ent_r_q <= {lab_a, (rank_a == rank_b && rank_a != RK_MAX) ? rank_a + 1'b1 : rank_a,
                      size_ab[SZW] ? SZ_MAX : size_ab[SZW-1:0], bad_ab[SZW] ? SZ_MAX : bad_ab[SZW-1:0],
                      ent_a[LA_L +: RW], ent_a[0 +: RFW] + 1'b1};
        end else begin
          ent_r_q <= t_rdata;
        end
      S_NEW:
        if (keep_q || (fresh_q == NONE && f_count_q == {LW{1'b0}})) code_q <= KEEP;
        else if (fresh_q != NONE) code_q <= fresh_q;
      S_POP: code_q <= {1'b0, f_rdata};
      S_STORE: begin  // (reached only with in_ok)
        left_word_q <= {in_word_q[31], in_word_q[15:0]};
        left_code_q <= code_q;
        res_word_q <= dec_word_q;
        ended_q    <= !in_real_q || dmeta[24 +: RW] != fid_q;
        den_q      <= dmeta[MW-2];
        dsize_q    <= dmeta[11:0];
        dtrust_q   <= dmeta[23:12];
        node_q     <= dec_code_q[LB-1:0];
        rel_q      <= 1'b1;
      end
      S_WALK: begin
        if (rel_q && e_refs1 != {RFW{1'b0}}) rel_q <= 1'b0;
        node_q <= e_parent;
        if (e_parent == node_q && !kept && den_q) res_word_q <= SPECKLE_WORD;
      end
      default: ;
    endcase
  end
  // the output beat's sideband: control, so reset (none before the first row)
  always @(posedge clk) begin
    if (!rst_n) res_side_q <= {`SM_SIDE_W{1'b0}};
    else if (state_q == S_LAB && !in_ok) res_side_q <= {`SM_SIDE_W{1'b0}};
    else if (state_q == S_STORE)
      res_side_q <= {dmeta[MW-3 -: 2], x_q == {XW{1'b0}}, x_q == {XW{1'b0}} && dmeta[MW-1], dmeta_real};
  end
endmodule
`default_nettype wire
