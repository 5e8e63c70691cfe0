`default_nettype none
`include "sm_defs.vh"
// Backward pass and left-occlusion fill of the trellis DP (docs/algorithm.md,
// section 6). While the array runs the forward pass of line k+1, this block walks the
// decision words of line k from the end node (2W, 0) back to site 0, two sites per
// clock, and pushes every match it meets as {x, d, rmin} onto a stack in block RAM;
// the matches come out in descending x, so rmin, the least d of the matches pushed so
// far in the line (the least d at or right of this match), is a running minimum.
// During the following line time the stack is popped in ascending x while the pixels
// are emitted in raster order: a pixel that is the head's x gets the head's d (and is
// "matched"); any other pixel lies after the last emitted match A (if any) and before
// the head B (if any) and gets
//   disparity  min(d_A, d_B) (the left-occlusion fill), d_A after the last match, d_B
//              before the first, 0 when the line had no match;
//   gap        |d_B - d_A| (at most 253), 255 when A or B does not exist (run_gaps in
//              model/evidence.cpp, whose cap at 254 never acts while DISP <= 254);
//   fill_bg    min(d_A, every match right of A) = rmin_A, rmin_B before the first
//              match, 0 when the line had no match (fill_background).
// d_A and rmin_A are remembered when A is popped; min(d_A, d_B) and |d_B - d_A| share
// one compare of the head's d with d_A. (The fill used to be pushed as a third field;
// rmin took its place, so the word keeps its width: one more 7-bit field would cost half
// a RAMB36 at MAX_WIDTH 640.) The stack is double buffered (push line k+1, pop line k).
//
// Folded (PU < DISP, sm_dp g_fold): dec_word is the word of one level group g,
// {dec of levels g*PU .. g*PU+PU-1, dec of level g*PU-1}, read on the clock after a
// ce at the group d_grp of the level this block then holds. A backward step from level
// d of group g needs the choices of d and at most one neighbour, d - 1 (possibly
// g*PU-1, the word's low bits) or d + 1 (inside the group, PU even), so one word a
// beat suffices; the level is also kept as (group, index in the group) so that the
// word's bit select and the next group come from small registers without a modulo.
module sm_dp_trace #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter DISP      = 128,  // disparity levels
    parameter PU        = DISP  // levels per clock of the forward pass (sm_dp)
) (
    input  wire              clk,
    input  wire              rst_n,
    input  wire              ce,
    input  wire [DEC_W-1:0]  dec_word,   // decisions of site pair t_dec (dec[t][d] at 2d)
    input  wire [AW-1:0]     t_dec,      // t of dec_word
    input  wire              step_last,  // this ce is the last backward step of a line
    input  wire              rd_start,   // this ce fetches the head of the finished line
    input  wire [XW-1:0]     x_out,      // pixel emitted (registered) by this ce
    output wire [GW-1:0]     d_grp,      // group of the current level (folded)
    output reg  [DW-1:0]     disp_q,     // disparity of pixel x_out, after the ce
    output reg               matched_q,  // pixel x_out is a match (with disp_q)
    output reg  [7:0]        gap_q,      // gap of its unmatched run, 0 if matched
    output reg  [DW-1:0]     fill_bg_q   // its background fill, its d if matched
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam AW = $clog2(MAX_WIDTH);
  localparam DW = $clog2(DISP);
  localparam SW = AW + 2 * DW;  // stack word {x, d, rmin}
  localparam F = (PU > 0) ? DISP / PU : 1;  // forward clocks per beat
  localparam GW = (F > 1) ? $clog2(F) : 1;  // group index width
  localparam DEC_W = (F > 1) ? 2 * PU + 2 : 2 * DISP;  // decision word (sm_dp)
  localparam LW = (PU > 1) ? $clog2(PU) : 1;  // index inside a group

  generate
    `SM_BAD_PARAM(g_bad_disp, DISP < 4 || DISP > 254 || DISP % 2 != 0,
                  ("sm_dp_trace: DISP (%0d) must be even, 4..254 (8-bit gap)", DISP))
    `SM_BAD_PARAM(g_bad_pu, PU < 2 || PU > DISP || DISP % PU != 0 || PU % 2 != 0,
                  ("sm_dp_trace: PU (%0d) must be an even divisor of DISP (%0d)", PU, DISP))
  endgenerate

  // ---- backward walk -----------------------------------------------------------
  reg  [DW-1:0] d_q;  // level at site 2*t_dec+2 (the end node's 0 at a line start)

  // the level reached by following choice c from level d
  function [DW-1:0] follow(input [DW-1:0] d, input [1:0] c);
    follow = (c == 2'd1) ? d - 1'b1 : (c == 2'd2) ? d + 1'b1 : d;
  endfunction

  // Folded: index n (-2 .. PU+1) of the next level relative to the current group ->
  // {into group g-1, into group g+1, index inside the new group}.
  function [LW+1:0] step(input integer n);
    reg [LW-1:0] v;
    begin
      /* verilator lint_off WIDTH */  // n is in 0..PU-1 after the wrap
      if (n < 0) v = n + PU;
      else if (n >= PU) v = n - PU;
      else v = n;
      /* verilator lint_on WIDTH */
      step = {n < 0, n >= PU, v};
    end
  endfunction

  // Site 2t+2 is an occlusion node for even d, site 2t+1 for odd d; both take their
  // choice from the same word. A match happens at 2t+2 (odd d) or, after choice 0, at
  // 2t+1 (even d); either way its x is t + ceil(d/2) and at most one per clock.
  wire          match;
  wire [DW-1:0] d2;
  generate
    if (F == 1) begin : g_par
      wire          odd  = d_q[0];
      wire [1:0]    ch_a = dec_word[2*d_q +: 2];
      wire [DW-1:0] d1   = odd ? d_q : follow(d_q, ch_a);
      wire [1:0]    ch_b = dec_word[2*d1 +: 2];
      assign match = odd || (ch_a == 2'd0);
      assign d2    = match && !odd ? d1 : follow(d1, ch_b);
      assign d_grp = 1'b0;
    end else begin : g_fold
      // l_q: index of d_q in its group g_q; word entry i (bits 2i+1:2i) is level
      // g*PU + i - 1. For every index l the whole step -- match, level change -2..+2,
      // next index, group change -- is a function of the entries l .. l+2 only (the
      // parity of l is fixed): one LUT level. The current index selects one result
      // (PU:1), and the next level / group are picked from d_q - 2 .. d_q + 2 and
      // g_q - 1 .. g_q + 1, counted from the registers: no adder after the RAM.
      localparam RW = 6 + LW;  // {match, dsel[2:0], dn, up, l_next}
      reg  [LW-1:0]    l_q;
      reg  [GW-1:0]    g_q;
      // the word with one zero entry above it (entry PU+1, never a traced choice)
      wire [DEC_W+1:0] wx = {2'b00, dec_word};
      wire [PU*RW-1:0] res;
      genvar l;
      for (l = 0; l < PU; l = l + 1) begin : g_idx
        wire [1:0] cm = wx[2*l +: 2];      // level d - 1
        wire [1:0] c0 = wx[2*(l+1) +: 2];  // level d
        wire [1:0] cp = wx[2*(l+2) +: 2];  // level d + 1
        wire       ev = (l % 2 == 0);      // d even: site 2t+2 is its occlusion node
        wire       mt = !ev || (c0 == 2'd0);
        wire [1:0] cb = !ev ? c0 : (c0 == 2'd1) ? cm : cp;  // choice at site 2t+1
        // dsel = level change + 2: the first step (even d) -1 / 0 / +1, then cb's
        wire [2:0] d_a = (!ev || c0 == 2'd0) ? 3'd2 : (c0 == 2'd1) ? 3'd1 : 3'd3;
        wire [2:0] dsel = (ev && c0 == 2'd0) ? 3'd2 :
                          (cb == 2'd1) ? d_a - 1'b1 : (cb == 2'd2) ? d_a + 1'b1 : d_a;
        reg  [LW+1:0] nxt;  // {dn, up, l_next}
        always @(*) begin
          case (dsel)
            3'd0:    nxt = step(l - 2);
            3'd1:    nxt = step(l - 1);
            3'd3:    nxt = step(l + 1);
            3'd4:    nxt = step(l + 2);
            default: nxt = step(l);
          endcase
        end
        assign res[l*RW +: RW] = {mt, dsel, nxt};
      end
      wire [RW-1:0] r = res[l_q*RW +: RW];
      wire [2:0]    sel = r[LW+4:LW+2];
      wire          dn = r[LW+1];
      wire          up = r[LW];
      assign match = r[RW-1];
      localparam [DW-1:0] TWO = 2;
      assign d2 = (sel == 3'd0) ? d_q - TWO : (sel == 3'd1) ? d_q - 1'b1 :
                  (sel == 3'd3) ? d_q + 1'b1 : (sel == 3'd4) ? d_q + TWO : d_q;
      always @(posedge clk) begin
        if (!rst_n) begin
          l_q <= {LW{1'b0}};
          g_q <= {GW{1'b0}};
        end else if (ce) begin
          if (step_last) begin
            l_q <= {LW{1'b0}};  // level 0
            g_q <= {GW{1'b0}};
          end else begin
            l_q <= r[LW-1:0];
            g_q <= dn ? g_q - 1'b1 : up ? g_q + 1'b1 : g_q;
          end
        end
      end
      assign d_grp = g_q;
    end
  endgenerate
  wire [DW:0]   ceil_d = ({1'b0, d_q} + 1'b1) >> 1;
  /* verilator lint_off WIDTH */  // x = t + ceil(d/2) < MAX_WIDTH on a traced path: AW bits
  wire [AW-1:0] mx    = t_dec + ceil_d;
  /* verilator lint_on WIDTH */

  reg           wbank_q;  // stack half being pushed; the other one is popped
  reg  [XW-1:0] cnt_q;    // matches pushed so far in this line
  reg  [XW-1:0] m_q;      // matches of the line being popped
  reg           first_q;  // no match pushed yet in this line
  reg  [DW-1:0] rmin_q;   // least d pushed so far in this line (all right of d_q's match)
  wire [DW-1:0] rmin = (first_q || d_q < rmin_q) ? d_q : rmin_q;

  always @(posedge clk) begin
    if (!rst_n) begin
      d_q     <= {DW{1'b0}};
      wbank_q <= 1'b0;
      cnt_q   <= {XW{1'b0}};
      m_q     <= {XW{1'b0}};
      first_q <= 1'b1;
      rmin_q  <= {DW{1'b0}};
    end else if (ce) begin
      if (match) rmin_q <= rmin;
      if (step_last) begin
        d_q     <= {DW{1'b0}};
        wbank_q <= ~wbank_q;
        cnt_q   <= {XW{1'b0}};
        m_q     <= cnt_q + {{(XW - 1) {1'b0}}, match};
        first_q <= 1'b1;
      end else begin
        d_q     <= d2;
        cnt_q   <= cnt_q + {{(XW - 1) {1'b0}}, match};
        first_q <= first_q && !match;
      end
    end
  end

  // ---- the stack ---------------------------------------------------------------
  wire [SW-1:0] head;
  reg  [AW-1:0] ptr_q;  // stack index of the head
  reg  [AW-1:0] raddr;
  wire          rbank = ~wbank_q;

  sm_sdp_ram #(
      .DATA_W(SW),
      .DEPTH (1 << (AW + 1))
  ) u_stack (
      .clk  (clk),
      .we   (ce && match),
      .waddr({wbank_q, cnt_q[AW-1:0]}),
      .wdata({mx, d_q, rmin}),
      .re   (ce),
      .raddr({rbank, raddr}),
      .rdata(head)
  );

  // ---- raster read-out with the fill -------------------------------------------
  reg  [XW-1:0] rem_q;   // matches left including the head
  reg           any_q;   // a match of this line has been emitted
  reg  [DW-1:0] ld_q;    // d of the last emitted match (A)
  reg  [DW-1:0] rm_q;    // rmin of the last emitted match
  wire [AW-1:0] hx = head[SW-1 -: AW];
  wire [DW-1:0] hd = head[2*DW-1 -: DW];
  wire [DW-1:0] hr = head[DW-1:0];
  wire          have = (rem_q != {XW{1'b0}});
  wire [XW:0]   hx_w = {{(XW + 1 - AW) {1'b0}}, hx};  // XW may equal AW
  wire          consume = have && (hx_w == {1'b0, x_out});
  // d_B - d_A and d_A - d_B side by side (two short carry chains after the RAM, in
  // parallel with the x compare): the borrow of the first is d_B < d_A, which picks the
  // fill min(d_A, d_B) and the absolute difference (a 2:1 select each). 9 bits: DW may be 8.
  wire [DW:0]   dba = {1'b0, hd} - {1'b0, ld_q};
  wire [DW-1:0] dab = ld_q - hd;
  wire          b_lo = dba[DW];
  wire [DW-1:0] fill = (have && b_lo) ? hd : ld_q;  // fill after A: min(d_A, d_B), or d_A
  // |d_B - d_A| <= DISP - 1 <= 253 (the DISP check above): the model's cap at 254 never
  // acts, so the gap is the difference itself.
  wire [DW-1:0] adiff = b_lo ? dab : dba[DW-1:0];
  /* verilator lint_off WIDTH */  // the difference zero-extended to the gap's 8 bits
  wire [7:0]    run_gap = adiff;
  /* verilator lint_on WIDTH */
  wire [DW-1:0] out_d = consume ? hd : any_q ? fill : have ? hd : {DW{1'b0}};
  wire [7:0]    out_gap = consume ? 8'd0 : (any_q && have) ? run_gap : 8'd255;
  wire [DW-1:0] out_bg = consume ? hd : any_q ? rm_q : have ? hr : {DW{1'b0}};

  always @(*) begin
    if (rd_start) raddr = m_q[AW-1:0] - 1'b1;
    else if (consume) raddr = ptr_q - 1'b1;
    else raddr = ptr_q;
  end

  always @(posedge clk) begin
    if (!rst_n) begin
      ptr_q     <= {AW{1'b0}};
      rem_q     <= {XW{1'b0}};
      any_q     <= 1'b0;
      ld_q      <= {DW{1'b0}};
      rm_q      <= {DW{1'b0}};
      disp_q    <= {DW{1'b0}};
      matched_q <= 1'b0;
      gap_q     <= 8'd0;
      fill_bg_q <= {DW{1'b0}};
    end else if (ce) begin
      disp_q    <= out_d;
      matched_q <= consume;
      gap_q     <= out_gap;
      fill_bg_q <= out_bg;
      ptr_q     <= raddr;
      if (rd_start) begin
        rem_q <= m_q;
        any_q <= 1'b0;
      end else if (consume) begin
        rem_q  <= rem_q - 1'b1;
        any_q  <= 1'b1;
        ld_q   <= hd;
        rm_q   <= hr;
      end
    end
  end
endmodule
`default_nettype wire
