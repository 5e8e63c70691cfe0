`default_nettype none
`include "sm_defs.vh"
// Trellis dynamic programming stage (docs/algorithm.md, section 6): a systolic array
// of DISP processing elements (sm_dp_pe), one per level, linked only to neighbours.
// Line k runs its forward pass in exactly W ce's (two sites per clock), writing one
// 2*DISP-bit decision word per clock into a block RAM; during the
// forward pass of line k+1, sm_dp_trace walks line k backwards and stacks its
// matches; during line k+2's forward pass line k leaves in raster order, filled.
// Lines follow each other with no gap, virtual rows included.
//
// Timing (x_in = column of the entering beat, S = DISP/2, P = 2):
//   PE d sees A(x, d) S - ceil(d/2) beats after it enters, so DP clock t of a line is
//   the ce on which column S + t enters (mod W, running into the next row); the ce at
//   x_in = S - 1 ends a line and loads U(0, .).
//   On forward clock t of line k+1, decision word W-1-t of line k (one bank rewritten
//   in place, lines alternating direction: "Decision rows" below) is read; the backward
//   step uses it on the next ce, so the last backward step of
//   line k is at x_in = S, the read-out head is fetched at x_in = S + 1, and pixel x
//   of line k is registered on the ce at x_in = S + 2 + x (mod W), two rows later.
//   Latency: 2*W + S + P beats (sm_win_ctrl with D_ROWS = 2, D_COLS = S + P).
//   Minimum active width: S + P + 1 (width must exceed D_COLS).
//
// Folded (PU < DISP, F = DISP/PU clocks per beat, branch g_fold): PU lanes (sm_dp_fpe;
// the odd lanes' occlusion node a clock ahead) serve the level groups g = levels [g*PU,
// g*PU+PU) one after the other. Relies on the input-stability rule: from the clock
// after ce k up to the ce k+1 the inputs hold the beat ce k+1 samples, so DP clock t of
// that beat runs as sub-steps g = 0..F-1 on the F clocks after ce k (a counter the ce
// restarts; sub-step F-1 may fall on ce k+1 itself), and everything visible (m_side,
// m_disp) still changes only on ce, with the same beat-level timing and latency as
// above (2*W + S + P beats). Sub-step g needs from group g-1 the site-2t+1 value of its
// top (odd) level, computed one clock earlier (kept in a register), and from group g+1
// U(2t) of its bottom (even) level, not yet updated (second read port of lane 0's state
// memory). State: per lane a LUT-RAM of F words U(2t, g*PU+j), read a clock ahead. Cost
// skew: per lane a LUT-RAM ring of (beat mod 2^KW, group) words, written at {wp, g} and
// read at {wp - (S - g*PU/2 - ceil(j/2)), g}; skew 0 (level DISP-1) takes the input
// directly.
// Penalty per occlusion node (docs/algorithm.md section 6, "Edge-dependent penalty"): the
// occlusion nodes of level pair m at DP clock t have xl = t + m + 1, the column that
// entered S-1-m beats before column S + t; node (i, d) costs occ_edge where that
// column's edge flag is set, else occ. s_edge runs one beat ahead (on the ce of column
// x it holds the flag of the next beat), so every pair's 8-bit penalty is registered on
// the ce before the DP clock that uses it: no select in front of the PE adders.
// Folded: lane j of group g reads the flag of tap S-1-g*PU/2-floor(j/2), prefetched
// into a register for the next sub-step like the lane's state.
// Decisions: one word of 2*PU+2 bits per sub-step at {row, g} of one bank rewritten in
// place (g_fold): the group's 2*PU bits above the 2 bits of level g*PU-1, so the
// backward step of any level of group g finds both levels it may need in one word
// (written one clock late through a register so that the trace's read, on the clock
// after a ce, never meets the write of the same word). The trace reads one word per
// beat, group of its current level.
// Legal PU: DISP (today's array), or an even divisor of DISP below it (PU >= 2; an odd
// PU would put an even level at the top of a group, breaking the group order above).
// After reset the first beat's sub-steps start at once, so its ce must come at least
// F clocks after rst_n rises (sm_top: the first beats are not real anyway).
module sm_dp #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter DISP      = 128,  // disparity levels 0..DISP-1 (even, 4..254)
    parameter CW        = 6,    // aggregated cost width
    // Cost skews of at least RING_MIN beats live in LUT-RAM ring buffers, shorter ones
    // in shift registers (sm_dp_pe). The default puts every chain longer than a 64-bit
    // word in a ring (paper configuration: skews of 11..64 beats).
    parameter RING_MIN  = 64 / CW + 1,
    // Disparity levels computed per clock: DISP (one beat per clock) or an even divisor
    // of DISP (F = DISP/PU clocks per beat, ce at most every F clocks).
    parameter PU        = DISP
) (
    input  wire               clk,
    input  wire               rst_n,
    input  wire               ce,
    input  wire [XW-1:0]      width,   // active width, S + 3 .. MAX_WIDTH
    input  wire [7:0]         occ,       // occlusion penalty, latched per frame
    input  wire [7:0]         occ_edge,  // penalty at flagged pixels, latched with occ
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [DISP*CW-1:0] s_cost,    // A(x, d) at [d*CW +: CW]
    // Edge flag of the NEXT beat (column x+1 when this ce samples column x; column 0 of
    // the next row, whose flag is 0, after a row's last beat), virtual rows included.
    input  wire               s_edge,
    output reg  [`SM_SIDE_W-1:0] m_side,
    output wire [15:0]        m_disp,    // bit 15 valid (always), low DW bits disparity
    // Evidence of the output stage (docs/algorithm.md section 9), with m_disp's timing:
    output wire               m_matched, // the pixel is matched by the trellis
    output wire [7:0]         m_gap,     // unmatched: gap of its run (model run_gaps); else 0
    output wire [DW-1:0]      m_fill_bg  // unmatched: background fill (fill_background); else d
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam AW = $clog2(MAX_WIDTH);
  localparam DW = $clog2(DISP);
  localparam S = DISP / 2;
  localparam P = 2;  // beats of the read-out beyond 2 lines + skew
  localparam ACC_W = $clog2(MAX_WIDTH * ((1 << CW) - 1) + 2 * MAX_WIDTH * 255 + 1) + 1;
  localparam KW = $clog2(S);  // ring pointers: the longest skew is S beats
  localparam F = (PU > 0) ? DISP / PU : 1;  // clocks per beat
  localparam GW = (F > 1) ? $clog2(F) : 1;  // group index width
  localparam DEC_W = (F > 1) ? 2 * PU + 2 : 2 * DISP;  // decision word
  localparam RAW = $clog2(MAX_WIDTH + 1);  // a decision row 0..MAX_WIDTH
  // decision address: the row at PU = DISP; folded {row, g}. One bank rewritten in place.
  localparam DEC_AW = (F > 1) ? AW + GW : RAW;
  // decision words: MAX_WIDTH + 1 rows (g_par); folded MAX_WIDTH rows of 2^GW words
  localparam DEC_DEPTH = (F > 1) ? MAX_WIDTH * (1 << GW) : MAX_WIDTH + 1;

  generate
    `SM_BAD_PARAM(g_bad_disp, DISP < `SM_DISP_MIN || DISP > `SM_DISP_MAX || DISP % 2 != 0,
                  ("sm_dp: DISP (%0d) must be even, %0d..%0d", DISP, `SM_DISP_MIN, `SM_DISP_MAX))
    `SM_BAD_PARAM(g_bad_cw, CW < 1 || CW > 8, ("sm_dp: CW (%0d) must be 1..8", CW))
    `SM_BAD_PARAM(g_bad_width, S + P + 1 > MAX_WIDTH,
                  ("sm_dp: MAX_WIDTH (%0d) must be at least DISP/2 + 3", MAX_WIDTH))
    `SM_BAD_PARAM(g_bad_ring, RING_MIN < 2, ("sm_dp: RING_MIN (%0d) must be at least 2", RING_MIN))
    `SM_BAD_PARAM(g_bad_pu, PU < 2 || PU > DISP || DISP % PU != 0 || PU % 2 != 0,
                  ("sm_dp: PU (%0d) must be an even divisor of DISP (%0d)", PU, DISP))
  endgenerate

  // ---- beat position -----------------------------------------------------------
  wire [XW-1:0] x_in;
  wire [`SM_SIDE_W-1:0] c_side;
  wire [XW-1:0] c_x;
  wire [0:0]    row_ok;
  wire [0:0]    col_ok;
  sm_win_ctrl #(
      .MAX_WIDTH(MAX_WIDTH),
      .D_ROWS   (2),
      .D_COLS   (S + P),
      .R_UP     (0),
      .R_DN     (0),
      .R_L      (0),
      .R_R      (0)
  ) u_win (
      .clk   (clk),
      .rst_n (rst_n),
      .ce    (ce),
      .width (width),
      .s_side(s_side),
      .s_x   (x_in),
      .c_side(c_side),
      .c_x   (c_x),
      .row_ok(row_ok),
      .col_ok(col_ok)
  );

  /* verilator lint_off WIDTH */  // small constants truncated to the column width
  localparam [XW-1:0] S_M1 = S - 1;
  localparam [XW-1:0] S_0 = S;
  localparam [XW-1:0] S_P1 = S + 1;
  localparam [XW-1:0] S_P2 = S + 2;
  /* verilator lint_on WIDTH */
  // forward DP clock of this ce, and the pixel the read-out emits on it
  wire          x_ge_s = (x_in >= S_0);  // the entering column is in this row's line
  wire [XW-1:0] t_f = x_ge_s ? x_in - S_0 : x_in + width - S_0;
  wire [XW-1:0] t_rev = width - 1'b1 - t_f;
  // Pixel the read-out emits: (x_in - S - 2) mod W. Counted instead of computed from
  // x_in: the modulo (compare, subtract, add) in front of the read-out's equality
  // compare and stack-address select made the longest register-to-register path. Lines
  // are exactly W beats with sol on beat 0 (sm_seq), so the count equals the formula:
  // at sol x_in = 0 gives W - S - 2, and it steps by one, wrapping after W - 1.
  reg  [XW-1:0] xo_q;       // x_out of the previous ce
  reg           xo_last_q;  // xo_q == W - 1
  wire [XW-1:0] x_out = s_side[`SM_SIDE_SOL] ? width - S_P2 : xo_last_q ? {XW{1'b0}} : xo_q + 1'b1;
  always @(posedge clk) begin
    if (ce) begin
      xo_q      <= x_out;
      xo_last_q <= (x_out == width - 1'b1);
    end
  end
  wire          line_end = (x_in == S_M1);  // forward clock W-1
  wire          step_last = (x_in == S_0);  // backward step of site pair 0
  wire          rd_start = (x_in == S_P1);
  // c_x/masks are not needed; t_rev's top bit is 0 (t < MAX_WIDTH)
  wire unused_win = &{c_x, row_ok, col_ok, t_rev};

  // ---- control: decision bank, per-frame occ and occ_edge -----------------------
  reg       fbank_q;     // the line's parity: the direction of its decision rows
  reg       rowfirst_q;  // the row entering is the first of a frame
  reg [7:0] occ_q;
  reg [7:0] occ_edge_q;
  // this ce latches the frame's penalties: the next ce starts the forward pass of this
  // row's line
  wire      occ_ld = ce && line_end && rowfirst_q;
  always @(posedge clk) begin
    if (!rst_n) begin
      fbank_q    <= 1'b0;
      rowfirst_q <= 1'b0;
      occ_q      <= 8'd0;
      occ_edge_q <= 8'd0;
    end else if (ce) begin
      if (line_end) fbank_q <= ~fbank_q;
      if (s_side[`SM_SIDE_SOL]) rowfirst_q <= s_side[`SM_SIDE_SOF];
      if (occ_ld) begin
        occ_q      <= occ;
        occ_edge_q <= occ_edge;
      end
    end
  end
  // The per-pair penalty registers below are loaded one clock before they are used, so
  // the frame's first line needs the values occ_q / occ_edge_q take on this edge
  // (occ_nx in g_par; the folded array's prefetch, occ_pf, assumes the ce).

  // Edge flags, one per beat: after the ce that samples column x (s_edge = e(x+1)),
  // fl_q[k] = e(x+1-k). DP clock t (column S+t entering) needs e(t+m+1) for pair m,
  // tap S-1-m counted from the entering column. Taps past a row's end see the next
  // row's beats, whose column 0 has flag 0: the model's p(W) = occ for the end node;
  // nodes with xl > W never reach it. A datapath register: no reset.
  reg  [S-1:0] fl_q;
  wire [S-1:0] fl_nx = {fl_q[S-2:0], s_edge};  // fl_q after this ce
  always @(posedge clk) begin
    if (ce) fl_q <= fl_nx;
  end

  // ---- shared by both branches --------------------------------------------------
  // wp: skew ring write pointer, one slot per beat.
  reg  [KW-1:0] wp_q;
  always @(posedge clk) begin
    if (!rst_n) wp_q <= {KW{1'b0}};
    else if (ce) wp_q <= wp_q + 1'b1;
  end

  wire [DEC_W-1:0]  dec;        // decision word of this DP clock (g_par) / sub-step (g_fold)
  wire              dec_we;
  wire [DEC_AW-1:0] dec_waddr;
  wire [DEC_W-1:0]  dec_wdata;
  wire              dec_re;
  wire [DEC_AW-1:0] dec_raddr;
  wire [DEC_W-1:0]  dec_rd;
  reg  [AW-1:0]     t_dec_q;    // t of dec_rd
  wire [GW-1:0]     d_grp;      // group of the trace's current level (g_fold)
  always @(posedge clk) begin
    if (ce) t_dec_q <= t_rev[AW-1:0];
  end

  // ---- decision rows: one bank, rewritten in place --------------------------------
  // The trace of line L-1 reads its word W-1-t on DP clock t of line L, so lines
  // alternate direction: with p the line's parity (fbank_q), word t sits in row t
  // (p = 0) or W - t (p = 1). On clock t line L writes row t | W - t and reads line
  // L-1's word W-1-t from row t + 1 | W - 1 - t: never the row it writes, and each row
  // is read on the clock before it is rewritten. Word 0 alternates between rows 0 and
  // W (g_par: MAX_WIDTH + 1 rows; folded, word 0 waits in a side store instead, and
  // rows stay below MAX_WIDTH). Rows from x_in with the direction folded into an XOR
  // and the constants (c - x = ~x + c + 1), kept in registers that follow fbank_q's
  // next value (width changes only between frames, while the pipeline is flushed):
  //   write: p = 0: t = x - S | x + W - S;  p = 1: W - t = W + S - x | S - x
  //   read:  p = 0: t + 1 = x + 1 - S | x + W + 1 - S;
  //          p = 1: W - 1 - t = W + S - 1 - x | S - 1 - x   (x >= S | x < S)
  /* verilator lint_off WIDTH */  // constants modulo 2^RAW; rows are at most MAX_WIDTH
  localparam [RAW-1:0] R_S = S;
  localparam [RAW-1:0] R_SP1 = S + 1;
  localparam [RAW-1:0] R_1MS = 1 - S;
  wire [RAW-1:0] width_r = width;
  /* verilator lint_on WIDTH */
  wire [RAW-1:0] x_r = x_in;  // (XW = RAW: both count to MAX_WIDTH)
  wire           fbank_nx = rst_n && (fbank_q ^ (ce && line_end));  // fbank_q next
  reg  [RAW-1:0] wa_q, wb_q, ra_q, rb_q;  // write / read constants for x >= S, x < S
  always @(posedge clk) begin
    wa_q <= fbank_nx ? width_r + R_SP1 : -R_S;
    wb_q <= fbank_nx ? R_SP1 : width_r - R_S;
    ra_q <= fbank_nx ? width_r + R_S : R_1MS;
    rb_q <= fbank_nx ? R_S : width_r + R_1MS;
  end
  wire [RAW-1:0] x_dir = x_r ^ {RAW{fbank_q}};
  wire [RAW-1:0] w_row = x_dir + (x_ge_s ? wa_q : wb_q);
  wire [RAW-1:0] r_row = x_dir + (x_ge_s ? ra_q : rb_q);

  generate
    if (F == 1) begin : g_par
      // ---- today's fully parallel array: DISP PEs, one DP clock per ce -----------
      // Skew rings: one write pointer, one read pointer per skew length k.
      // rp of length k is kept equal to wp - k (mod 2^KW) by counting alongside wp, so every
      // ring address comes straight from flip-flops (no subtractor in front of the RAM).
      // Both PEs of a length share its pointer. Every ring of depth 2^RW <= 2^KW uses the
      // pointers' low RW bits.
      wire [(S+1)*KW-1:0] rps;  // read pointer of skew length k at [k*KW +: KW]
      genvar k;
      for (k = 0; k <= S; k = k + 1) begin : g_rp
        if (k >= RING_MIN) begin : g_ring
          /* verilator lint_off WIDTH */  // -k modulo 2^KW
          localparam [KW-1:0] RP0 = (1 << KW) - k;
          /* verilator lint_on WIDTH */
          reg [KW-1:0] rp_q;
          always @(posedge clk) begin
            if (!rst_n) rp_q <= RP0;
            else if (ce) rp_q <= rp_q + 1'b1;
          end
          assign rps[k*KW +: KW] = rp_q;
        end else begin : g_shift
          assign rps[k*KW +: KW] = {KW{1'b0}};  // shift-register skew: unused
        end
      end

      // ---- per-pair penalties ----------------------------------------------------
      // Registered on the ce before the DP clock that uses them: on the ce of column x
      // the next DP clock is that of column x+1, whose pair m needs tap S-1-m of
      // fl_nx (tap 0 = s_edge, the flag of x+1 itself). Levels 2m and 2m+1 share it.
      wire [8*S-1:0] pens;  // penalty of pair m at [8*m +: 8]
      wire [7:0] occ_nx = occ_ld ? occ : occ_q;
      wire [7:0] occ_edge_nx = occ_ld ? occ_edge : occ_edge_q;
      genvar m;
      for (m = 0; m < S; m = m + 1) begin : g_pen
        reg [7:0] pen_q;
        always @(posedge clk) begin
          if (ce) pen_q <= fl_nx[S-1-m] ? occ_edge_nx : occ_nx;
        end
        assign pens[8*m +: 8] = pen_q;
      end
      wire unused_fl = fl_q[S-1];  // tap S-1 is fl_q[S-2] after the shift

      // ---- the array -------------------------------------------------------------
      wire [(DISP+2)*ACC_W-1:0] nbx;  // nb of level d at (d+1)*ACC_W, zero pads at both ends
      assign nbx[ACC_W-1:0] = {ACC_W{1'b0}};
      assign nbx[(DISP+1)*ACC_W +: ACC_W] = {ACC_W{1'b0}};
      genvar d;
      for (d = 0; d < DISP; d = d + 1) begin : g_pe
        sm_dp_pe #(
            .CW    (CW),
            .ACC_W (ACC_W),
            .ODD   (d % 2),
            .HAS_LO(d > 0 ? 1 : 0),
            .HAS_HI(d < DISP - 1 ? 1 : 0),
            .IS_D0 (d == 0 ? 1 : 0),
            .DELAY (S - (d + 1) / 2),
            .RING  (S - (d + 1) / 2 >= RING_MIN ? 1 : 0),
            .KW    (KW)
        ) u_pe (
            .clk  (clk),
            .ce   (ce),
            .init (line_end),
            .occ  (pens[8*(d/2) +: 8]),
            .cost (s_cost[d*CW +: CW]),
            .wp   (wp_q),
            .ra   (rps[(S-(d+1)/2)*KW +: KW]),
            .nb_lo(nbx[d*ACC_W +: ACC_W]),
            .nb_hi(nbx[(d+2)*ACC_W +: ACC_W]),
            .nb   (nbx[(d+1)*ACC_W +: ACC_W]),
            .dec  (dec[2*d +: 2])
        );
      end

      // ---- decisions: written by the forward pass, read back mirrored ------------
      assign dec_we    = ce;
      assign dec_waddr = w_row;
      assign dec_wdata = dec;
      assign dec_re    = ce;
      assign dec_raddr = r_row;
      wire unused_grp = &d_grp;  // one group
    end else begin : g_fold
      // ---- folded array: PU lanes, sub-steps g = 0..F-1 per DP clock ---------------
      localparam GD = 1 << GW;  // state words per lane
      localparam RD = KW + GW;  // ring address {beat slot, group}
      /* verilator lint_off WIDTH */  // constants truncated to the counter widths
      localparam [GW-1:0] G_LAST = F - 1;
      localparam [KW-1:0] SL_STEP = PU / 2;  // skew shrinks by PU/2 beats per group
      /* verilator lint_on WIDTH */
      localparam [ACC_W-1:0] BIG = {1'b1, {(ACC_W - 1) {1'b0}}};

      // Sub-step counter: run_q = sub-step g_q executes on this clock edge.
      wire [GW-1:0] g_q;
      wire          run_q;
      wire          fs_start, fs_step;
      sm_fold_step #(.F(F)) u_step (
          .clk(clk), .rst_n(rst_n), .ce(ce), .m_start(fs_start), .m_step(fs_step), .m_run(run_q), .m_g(g_q)
      );
      wire unused_fs = fs_step;

      // The held beat's costs of group g_q (one F:1 selection of PU*CW bits).
      wire [PU*CW-1:0] cost_g = s_cost[g_q*(PU*CW) +: PU*CW];

      // Ring read slots, one per ceil(j/2) = k: wp - (S - g*PU/2 - k), counted (reset:
      // wp = 0, sub-step 0). The lanes read the ring a clock ahead, like their state
      // words (a_q below), so they take the slot the counter takes next (slots_nx).
      wire [(PU/2+1)*KW-1:0] slots_nx;
      genvar k;
      for (k = 0; k <= PU / 2; k = k + 1) begin : g_slot
        /* verilator lint_off WIDTH */  // -S + k (+ 1) modulo 2^KW
        localparam [KW-1:0] SL_RST = (1 << KW) + k - S;
        localparam [KW-1:0] SL_CE = (1 << KW) + 1 + k - S;  // wp is wp_q + 1 after a ce
        /* verilator lint_on WIDTH */
        reg  [KW-1:0] sl_q;
        wire [KW-1:0] sl_nx = !rst_n ? SL_RST : ce ? wp_q + SL_CE : run_q ? sl_q + SL_STEP : sl_q;
        always @(posedge clk) sl_q <= sl_nx;
        assign slots_nx[k*KW +: KW] = sl_nx;
      end

      // Skew ring write port, shared by the lanes. For F > 2 it is registered (the rings
      // are written a clock late): the held input's F:1 select then ends at a register
      // instead of at every lane's ring (placed and routed at zynq, g_q through that select
      // into the rings' write was the block's slowest path). A word so written is read
      // no sooner than the next beat's sub-step of its group, prefetched a clock ahead:
      // F - 2 clocks after the late write at the least (the next ce comes F clocks after
      // the last one or later). At F = 2 that is the clock of the late write itself, so
      // there the rings are written directly.
      wire             ring_we;
      wire [RD-1:0]    ring_wa;
      wire [PU*CW-1:0] ring_wd;
      if (F == 2) begin : g_ring_now
        assign ring_we = run_q;
        assign ring_wa = {wp_q, g_q};
        assign ring_wd = cost_g;
      end else begin : g_ring_late
        reg              rw_we_q;
        reg [RD-1:0]     rw_wa_q;
        reg [PU*CW-1:0]  rw_wd_q;
        always @(posedge clk) begin
          if (!rst_n) rw_we_q <= 1'b0;
          else rw_we_q <= run_q;
          rw_wa_q <= {wp_q, g_q};
          rw_wd_q <= cost_g;
        end
        assign ring_we = rw_we_q;
        assign ring_wa = rw_wa_q;
        assign ring_wd = rw_wd_q;
      end

      // ---- lanes -----------------------------------------------------------------
      // fresh_q: this beat is DP clock 0 of a line; the beat before (the line-end ce,
      // clock W-1 of the previous line) wrote U(2W, .), never needed, so its reads
      // give U(0, .) instead.
      reg fresh_q;
      always @(posedge clk) begin
        if (!rst_n) fresh_q <= 1'b0;
        else if (ce) fresh_q <= line_end;
      end
      // The lanes read their state words and skewed costs one clock ahead (below), for
      // the next sub-step g_nx: g_q + 1 while the beat's sub-steps run, else 0 (words
      // 0 .. g_q were written by sub-steps already done, and the word read is never the
      // one written on that edge). g_nx is a register of its own, without ce: by the
      // pacing rule a ce comes only when no sub-step but the last runs (sm_fold_step
      // reports any other in simulation), and a prefetch for sub-step 0 is used only if a
      // ce comes on its clock (sub-step 0 runs on the clock after one), so it assumes
      // one: the new line's start, the penalties it loads, the flags it shifts. ce is then
      // on no path into the lanes' registers (placed and routed at zynq, g_q and ce
      // through the select into the odd lanes' node was the block's slowest path).
      localparam [GW-1:0] G_ONE = 1;
      reg  [GW-1:0] g_nx_q;
      always @(posedge clk) begin
        if (fs_start) g_nx_q <= G_ONE;  // sub-step 0 runs next: prefetch 1 on its clock
        else if (g_nx_q == {GW{1'b0}} || g_nx_q == G_LAST) g_nx_q <= {GW{1'b0}};
        else g_nx_q <= g_nx_q + 1'b1;
      end
      wire [GW-1:0] g_nx = g_nx_q;
      wire          nx0 = (g_nx == {GW{1'b0}});  // the prefetch is for a ce's sub-step 0
      // line_end registered: the input (and so x_in) holds from the clock after a ce, and
      // the next ce comes at least F >= 2 clocks after that ce, so on a ce's clock le_q
      // equals line_end (x_in's increment and compare then end at a register)
      reg           le_q;
      always @(posedge clk) le_q <= line_end;
      wire          fresh_nx = nx0 ? le_q : fresh_q;
      wire          occ_ld_nx = nx0 && le_q && rowfirst_q;  // occ_ld, if the ce comes
      wire [7:0]    occ_pf = occ_ld_nx ? occ : occ_q;
      wire [7:0]    occ_edge_pf = occ_ld_nx ? occ_edge : occ_edge_q;

      // ---- per-lane-pair penalties --------------------------------------------------
      // Sub-step g of the beat on the input (column x, fl_q[k] = e(x-k) since the ce
      // before it) needs, for lanes 2k and 2k+1 (pair m = g*PU/2 + k), tap
      // S-1-g*PU/2-k of fl_q: an F:1 select, prefetched into a register one clock ahead
      // like the state words (g_nx above). The prefetch for sub-step 0 is for the next
      // beat, whose flags are fl_q shifted by the ce it assumes (tap - 1 of fl_q); on
      // idle clocks it is for nothing (the ce's clock reloads it). The odd lanes take the
      // select itself (pens_nx): their node is computed a clock ahead.
      wire [8*(PU/2)-1:0] pens_nx;  // penalty of lanes 2k, 2k+1 next sub-step, [8*k +: 8]
      wire [8*(PU/2)-1:0] pens;     // the same, registered: this sub-step's
      genvar g;
      for (k = 0; k < PU / 2; k = k + 1) begin : g_pen
        wire [GD-1:0] fsel;  // flag of the sub-step g at [g]
        for (g = 0; g < GD; g = g + 1) begin : g_tap
          if (g == 0) begin : g_first
            assign fsel[g] = fl_q[S-2-k];  // fl_q shifted by the ce it assumes
          end else if (g < F) begin : g_mid
            assign fsel[g] = fl_q[S-1-g*(PU/2)-k];
          end else begin : g_none
            assign fsel[g] = 1'b0;  // no such group (F not a power of two)
          end
        end
        wire [7:0] pen_nx = fsel[g_nx] ? occ_edge_pf : occ_pf;
        reg  [7:0] pen_q;
        always @(posedge clk) pen_q <= pen_nx;
        assign pens_nx[8*k +: 8] = pen_nx;
        assign pens[8*k +: 8]    = pen_q;
      end

      // The odd lanes' occlusion node (site 2t+1) reads only U(2t) of its own level and
      // of the two around it, all in the state memories before the sub-step starts, so it
      // is computed a clock ahead from the prefetch (sm_dp_fpe, NODE = 1, on u_nx) and
      // registered: a sub-step then runs one add-compare-select (the even lanes' node,
      // on the odd lanes' registered values) instead of two in series (placed and routed
      // at zynq, odd node then even node into the state memory was the block's slowest
      // path at every placer seed). At F = 2 lane PU-1's node still follows lane 0's on
      // the clock that bypasses it (up_byp).
      // u_nx: U(2t, g*PU+j) of the next sub-step at [j*ACC_W +: ACC_W], and above lane
      // PU-1 the bottom level of group g+1, not yet updated.
      wire [(PU+1)*ACC_W-1:0] u_nx;
      // ob: below even lane 2k (slot k) and above it (slot k+1), the site-2t+1 values of
      // the odd levels around it; slot 0 is the top of group g-1.
      wire [(PU/2+1)*ACC_W-1:0] ob;
      wire [2*PU-1:0]     f_dec;  // choice of lane j at [2j +: 2]
      reg  [ACC_W-1:0]    top_q;  // site-2t+1 value of level g*PU-1 (lane PU-1, g-1)
      reg  [1:0]          top_dec_q;
      genvar j;
      for (j = 0; j < PU; j = j + 1) begin : g_lane
        wire [ACC_W-1:0] u_next;
        // State: U(2t, g*PU+j) of every group; sub-step g reads and rewrites word g.
        (* ram_style = "distributed" *)
        reg  [ACC_W-1:0] um [0:GD-1];
        // The state words are prefetched one clock ahead (the even lanes into u_q, the odd
        // lanes through their node into o_q), so the longest path starts at a flip-flop
        // instead of a LUT-RAM read. The line start substitutes U(0, .) on the read side
        // (fresh_nx): a select in front of the register, not behind the last select
        // before the LUT-RAM's data input.
        wire [ACC_W-1:0] u0 = (j == 0 && nx0) ? {ACC_W{1'b0}} : BIG;
        always @(posedge clk) begin
          if (run_q) um[g_q] <= u_next;
        end
        assign u_nx[j*ACC_W +: ACC_W] = fresh_nx ? u0 : um[g_nx];
        if (j == 0) begin : g_up
          // (g = F-1: any word, unused: level DISP does not exist)
          // F = 2: the ce that ends sub-step 1 prefetches word 0 + 1, written on
          // that same edge: take the value being written.
          wire up_byp = (F == 2) && run_q && (g_q == g_nx + 1'b1);
          assign u_nx[PU*ACC_W +: ACC_W] = fresh_nx ? BIG : up_byp ? u_next : um[g_nx+1'b1];
        end
        // Cost skew: ring of CW-bit words {beat slot, group}.
        (* ram_style = "distributed" *)
        reg  [CW-1:0] ring [0:(1<<RD)-1];
        always @(posedge clk) begin
          if (ring_we) ring[ring_wa] <= ring_wd[j*CW +: CW];
        end
        // The skewed cost of the sub-step executing next, read a clock ahead (as u_q):
        // the ring's LUT-RAM read (and at the top lane the held input's F:1 choice) then
        // sits before a register, not in front of the lane's adders (placed and routed,
        // g_q through the read into the adders was the block's slowest path). The word
        // read is never the one written on that edge (another group), and the held
        // input is stable from the clock after the ce (the rule above).
        wire [CW-1:0] a_ring = ring[{slots_nx[((j+1)/2)*KW +: KW], g_nx}];
        reg  [CW-1:0] a_q;
        if (j == PU - 1) begin : g_top
          // level DISP-1 (g = F-1) has skew 0: the held input itself
          always @(posedge clk) begin
            a_q <= (g_nx == G_LAST) ? s_cost[G_LAST*(PU*CW) + j*CW +: CW] : a_ring;
          end
        end else begin : g_mid
          always @(posedge clk) a_q <= a_ring;
        end
        if (j % 2 == 1) begin : g_odd
          // site 2t+1: the occlusion node, a clock ahead; 2t+2: matched
          wire [ACC_W-1:0] o_nx;
          wire [1:0]       od_nx;
          wire [ACC_W-1:0] nb_unused;  // the node's value again (o_nx)
          sm_dp_fpe #(
              .CW   (CW),
              .ACC_W(ACC_W),
              .ODD  (1),
              .NODE (1)
          ) u_fpe (
              .u     (u_nx[j*ACC_W +: ACC_W]),
              .a     ({CW{1'b0}}),
              .occ   (pens_nx[8*(j/2) +: 8]),
              .has_lo(1'b1),
              .has_hi(j < PU - 1 ? 1'b1 : (g_nx != G_LAST)),
              .nb_lo (u_nx[(j-1)*ACC_W +: ACC_W]),
              .nb_hi (u_nx[(j+1)*ACC_W +: ACC_W]),
              .nb    (nb_unused),
              .u_next(o_nx),
              .dec   (od_nx)
          );
          wire unused_nb = ^nb_unused;
          reg [ACC_W-1:0] o_q;  // U(2t+1) of the sub-step executing
          reg [1:0]       od_q;
          always @(posedge clk) begin
            o_q  <= o_nx;
            od_q <= od_nx;
          end
          assign u_next = o_q + {{(ACC_W - CW) {1'b0}}, a_q};
          assign ob[((j+1)/2)*ACC_W +: ACC_W] = o_q;
          assign f_dec[2*j +: 2] = od_q;
        end else begin : g_even
          // site 2t+1 matched, 2t+2 the occlusion node on the odd lanes' o_q
          reg  [ACC_W-1:0] u_q;  // U(2t, g*PU+j) of the sub-step executing
          wire [ACC_W-1:0] nb_unused;  // U(2t): the odd lanes took it from u_nx
          always @(posedge clk) u_q <= u_nx[j*ACC_W +: ACC_W];
          sm_dp_fpe #(
              .CW   (CW),
              .ACC_W(ACC_W),
              .ODD  (0)
          ) u_fpe (
              .u     (u_q),
              .a     (a_q),
              .occ   (pens[8*(j/2) +: 8]),
              .has_lo(j > 0 ? 1'b1 : (g_q != {GW{1'b0}})),
              .has_hi(1'b1),
              .nb_lo (ob[(j/2)*ACC_W +: ACC_W]),
              .nb_hi (ob[(j/2+1)*ACC_W +: ACC_W]),
              .nb    (nb_unused),
              .u_next(u_next),
              .dec   (f_dec[2*j +: 2])
          );
          wire unused_nb = ^nb_unused;
        end
      end
      assign ob[ACC_W-1:0] = top_q;
      always @(posedge clk) begin
        if (run_q) begin
          top_q     <= ob[(PU/2)*ACC_W +: ACC_W];
          top_dec_q <= f_dec[2*PU-1 -: 2];
        end
      end

      // ---- decisions: {group, level g*PU-1} per sub-step, written a clock late ----
      // The trace reads its word on the clock after a ce; after the line-end ce that is
      // word (t = 0) of the line before, in row 0.
      assign dec = {f_dec, top_dec_q};
      reg              dw_we_q;
      reg [DEC_AW-1:0] dw_addr_q;
      reg [DEC_W-1:0]  dw_dec_q, dw_side_q;  // the sub-step's word; the side store's
      reg              dw_side_sel_q;        // word 0: the write takes the side store's
      reg              rd_pend_q;  // the clock after a ce: fetch the trace's word
      // One bank, rewritten in place (MAX_WIDTH rows of GD words; two banks cost vga 10
      // RAMB36 instead of 5). The trace of line L-1 reads its word W-1-t on the clock
      // after the ce of line L's clock t, and the sub-steps of line L's clock t run after
      // the ce of its clock t-1, so line L's word t (t >= 1) goes where line L-1's word
      // W-t was, read one beat earlier: lines alternate direction. With p the line's
      // parity (fbank_q), word t >= 1 of a line sits in row t (p = 0) or W - t (p = 1),
      // and word 0 in row 0. Row 0 still holds the previous line's word 0 while a line
      // computes its own (read last, after the line-end ce), so word 0 waits in a side
      // store of GD words and is copied into row 0 while the next line computes its word
      // 0 (into the side store): the read of row 0 comes on the clock after the line-end
      // ce, the copy's writes from the clock after that.
      // (rows: "decision rows" above; here below MAX_WIDTH, AW bits)
      if (RAW > AW) begin : g_unused_row_msb
        wire unused_row_msb = w_row[RAW-1] ^ r_row[RAW-1];
      end
      reg  [AW-1:0] r_row_q;  // row of the trace's word
      // word 0 of the line: into the side store, its predecessor out of it into row 0
      (* ram_style = "distributed" *)
      reg  [DEC_W-1:0] side [0:GD-1];
      always @(posedge clk) begin
        if (run_q && step_last) side[g_q] <= dec;
      end
      always @(posedge clk) begin
        if (!rst_n) begin
          dw_we_q   <= 1'b0;
          rd_pend_q <= 1'b0;
        end else begin
          dw_we_q   <= run_q;
          rd_pend_q <= ce;
        end
        dw_addr_q <= {step_last ? {AW{1'b0}} : w_row[AW-1:0], g_q};
        // both registered and selected behind the registers: a select in front of them
        // lengthened the lanes' longest path (7 -> 8 LUT levels at vga)
        dw_dec_q      <= dec;
        dw_side_q     <= side[g_q];
        dw_side_sel_q <= step_last;
        if (ce) r_row_q <= line_end ? {AW{1'b0}} : r_row[AW-1:0];
      end
      assign dec_we    = dw_we_q;
      assign dec_waddr = dw_addr_q;
      assign dec_wdata = dw_side_sel_q ? dw_side_q : dw_dec_q;
      assign dec_re    = rd_pend_q;
      assign dec_raddr = {r_row_q, d_grp};
    end
  endgenerate

  sm_sdp_ram #(
      .DATA_W(DEC_W),
      .DEPTH (DEC_DEPTH)
  ) u_dec (
      .clk  (clk),
      .we   (dec_we),
      .waddr(dec_waddr),
      .wdata(dec_wdata),
      .re   (dec_re),
      .raddr(dec_raddr),
      .rdata(dec_rd)
  );

  // ---- backward pass, fill, read-out --------------------------------------------
  wire [DW-1:0] disp_q;
  sm_dp_trace #(
      .MAX_WIDTH(MAX_WIDTH),
      .DISP     (DISP),
      .PU       (PU)
  ) u_trace (
      .clk      (clk),
      .rst_n    (rst_n),
      .ce       (ce),
      .dec_word (dec_rd),
      .t_dec    (t_dec_q),
      .step_last(step_last),
      .rd_start (rd_start),
      .x_out    (x_out),
      .d_grp    (d_grp),
      .disp_q   (disp_q),
      .matched_q(m_matched),
      .gap_q    (m_gap),
      .fill_bg_q(m_fill_bg)
  );
  assign m_disp = {1'b1, {(15 - DW) {1'b0}}, disp_q};

  always @(posedge clk) begin
    if (!rst_n) m_side <= {`SM_SIDE_W{1'b0}};
    else if (ce) m_side <= c_side;
  end
endmodule
`default_nettype wire
