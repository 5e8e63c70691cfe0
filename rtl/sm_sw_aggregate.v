`default_nettype none
`include "sm_defs.vh"
// Adaptive support-weight cost aggregation (docs/algorithm.md, section 5).
//
// Every cost level of every pixel in the SW x SW window is weighted by a power of two
// (0, 1, 2 or 4) chosen from the left-image intensity difference to the centre, summed,
// and normalised by the reciprocal of the weight sum. The weights, their sum and the
// reciprocal depend only on the pixel, so they are computed once per beat and shared by
// all DISP levels. The costs travel in bit-plane order (bit b of all levels together),
// so the weighted sums of all levels are one bit heap (sm_bitheap) whose every stage
// is a few operations on DISP-bit vectors; per level there remain one adder and one
// multiplier (sm_sw_level).
//
// Pipeline, counted in ce from the one on which beat (x+R, y+R) enters (ce 0); the
// output of pixel (x, y) is on m_side/m_agg after ce 4 (latency 5 beats after the
// window delay of R rows and R columns; `SM_AGG_PIPE_BEATS, which sm_top's edge-flag
// delay and the block test use):
//   ce 0  line-buffer read of the entering column; window-controller masks registered;
//         sw_table latched when the centre is sof
//   ce 1  column into the window (a circular buffer of SW columns, sm_colwin); weight
//         codes of the window being formed registered
//   ce 2  A_raw of every level: weighted cost bits (a choice among three planes), the
//         bit heap, per level the sum of its two rows; weight sum and RECIP(weight sum)
//         from the ROM, once per pixel
//   ce 3  per level: A_raw * RECIP
//   ce 4  per level: round, shift by 12, saturate to CW bits (the output register)
//
// Resources: the window of SW x SW x DISP costs is the block's largest state. It lives
// in LUT-RAM (sm_colwin), written once per beat and read at SW addresses, instead of
// SW x SW x DISP x CW shifting flip-flops. A_raw is the only per-level register before
// the multiplier.
//
// Folded datapath (PU < DISP, F = DISP / PU clocks per beat; PU = DISP is the parallel
// datapath above, unchanged): the aggregation of a level does not depend on the other
// levels, so the window, bit heap and levels exist for PU levels and run over the F
// level groups of a beat in F consecutive steps (group g = levels g*PU .. g*PU+PU-1).
// It relies on sm_top's ce pacing (after a ce, ce stays low for F - 1 clocks; checked
// in simulation) and on the "register at ce, compute on the following clocks" rule:
// everything registered on a ce (the live costs and pixel, the line buffer of pixels,
// the masks, the sideband) is as above, and the F steps of the beat entering on ce 0
// run on the F clocks after it, with those registers, whatever comes next. The pixel
// part (codes, weight sum, RECIP) stays once per beat; the codes are registered on the
// second clock after ce 0 and RECIP on the one after that, and both hold for the F steps.
// Step g of the beat of ce 0 (clock c0 + 1 + g):
//   clock c0+1+g  line-buffer read of word {column, g} (sm_sw_foldlb: one word per
//                 column and group, SW-1 rows of PU levels); group g of the live costs
//   clock c0+2+g  the group's column (live row + SW-1 rows) written back to the line
//                 buffer and registered (col_q: the block RAM's data ends its path here)
//   clock c0+3+g  col_q into the window (sm_sw_foldwin: LUT-RAM at {slot, g}); the
//                 window's SW-1 previous columns of group g read from it; bit heap of
//                 PU lanes; per level A_raw
//   c0+4+g .. c0+6+g  sm_sw_level (multiply, round and saturate into its register)
//   end of c0+6+g the group's results into the output ring (sm_sw_foldout), read on
//                 ce 4 into m_agg (the last group is written by clock c0 + F + 5, before
//                 ce 4, which comes 4 * F clocks after ce 0 at the earliest, F >= 2)
// So the latency is the same as above: pixel (x, y) on m_side/m_agg after ce 4.
module sm_sw_aggregate #(
    parameter MAX_WIDTH  = 320,  // widest active line
    parameter DISP       = 128,  // disparity levels
    parameter CENSUS     = 15,   // census window side: sets the raw cost width
    parameter SW         = 5,    // support-weight window side (odd, 3..7)
    parameter COST_SHIFT = 2,    // raw Hamming cost >> COST_SHIFT before aggregation
    parameter PU         = DISP  // levels computed per clock: a divisor of DISP
) (
    input  wire                 clk,
    input  wire                 rst_n,
    input  wire                 ce,
    input  wire [XW-1:0]        width,     // active width
    input  wire [63:0]          sw_table,  // code of |dI| >> 3 = k at [2k +: 2]
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [CW*DISP-1:0]   s_cost,    // C = cost >> COST_SHIFT (sm_cost), bit b of level d at [b*DISP + d]
    input  wire [7:0]           s_left,    // left rectified pixel of the same beat
    output wire [`SM_SIDE_W-1:0] m_side,
    output wire [DISP*CW-1:0]   m_agg      // aggregated cost of level d at [d*CW +: CW]
);
  localparam XW    = `SM_COUNT_W(MAX_WIDTH);
  localparam CB    = CENSUS * CENSUS - 1;           // census bits = largest raw cost
  localparam CMAX  = CB >> COST_SHIFT;              // largest shifted cost
  localparam CW    = $clog2(CMAX + 1);              // shifted / aggregated cost width
  localparam R     = (SW - 1) / 2;                  // window radius
  localparam NQ    = SW * SW;                       // window positions
  localparam WMAX  = 4 * NQ;                        // largest weight sum
  localparam SUMW  = $clog2(WMAX + 1);              // weight sum width
  localparam RW    = 13;                            // RECIP width: RECIP(1) = 4096
  localparam LVW   = DISP * CW;                     // shifted costs of one pixel
  localparam LBW   = LVW + 8;                       // line-buffer word per row: costs, pixel
  localparam COLW  = SW * LVW;                      // costs of one window column
  localparam F     = (PU >= 1) ? DISP / PU : 1;     // clocks (steps) per beat
  localparam FGW   = (F > 1) ? $clog2(F) : 1;       // step / group index
  localparam GW    = PU * CW;                       // shifted costs of one group
  localparam COLG  = SW * GW;                       // one group of one window column
  localparam LAW   = $clog2(MAX_WIDTH);             // column address (columns < MAX_WIDTH)

  generate
    `SM_BAD_PARAM(g_bad_sw, SW < `SM_SW_MIN || SW > `SM_SW_MAX || SW % 2 == 0,
                  ("sm_sw_aggregate: SW (%0d) must be odd, %0d..%0d", SW, `SM_SW_MIN, `SM_SW_MAX))
    `SM_BAD_PARAM(g_bad_census, CENSUS < `SM_CENSUS_MIN || CENSUS > `SM_CENSUS_MAX || CENSUS % 2 == 0,
                  ("sm_sw_aggregate: CENSUS (%0d) must be odd, %0d..%0d", CENSUS, `SM_CENSUS_MIN, `SM_CENSUS_MAX))
    `SM_BAD_PARAM(g_bad_shift, CMAX < 1,
                  ("sm_sw_aggregate: COST_SHIFT (%0d) leaves no cost bits", COST_SHIFT))
    `SM_BAD_PARAM(g_bad_disp, DISP < 1, ("sm_sw_aggregate: DISP (%0d) must be at least 1", DISP))
    `SM_BAD_PARAM(g_bad_pu, PU < 1 || PU > DISP || DISP % PU != 0,
                  ("sm_sw_aggregate: PU (%0d) must divide DISP (%0d)", PU, DISP))
  endgenerate

  // ---------------------------------------------------------------- ce 0: entry
  wire [XW-1:0]   s_x;
  wire [`SM_SIDE_W-1:0] c_side;
  wire [XW-1:0]   unused_c_x;
  wire [2*R:0]    row_ok, col_ok;
  sm_win_ctrl #(
      .MAX_WIDTH(MAX_WIDTH), .D_ROWS(R), .D_COLS(R),
      .R_UP(R), .R_DN(R), .R_L(R), .R_R(R)
  ) u_win (
      .clk(clk), .rst_n(rst_n), .ce(ce), .width(width), .s_side(s_side),
      .s_x(s_x), .c_side(c_side), .c_x(unused_c_x), .row_ok(row_ok), .col_ok(col_ok)
  );

  // The costs arrive and are kept in bit-plane order (plane b holds bit b of every
  // level, at [b*DISP +: DISP]): the weighted sums are then one bit heap for all levels
  // (below). They arrive shifted (sm_cost drops the low COST_SHIFT planes).
  wire [LVW-1:0] cost_in = s_cost;
  genvar d, k, c;

  // Live row of the entering column, beside the line buffer's rows: the line buffer's
  // own register of its input (g_par: costs and pixel; g_fold: the pixel's buffer, and
  // a register for the costs, whose buffer is written by steps).
  wire [LVW-1:0] live_cost;
  wire [7:0]     live_pix;
  reg [2*R:0]   row_ok_q, col_ok_q;
  reg [63:0]    table_q;      // weight codes of the frame whose pixels are centred now

  always @(posedge clk) begin
    if (ce) begin
      row_ok_q    <= row_ok;
      col_ok_q    <= col_ok;
      // The codes of the sof centre are formed on the next ce, after this latch.
      if (c_side[`SM_SIDE_SOF]) table_q <= sw_table;
    end
  end

  // ---------------------------------------------------------------- ce 1: window
  // Column c of the window is offset i = R - c from the centre (column 0 entered last),
  // row k is offset j = R - k (row 0 is the live row). The left pixels of the entering
  // column come from the line buffer of the datapath (g_par: pixels beside the costs;
  // g_fold: a line buffer of pixels alone).
  wire [SW*8-1:0] col_pix;
  assign col_pix[0 +: 8] = live_pix;

  // Left pixels of columns 0..SW-2 only: the oldest column is needed just once, for the
  // weights computed while the window forms.
  reg [(SW-1)*SW*8-1:0] pwin_q;  // column c at [c*SW*8 +: SW*8]

  // The weights are needed together with the window's costs, so they are computed from
  // the window as it forms on this ce: the entering column plus columns 0..SW-2.
  wire [NQ*8-1:0] pform = {pwin_q, col_pix};
  wire [7:0]      centre = pform[(R*SW + R)*8 +: 8];
  wire [NQ*2-1:0] code;  // code of row k, column c at [(k*SW + c)*2 +: 2]
  generate
    for (k = 0; k < SW; k = k + 1) begin : g_wrow
      for (c = 0; c < SW; c = c + 1) begin : g_wcol
        wire [7:0] pix  = pform[(c*SW + k)*8 +: 8];
        wire [7:0] diff = (pix > centre) ? pix - centre : centre - pix;
        // |dI| >> 3 of an 8-bit difference never exceeds 31: the min() is free.
        wire [4:0] kidx = diff[7:3];
        wire [2:0] unused_diff = diff[2:0];
        wire       in_img = row_ok_q[2*R-k] & col_ok_q[2*R-c];
        assign code[(k*SW + c)*2 +: 2] = in_img ? table_q[{kidx, 1'b0} +: 2] : 2'd0;
      end
    end
  endgenerate

  // The codes and RECIP are registered on ce (g_par) or on the first and second clock
  // after it (g_fold: they hold for the F steps, which start on the clock after ce).
  wire           code_en, recip_en;
  reg [NQ*2-1:0] code_q;
  always @(posedge clk) begin
    if (ce) pwin_q <= pform[(SW-1)*SW*8-1:0];
    if (code_en) code_q <= code;
  end

  // ---------------------------------------------------------------- ce 2..5: levels
  // Weight sum and its reciprocal, once per pixel (ce 2).
  wire [NQ*3-1:0] wts;  // one-hot weight 4, 2, 1 (code 3, 2, 1) of position q at [3q +: 3]
  generate
    for (k = 0; k < NQ; k = k + 1) begin : g_wt
      wire [1:0] cd = code_q[k*2 +: 2];
      assign wts[k*3 +: 3] = {cd == 2'd3, cd == 2'd2, cd == 2'd1};
    end
  endgenerate
  wire [SUMW-1:0] wsum;
  sm_sw_addtree #(.N(NQ), .IW(3), .OW(SUMW)) u_wsum (.terms(wts), .sum(wsum));

  // RECIP(s) = floor((4096 + floor(s/2)) / s), RECIP(0) = 0: a ROM filled at
  // elaboration, read through its register. In LUTs the ROM would put four more levels
  // behind the weight-sum tree; as a block RAM (half a RAMB36) its address is the end
  // of the path.
  (* ram_style = "block" *)
  reg [RW-1:0] recip_rom [0:WMAX];
  integer s;
  integer recip_unused_hi;  // RECIP <= 4096: only its low RW bits are stored
  initial begin
    recip_rom[0] = {RW{1'b0}};
    for (s = 1; s <= WMAX; s = s + 1) begin
      recip_unused_hi = (4096 + s / 2) / s;
      recip_rom[s]    = recip_unused_hi[RW-1:0];
    end
  end

  reg [RW-1:0] recip_q;
  always @(posedge clk) begin
    if (recip_en) recip_q <= recip_rom[wsum];
  end

  // A_raw of every level as one bit heap (sm_bitheap), all levels side by side: the
  // weighted cost of position q is its cost shifted by 0, 1 or 2 (weight 1, 2, 4) or 0,
  // so bit g of it is cost plane g, g-1 or g-2 of that position, chosen by the code
  // (one LUT per bit, as the product's shift-and-mask was). Column g of the heap holds
  // bit g of the NQ weighted costs (g = 0 .. CW+1; A_raw < 2^AW, so the heap has AW
  // columns). The heap leaves two rows; each level adds its two AW-bit numbers on a
  // carry chain (sm_sw_level). Against one adder tree per level: about the same LUTs,
  // one LUT level per counter stage instead of an adder per tree level.
  localparam AW = $clog2(4 * NQ * ((1 << CW) - 1) + 1);  // A_raw width, as sm_sw_level
  localparam TP = CW + 2;                     // bit planes of one weighted cost
  /* verilator coverage_off */  // a constant function: runs at elaboration only
  function [32*AW-1:0] term_heights(input integer nq);
    integer j;
    begin
      term_heights = {32 * AW{1'b0}};
      for (j = 0; j < TP && j < AW; j = j + 1) term_heights[j*32 +: 32] = nq;
    end
  endfunction
  /* verilator coverage_on */
  localparam [32*AW-1:0] H0 = term_heights(NQ);

  genvar gi, pl;
  generate
    if (F == 1) begin : g_par
      // ------------------------------------------------ all DISP levels in one clock
      assign code_en  = ce;
      assign recip_en = ce;

      wire [(SW-1)*LBW-1:0] lb_dout;  // rows live-1 .. live-(SW-1) of the entering column
      sm_linebuf #(.MAX_WIDTH(MAX_WIDTH), .DATA_W(LBW), .ROWS(SW - 1)) u_lb (
          .clk(clk), .ce(ce), .col(s_x), .din({s_left, cost_in}), .dout(lb_dout),
          .live({live_pix, live_cost})
      );

      wire [COLW-1:0] col_cost;
      assign col_cost[0 +: LVW] = live_cost;
      for (k = 1; k < SW; k = k + 1) begin : g_col
        assign col_cost[k*LVW +: LVW] = lb_dout[(k-1)*LBW +: LVW];
        assign col_pix[k*8 +: 8]      = lb_dout[(k-1)*LBW + LVW +: 8];
      end

      // Cost window: column c entered c + 1 ce ago, all SW columns in LUT-RAM (sm_colwin).
      wire [SW*COLW-1:0] cwin;  // column c at [c*COLW +: COLW]
      sm_colwin #(.W(COLW), .N(SW)) u_cwin (
          .clk(clk), .rst_n(rst_n), .ce(ce), .col(col_cost), .win(cwin)
      );

      // Bit g of position q's weighted cost at [(g*NQ + q)*DISP +: DISP] (sm_sw_terms).
      wire [TP*NQ*DISP-1:0] terms;
      sm_sw_terms #(.L(DISP), .CW(CW), .SW(SW)) u_terms (.code(code_q), .win(cwin), .terms(terms));

      wire [AW*DISP-1:0] row_a, row_b;  // bit-plane order
      /* verilator coverage_off */  // lint sink: the rows are added in sm_sw_level
      wire unused_sum;
      /* verilator coverage_on */
      sm_bitheap #(.NC(AW), .H0(H0), .L(DISP), .REG(0)) u_heap (
          .clk(clk), .ce(ce), .bits(terms), .row_a(row_a), .row_b(row_b), .sum(unused_sum));
      // split_var: each level reads its own variables, not a slice of one long vector
      wire [DISP*AW-1:0] lane_a  /*verilator split_var*/;  // level order
      wire [DISP*AW-1:0] lane_b  /*verilator split_var*/;
      sm_plane2lane #(.P(AW), .L(DISP)) u_ta (.planes(row_a), .lanes(lane_a));
      sm_plane2lane #(.P(AW), .L(DISP)) u_tb (.planes(row_b), .lanes(lane_b));

      for (d = 0; d < DISP; d = d + 1) begin : g_lvl
        sm_sw_level #(.CW(CW), .SW(SW), .RW(RW)) u_lvl (
            .clk(clk), .ce(ce), .row_a(lane_a[d*AW +: AW]), .row_b(lane_b[d*AW +: AW]),
            .recip(recip_q), .agg(m_agg[d*CW +: CW]));
      end
    end else begin : g_fold
      // ------------------------------------------------ PU levels per clock, F steps
      // Step control: a ce starts the F steps of its beat on the next F clocks.
      /* verilator lint_off WIDTH */  // small constant truncated to the index width
      localparam [FGW-1:0] GLAST = F - 1;
      /* verilator lint_on WIDTH */
      reg           act0_q;   // a step: group grp0_q of the beat of the last ce
      reg [FGW-1:0] grp0_q;
      reg           ce1_q, ce2_q, ce3_q;  // the first / second / third clock after a ce
      always @(posedge clk) begin
        if (!rst_n) begin
          act0_q <= 1'b0;
          grp0_q <= {FGW{1'b0}};
          ce1_q  <= 1'b0;
          ce2_q  <= 1'b0;
          ce3_q  <= 1'b0;
        end else begin
          ce1_q <= ce;
          ce2_q <= ce1_q;
          ce3_q <= ce2_q;
          if (ce) begin
            act0_q <= 1'b1;
            grp0_q <= {FGW{1'b0}};
          end else if (act0_q) begin
            act0_q <= grp0_q != GLAST;
            grp0_q <= (grp0_q == GLAST) ? {FGW{1'b0}} : grp0_q + 1'b1;
          end
        end
      end
      assign code_en  = ce2_q;
      assign recip_en = ce3_q;

`ifndef SYNTHESIS
      // sm_top's pacing: after a ce, the next F - 1 clocks have ce low.
      always @(posedge clk) begin
        if (rst_n && ce && act0_q && grp0_q != GLAST)
          $error("sm_sw_aggregate: ce during step %0d of %0d (PU %0d)", grp0_q, F, PU);
      end
`endif

      // Left pixels: a line buffer of their own, on ce as in g_par.
      wire [(SW-1)*8-1:0] lbp_dout;
      sm_linebuf #(.MAX_WIDTH(MAX_WIDTH), .DATA_W(8), .ROWS(SW - 1)) u_lbp (
          .clk(clk), .ce(ce), .col(s_x), .din(s_left), .dout(lbp_dout), .live(live_pix)
      );
      reg [LVW-1:0] live_cost_q;
      always @(posedge clk) if (ce) live_cost_q <= cost_in;
      assign live_cost = live_cost_q;
      for (k = 1; k < SW; k = k + 1) begin : g_colp
        assign col_pix[k*8 +: 8] = lbp_dout[(k-1)*8 +: 8];
      end

      reg [LAW-1:0] x_q;  // column of the beat whose steps run
      always @(posedge clk) begin
        if (ce) x_q <= s_x[LAW-1:0];
      end
      if (XW > LAW) begin : g_unused_xmsb
        wire unused_xmsb = s_x[XW-1];  // columns are below MAX_WIDTH
      end

      // Group g of the live costs (planes of its PU levels) at [g*GW +: GW]: an F:1
      // choice of PU * CW bits, cheaper than rotating all DISP * CW of them.
      wire [LVW-1:0] live_gm;
      for (gi = 0; gi < F; gi = gi + 1) begin : g_lgrp
        for (pl = 0; pl < CW; pl = pl + 1) begin : g_lpl
          assign live_gm[gi*GW + pl*PU +: PU] = live_cost[pl*DISP + gi*PU +: PU];
        end
      end
      reg [GW-1:0] live_sel;
      integer si;
      always @* begin
        live_sel = live_gm[0 +: GW];
        for (si = 1; si < F; si = si + 1)
          if (grp0_q == si[FGW-1:0]) live_sel = live_gm[si*GW +: GW];
      end

      // Cost rows: one block-RAM word per (column, group), at {column, group}, so the
      // addresses run to MAX_WIDTH x 2^FGW (exactly MAX_WIDTH x F when F is a power of
      // two); sm_sw_foldlb keeps that depth in two power-of-two banks (5,120 words at
      // 320 columns and 16 groups: 4,096 + 1,024, not 8,192).
      wire [COLG-1:0] col_g;  // the step's group of the entering column, row k at [k*GW]
      sm_sw_foldlb #(.DEPTH(MAX_WIDTH << FGW), .DATA_W(GW), .ROWS(SW - 1)) u_lbc (
          .clk(clk), .rst_n(rst_n), .en(act0_q), .addr({x_q, grp0_q}), .din(live_sel),
          .col(col_g)
      );

      // Steps through the datapath: 1 the line buffer's word into col_q, 2 window and
      // heap, 3..5 sm_sw_level, 5 result.
      reg [5:1]     act_q;
      reg [FGW-1:0] grp_q [1:5];
      always @(posedge clk) begin
        if (!rst_n) act_q <= 5'd0;
        else act_q <= {act_q[4:1], act0_q};
      end
      always @(posedge clk) begin
        grp_q[1] <= grp0_q;
        grp_q[2] <= grp_q[1];
        grp_q[3] <= grp_q[2];
        grp_q[4] <= grp_q[3];
        grp_q[5] <= grp_q[4];
      end

      // The block RAM's data (clock to output 5.8 ns on ECP5, then the choice of bank)
      // would otherwise start the heap's path: placed and routed, that path set the
      // block's clock (docs/synthesis.md). The steps have the clocks to spare.
      reg [COLG-1:0] col_q;
      always @(posedge clk) begin
        if (act_q[1]) col_q <= col_g;
      end

      // Window: the entering column's group from the line buffer, the SW-1 previous
      // columns' from LUT-RAM at {slot, group}.
      wire [(SW-1)*COLG-1:0] owin;
      sm_sw_foldwin #(.W(COLG), .N(SW - 1), .F(F)) u_fwin (
          .clk(clk), .rst_n(rst_n), .en(act_q[2]), .col(col_q), .win(owin)
      );
      wire [SW*COLG-1:0] cwin = {owin, col_q};  // column c at [c*COLG +: COLG]

      // The weighted cost bits of the PU levels of the step's group (sm_sw_terms, as g_par).
      wire [TP*NQ*PU-1:0] terms;
      sm_sw_terms #(.L(PU), .CW(CW), .SW(SW)) u_terms (.code(code_q), .win(cwin), .terms(terms));

      wire [AW*PU-1:0] row_a, row_b;  // bit-plane order
      /* verilator coverage_off */  // lint sink: the rows are added in sm_sw_level
      wire unused_sum;
      /* verilator coverage_on */
      sm_bitheap #(.NC(AW), .H0(H0), .L(PU), .REG(0)) u_heap (
          .clk(clk), .ce(ce), .bits(terms), .row_a(row_a), .row_b(row_b), .sum(unused_sum));
      wire [PU*AW-1:0] lane_a  /*verilator split_var*/;  // level order
      wire [PU*AW-1:0] lane_b  /*verilator split_var*/;
      sm_plane2lane #(.P(AW), .L(PU)) u_ta (.planes(row_a), .lanes(lane_a));
      sm_plane2lane #(.P(AW), .L(PU)) u_tb (.planes(row_b), .lanes(lane_b));

      // The levels run every clock (a pipeline of three registers); RECIP holds for the
      // F steps of its beat.
      wire [GW-1:0] agg_g;  // level l of the group at [l*CW +: CW]
      for (d = 0; d < PU; d = d + 1) begin : g_lvl
        sm_sw_level #(.CW(CW), .SW(SW), .RW(RW)) u_lvl (
            .clk(clk), .ce(1'b1), .row_a(lane_a[d*AW +: AW]), .row_b(lane_b[d*AW +: AW]),
            .recip(recip_q), .agg(agg_g[d*CW +: CW]));
      end

      // Results: group g of the beat of ce 0 leaves sm_sw_level on clock c0 + 6 + g;
      // ring slots until ce 4 presents the beat.
      sm_sw_foldout #(.W(GW), .F(F), .DELAY(4)) u_out (
          .clk(clk), .rst_n(rst_n), .ce(ce), .en(act_q[5]), .grp(grp_q[5]), .din(agg_g),
          .dout(m_agg)
      );
    end
  endgenerate

  sm_side_delay #(.DEPTH(`SM_AGG_PIPE_BEATS)) u_side (.clk(clk), .rst_n(rst_n), .ce(ce), .d(c_side), .q(m_side));
endmodule
`default_nettype wire
