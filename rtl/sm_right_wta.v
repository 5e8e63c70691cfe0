`default_nettype none
`include "sm_defs.vh"
// Right-view winner-take-all (docs/algorithm.md section 9.0, field lr; model right_wta):
// for every right pixel xr of a line, the lowest level k of least A(xr + k, k) over the
// levels with xr + k < W, from the aggregated costs as they stream into the DP.
//
// Column x offers A(x, k) to right pixel x - k, so right pixel xr takes its offers from
// the columns xr .. xr + DISP - 1 of its own line, one level per column, in level order.
// One running (cost, level) entry per beat in flight, R[k] for the beat that entered k
// ce's before the one entering (right pixel x - k), takes them on the way:
//   R'[0] = (A(x, 0), 0)
//   R'[k] = A(x, k) < cost(R[k-1]) && v(R[k-1]) && !sol ? (A(x, k), k) : R[k-1]
// A tie keeps the entry: its level is lower (the offers come in level order). v marks the
// entries of the row entering: set on R'[0], cleared in all by a row start, so
// v(R'[k]) = (k <= x). The offers with k > x go to right pixels left of the image (the
// model ignores them) and are masked; the entries of earlier rows move on untouched, so
// neither another line, a virtual row nor another frame leaks into a line. After the
// update R'[DISP-1] has every offer of its pixel: the DISP - 1 columns after it have
// entered, or its line ended before them and the rest were masked.
//
// Latency: DISP - 1 beats at every PU and width: m_lr and m_side after the ce of beat n
// are those of beat n - (DISP - 1) (the level of R'[DISP-1], registered on that ce). The
// sideband waits in a ring of DISP - 1 slots (LUT-RAM, not reset) read and rewritten on
// every ce; m_side stays 0 after reset until the ring has been filled once (a reset flag),
// so no stale real beat leaves. The block needs no line width: rows are seen by their sol,
// so any width 1..MAX_WIDTH works, also below DISP - 1 (the beat leaving then belongs to a
// row several rows back); ceil((DISP - 1) / W) virtual rows flush a frame's last line.
// `width` is one of the common stage ports and is not read.
//
// Logic depth: one CW-bit compare (a subtraction's borrow, on the carry chain) and a
// select per level and clock.
//
// Folded (PU < DISP, F = DISP/PU clocks per beat, branch g_fold): PU lanes; lane j keeps
// the entries R[g*PU + j] of the F level groups g in a LUT-RAM (word g). Relies on the
// input-stability rule (docs/algorithm.md, "Folded datapath"): from the clock after ce
// n up to ce n + 1 the inputs hold the beat ce n + 1 samples, so its update runs as
// sub-steps on the F clocks after ce n, group g = F-1 first down to group 0 (the last
// may fall on ce n + 1 itself); a sub-step rewrites word g of every lane in place. Lane
// j > 0 reads word g of lane j - 1 (the old entry: written on the same edge) and lane 0
// reads word g - 1 of lane PU - 1, which group g - 1 rewrites only on a later clock: the
// group order makes the in-place shift exact. The first sub-step (group F - 1) yields
// R'[DISP-1]; its level waits in a register for the ce, so m_lr and m_side change only
// on ce, with the latency above. Per clock: the F:1 select of the held costs, the
// LUT-RAM read, one compare and a select.
// After reset the first beat's sub-steps start at once, so its ce must come at least F
// clocks after rst_n rises (sm_top: the first beats are not real anyway).
module sm_right_wta #(
    parameter MAX_WIDTH = 320,  // widest active line (sizes the width port only)
    parameter DISP      = 128,  // disparity levels 0..DISP-1 (even, 4..254)
    parameter CW        = 6,    // aggregated cost width
    // Disparity levels updated per clock: DISP (one beat per clock) or an even divisor
    // of DISP (F = DISP/PU clocks per beat, ce at most every F clocks), as sm_dp's.
    parameter PU        = DISP
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [XW-1:0]         width,   // active width (not needed: rows end at sol)
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [DISP*CW-1:0]    s_cost,  // A(x, k) at [k*CW +: CW]
    output reg  [`SM_SIDE_W-1:0] m_side,  // sideband of right pixel xr (DISP - 1 beats back)
    output reg  [DW-1:0]         m_lr     // the right-view WTA level of xr
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam DW = $clog2(DISP);
  localparam EW = 1 + CW + DW;  // entry {v, cost, level}
  localparam L = DISP - 1;      // latency in beats, and the sideband ring's slots
  localparam PW = $clog2(L);    // ring pointer
  localparam F = (PU > 0) ? DISP / PU : 1;  // clocks per beat
  localparam GW = (F > 1) ? $clog2(F) : 1;  // group index width

  generate
    `SM_BAD_PARAM(g_bad_disp, DISP < `SM_DISP_MIN || DISP > `SM_DISP_MAX || DISP % 2 != 0,
                  ("sm_right_wta: DISP (%0d) must be even, %0d..%0d", DISP, `SM_DISP_MIN, `SM_DISP_MAX))
    `SM_BAD_PARAM(g_bad_cw, CW < 1 || CW > 8, ("sm_right_wta: CW (%0d) must be 1..8", CW))
    `SM_BAD_PARAM(g_bad_width, MAX_WIDTH < 1, ("sm_right_wta: MAX_WIDTH (%0d) must be at least 1", MAX_WIDTH))
    `SM_BAD_PARAM(g_bad_pu, PU < 2 || PU > DISP || DISP % PU != 0 || PU % 2 != 0,
                  ("sm_right_wta: PU (%0d) must be an even divisor of DISP (%0d)", PU, DISP))
  endgenerate

  wire unused_width = &width;
  wire sol = s_side[`SM_SIDE_SOL];

  // ---- sideband: DISP - 1 beats through a ring ------------------------------------
  /* verilator lint_off WIDTH */  // the last slot, truncated to the pointer width
  localparam [PW-1:0] P_LAST = L - 1;
  /* verilator lint_on WIDTH */
  (* ram_style = "distributed" *)
  reg [`SM_SIDE_W-1:0] ring [0:L-1];
  reg [PW-1:0] rp_q;    // slot of the beat entering: it holds the beat of L ce's ago
  reg          full_q;  // every slot written since reset
  always @(posedge clk) begin
    if (ce) ring[rp_q] <= s_side;
  end
  always @(posedge clk) begin
    if (!rst_n) begin
      rp_q   <= {PW{1'b0}};
      full_q <= 1'b0;
      m_side <= {`SM_SIDE_W{1'b0}};
    end else if (ce) begin
      rp_q   <= (rp_q == P_LAST) ? {PW{1'b0}} : rp_q + 1'b1;
      if (rp_q == P_LAST) full_q <= 1'b1;
      m_side <= full_q ? ring[rp_q] : {`SM_SIDE_W{1'b0}};
    end
  end

  generate
    if (F == 1) begin : g_par
      // ---- one beat per clock: R'[k] from R[k-1] for every level ------------------
      // Entries 0..DISP-2 are kept; R'[DISP-1] only gives m_lr. Datapath: no reset
      // (the entries of the beats before the first sol after reset never leave as real).
      reg  [(DISP-1)*EW-1:0] r_q;  // R[k] at [k*EW +: EW]
      wire [DISP*EW-1:0]     nx;   // R'[k] at [k*EW +: EW]
      genvar k;
      for (k = 0; k < DISP; k = k + 1) begin : g_lvl
        wire [CW-1:0] a = s_cost[k*CW +: CW];
        if (k == 0) begin : g_first
          assign nx[0 +: EW] = {1'b1, a, {DW{1'b0}}};
        end else begin : g_next
          /* verilator lint_off WIDTH */  // the level, truncated to DW bits
          localparam [DW-1:0] LV = k;
          /* verilator lint_on WIDTH */
          wire [EW-1:0] p = r_q[(k-1)*EW +: EW];
          wire          pv = p[EW-1] && !sol;
          wire [CW:0]   df = {1'b0, a} - {1'b0, p[DW +: CW]};  // borrow: a < cost
          wire          take = pv && df[CW];
          assign nx[k*EW +: EW] = {pv, take ? a : p[DW +: CW], take ? LV : p[DW-1:0]};
        end
      end
      always @(posedge clk) begin
        if (ce) begin
          r_q  <= nx[(DISP-1)*EW-1:0];
          m_lr <= nx[(DISP-1)*EW +: DW];
        end
      end
      wire unused_top = &nx[DISP*EW-1 : (DISP-1)*EW+DW];  // v and cost of R'[DISP-1]
    end else begin : g_fold
      // ---- folded: PU lanes, groups g = F-1 .. 0 on the F clocks after a ce --------
      localparam GD = 1 << GW;  // state words per lane
      /* verilator lint_off WIDTH */  // constants truncated to the counter widths
      localparam [GW-1:0] G_LAST = F - 1;
      localparam [GW-1:0] GM_LAST = F - 2;
      localparam [DW-1:0] KB_LAST = DISP - PU;  // first level of group F-1
      localparam [DW-1:0] KB_STEP = PU;
      /* verilator lint_on WIDTH */

      // Sub-step counter: run_q = the sub-step of group g_q executes on this clock
      // edge (g_q = F-1 down to 0). gm_q = g_q - 1 and kb_q = g_q * PU are counted beside
      // it, so the LUT-RAM addresses and the lanes' levels come from flip-flops.
      wire [GW-1:0] g_q;
      wire          run_q, fs_start, fs_step;
      sm_fold_step #(.F(F), .DOWN(1)) u_step (
          .clk(clk), .rst_n(rst_n), .ce(ce), .m_start(fs_start), .m_step(fs_step), .m_run(run_q), .m_g(g_q)
      );
      reg [GW-1:0] gm_q;
      reg [DW-1:0] kb_q;
      always @(posedge clk) begin
        if (fs_start) begin
          gm_q <= GM_LAST;
          kb_q <= KB_LAST;
        end else if (fs_step) begin
          gm_q <= gm_q - 1'b1;
          kb_q <= kb_q - KB_STEP;
        end
      end

      wire [PU*EW-1:0] rd;      // word g_q of lane j at [j*EW +: EW] (before this edge)
      wire [EW-1:0]    top_rd;  // word g_q - 1 of lane PU-1: R[g_q*PU - 1], not yet updated
      wire [PU*EW-1:0] nw;      // R'[g_q*PU + j] at [j*EW +: EW]
      genvar j;
      for (j = 0; j < PU; j = j + 1) begin : g_lane
        (* ram_style = "distributed" *)
        reg [EW-1:0] mem [0:GD-1];
        always @(posedge clk) begin
          if (run_q) mem[g_q] <= nw[j*EW +: EW];
        end
        assign rd[j*EW +: EW] = mem[g_q];
        if (j == PU - 1) begin : g_top
          assign top_rd = mem[gm_q];
        end

        /* verilator lint_off WIDTH */  // the lane offset, truncated to DW bits
        localparam [DW-1:0] J = j;
        /* verilator lint_on WIDTH */
        // A(x, g_q*PU + j) of the held beat: per bit an F:1 select by g_q (Yosys maps a
        // part-select at g_q*PU*CW as a shifter: 1,226 LUTs instead of 878 at DISP 128, PU 8).
        wire [CW-1:0] a;
        genvar b, g;
        for (b = 0; b < CW; b = b + 1) begin : g_abit
          wire [GD-1:0] col;  // bit b of the level's cost in group g at [g]
          for (g = 0; g < GD; g = g + 1) begin : g_grp
            if (g < F) begin : g_in
              assign col[g] = s_cost[(g*PU+j)*CW+b];
            end else begin : g_none
              assign col[g] = 1'b0;  // no such group (F not a power of two)
            end
          end
          assign a[b] = col[g_q];
        end
        wire [EW-1:0] p = (j == 0) ? top_rd : rd[(j-1)*EW +: EW];
        wire          pv = p[EW-1] && !sol;
        wire [CW:0]   df = {1'b0, a} - {1'b0, p[DW +: CW]};  // borrow: a < cost
        wire          take = pv && df[CW];
        wire [DW-1:0] lv = kb_q + J;
        wire          first = (j == 0) && (g_q == {GW{1'b0}});  // R'[0]
        assign nw[j*EW +: EW] = first ? {1'b1, a, {DW{1'b0}}}
                                      : {pv, take ? a : p[DW +: CW], take ? lv : p[DW-1:0]};
      end
      wire unused_rd = &rd[PU*EW-1 : (PU-1)*EW];  // lane PU-1's word g_q: no lane above

      // R'[DISP-1] comes from lane PU-1 in the first sub-step, never on a ce (F > 1).
      reg [DW-1:0] lr_nx_q;
      always @(posedge clk) begin
        if (run_q && g_q == G_LAST) lr_nx_q <= nw[(PU-1)*EW +: DW];
        if (ce) m_lr <= lr_nx_q;
      end
    end
  endgenerate
endmodule
`default_nettype wire
