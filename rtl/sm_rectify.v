`default_nettype none
`include "sm_defs.vh"
// Grid-based rectification of one camera (docs/algorithm.md, section 2).
//
// Output pixel (x, y) leaves while input (x, y + RECT_RADIUS + 1) enters (sm_win_ctrl
// with D_ROWS = RECT_RADIUS + 1, D_COLS = 0), so rows y-R..y+R of the frame are in the
// n-line buffer. The buffer holds 2R+2 row slots: the live row and the 2R+1 window rows.
// It is split into four banks by row-slot parity and column parity; the four bilinear
// taps (ix|ix+1, iy|iy+1) always fall into four different banks, so one read per bank
// per beat fetches them all.
//
// Pipeline (ce's after the entering beat): 0 grid read, 1 the grid words registered, 2
// V0/V1 (only the first pixel of a 16-pixel segment loads them), 3 S accumulated across
// the segment, 4 source position, tap validity and buffer rows/columns, 5 buffer
// addresses (from registers, straight into the read port) and read, 6 the four taps
// registered, 7 bilinear blend into m_pix. Stages 1 and 6 keep the block RAMs' data
// (5.8 ns after the clock on ECP5) off the multipliers' paths: placed and routed, each
// was the block's slowest in turn (docs/synthesis.md). The buffer write of an entering
// pixel is delayed to ce 5 as well, so the read of a beat sees every earlier row and
// none of the rows entering after it: the slot of row y-R is only overwritten by the
// row after the live one.
//
// Grid memory: point (gx, gy) of bank b is at grid_waddr = {b, gy[GYB-1:0], gx[GXB-1:0]},
// i.e. point index gy * GWMAX + gx with GWMAX = 2**GXB (docs/algorithm.md, section 2).
// The four corners of a grid cell lie in four different (gx, gy) parity banks.
module sm_rectify #(
    parameter MAX_WIDTH   = 320,  // widest active line
    parameter MAX_HEIGHT  = 240,  // tallest active frame
    parameter RECT_RADIUS = 15    // rows above/below the output row the source may use
) (
    input  wire           clk,
    input  wire           rst_n,
    input  wire           ce,
    input  wire [XW-1:0]  width,       // active width, 16..MAX_WIDTH
    input  wire           enable,      // 0: pass pixels through (latched at output sof)
    input  wire           grid_bank,   // grid bank to use (latched at output sof)
    input  wire           grid_we,     // grid write, independent of ce
    input  wire [GAW-1:0] grid_waddr,  // {bank, gy, gx}
    input  wire [31:0]    grid_wdata,  // {sy, sx}, signed Q.5
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [7:0]     s_pix,
    output wire [`SM_SIDE_W-1:0] m_side,
    output reg  [7:0]     m_pix
);
  localparam R      = RECT_RADIUS;
  localparam XW     = `SM_COUNT_W(MAX_WIDTH);
  localparam YW     = `SM_COUNT_W(MAX_HEIGHT);
  localparam NR     = 2 * R + 2;              // row slots of the line buffer
  localparam SB     = $clog2(NR);             // slot number bits
  localparam HALFW  = (MAX_WIDTH + 1) / 2;    // columns per column-parity bank row
  localparam CHW    = $clog2(HALFW);          // bits of a column pair index
  localparam BDEPTH = (R + 1) * HALFW;        // words per line-buffer bank
  localparam BAW    = $clog2(BDEPTH);
  localparam GXB    = `SM_GRID_AB(MAX_WIDTH);  // grid x bits, GWMAX = 2**GXB
  localparam GYB    = `SM_GRID_AB(MAX_HEIGHT);  // grid y bits
  localparam GAW    = 1 + GYB + GXB;          // grid_waddr width
  localparam GBW    = GAW - 2;                // address of one grid parity bank
  localparam VW     = 22;                     // V0/V1 (Q.9), |V| <= 2^19
  localparam SW     = 27;                     // S (Q.13), |S| <= 2^23
  localparam IW     = 14;                     // ix/iy, signed, |ix| <= 1024
  localparam DYW    = 16;                     // row offsets, signed
  localparam RW     = 2 * R + 1;              // window rows

  generate
    `SM_BAD_PARAM(g_bad_r, R < `SM_RECT_RADIUS_MIN || R > `SM_RECT_RADIUS_MAX,
                  ("sm_rectify: RECT_RADIUS (%0d) must be %0d..%0d", R, `SM_RECT_RADIUS_MIN, `SM_RECT_RADIUS_MAX))
    `SM_BAD_PARAM(g_bad_w, MAX_WIDTH < `SM_MAX_WIDTH_MIN || MAX_WIDTH > `SM_MAX_WIDTH_MAX,
                  ("sm_rectify: MAX_WIDTH (%0d) must be %0d..%0d", MAX_WIDTH, `SM_MAX_WIDTH_MIN, `SM_MAX_WIDTH_MAX))
    `SM_BAD_PARAM(g_bad_h, MAX_HEIGHT < `SM_MAX_HEIGHT_MIN || MAX_HEIGHT > `SM_MAX_HEIGHT_MAX,
                  ("sm_rectify: MAX_HEIGHT (%0d) must be %0d..%0d", MAX_HEIGHT, `SM_MAX_HEIGHT_MIN, `SM_MAX_HEIGHT_MAX))
  endgenerate

  // ---------------------------------------------------------------- stage 0 (entering)
  wire [XW-1:0] s_x;
  wire [`SM_SIDE_W-1:0] c_side;
  wire [XW-1:0] c_x;
  wire [RW-1:0] row_ok;
  /* verilator lint_off UNUSEDSIGNAL */  // no column window: taps test columns themselves
  wire          col_ok;
  /* verilator lint_on UNUSEDSIGNAL */

  sm_win_ctrl #(
      .MAX_WIDTH(MAX_WIDTH),
      .D_ROWS   (R + 1),
      .D_COLS   (0),
      .R_UP     (R),
      .R_DN     (R),
      .R_L      (0),
      .R_R      (0)
  ) u_win (
      .clk   (clk),
      .rst_n (rst_n),
      .ce    (ce),
      .width (width),
      .s_side(s_side),
      .s_x   (s_x),
      .c_side(c_side),
      .c_x   (c_x),
      .row_ok(row_ok),
      .col_ok(col_ok)
  );

  // Parameters overridden by a parent arrive as 32-bit integers; the truncation to the
  // sized constants below is intended (the values fit).
  /* verilator lint_off WIDTH */
  localparam [SB-1:0]  LAST_SLOT = NR - 1;
  localparam [SB-1:0]  HALF_NR   = R + 1;
  localparam [DYW-1:0] RD        = R;
  localparam [SB+1:0]  NRS       = NR;
  localparam [SB-2:0]  LAST_HS   = R;   // last slot pair
  localparam [BAW-1:0] HALFW_B   = HALFW;
  /* verilator lint_on WIDTH */

  // Row slot of the live row; the centre row is R+1 slots back, which modulo 2R+2 is
  // also R+1 slots ahead.
  reg  [SB-1:0] ls_q;
  wire [SB-1:0] ls = !s_side[`SM_SIDE_SOL] ? ls_q : (ls_q == LAST_SLOT) ? {SB{1'b0}} : ls_q + 1'b1;
  wire [SB-1:0] cs = (ls >= HALF_NR) ? ls - HALF_NR : ls + HALF_NR;

  // Centre row number and the frame's parameters, taken at the centre's sof.
  reg  [YW-1:0] cy_q;
  reg           bank_q, en_q;
  wire          c_sof = c_side[`SM_SIDE_SOF];
  wire [YW-1:0] cy = c_sof ? {YW{1'b0}} : c_side[`SM_SIDE_SOL] ? cy_q + 1'b1 : cy_q;
  wire          bank_f = c_sof ? grid_bank : bank_q;
  wire          en_f = c_sof ? enable : en_q;

  // Grid cell of the centre; c_x >> 4 and cy >> 4 fit GXB/GYB bits for in-frame pixels,
  // the bits cut off only matter on virtual rows.
  /* verilator lint_off WIDTH */
  wire [GXB-1:0] gx = c_x >> 4;
  wire [GYB-1:0] gy = cy >> 4;
  /* verilator lint_on WIDTH */
  wire [GXB-1:0] gx1 = gx + 1'b1;
  wire [GYB-1:0] gy1 = gy + 1'b1;

  // Grid parity banks, index {y parity, x parity}: each reads the cell corner with its
  // parities.
  wire [31:0] g_rd[0:3];
  genvar b;
  generate
    for (b = 0; b < 4; b = b + 1) begin : g_grid
      localparam PX = b & 1;
      localparam PY = b >> 1;
      wire [GXB-1:0] cx_b = (gx[0] == PX[0]) ? gx : gx1;
      wire [GYB-1:0] cy_b = (gy[0] == PY[0]) ? gy : gy1;
      wire           w_hit = (grid_waddr[0] == PX[0]) && (grid_waddr[GXB] == PY[0]);
      wire [GBW-1:0] waddr = {grid_waddr[GAW-1], grid_waddr[GAW-2:GXB+1], grid_waddr[GXB-1:1]};
      wire [GBW-1:0] raddr = {bank_f, cy_b[GYB-1:1], cx_b[GXB-1:1]};
      /* verilator lint_off UNUSEDSIGNAL */  // parity bit 0 is the bank itself
      wire           unused_par = cx_b[0] ^ cy_b[0];
      /* verilator lint_on UNUSEDSIGNAL */
      sm_sdp_ram #(
          .DATA_W(32),
          .DEPTH (1 << GBW)
      ) u_ram (
          .clk  (clk),
          .we   (grid_we && w_hit),
          .waddr(waddr),
          .wdata(grid_wdata),
          .re   (ce),
          .raddr(raddr),
          .rdata(g_rd[b])
      );
    end
  endgenerate

  // ---------------------------------------------------------------- stage 1: grid words
  // Everything stage 0 hands on waits here one ce beside the grid words.
  reg [31:0]   gr_q [0:3];
  reg [3:0]    fx_q0, fy_q0;
  reg          gxp_q0, gyp_q0, en_q0;
  reg [XW-1:0] cx_q0, wx_q0;
  reg [YW-1:0] cy_q0;
  reg [SB-1:0] cs_q0, wls_q0;
  reg [RW-1:0] rok_q0;
  reg [7:0]    wp_q0;
  integer gi;
  always @(posedge clk) begin
    if (ce) begin
      for (gi = 0; gi < 4; gi = gi + 1) gr_q[gi] <= g_rd[gi];
      fx_q0  <= c_x[3:0];
      fy_q0  <= cy[3:0];
      gxp_q0 <= gx[0];
      gyp_q0 <= gy[0];
      en_q0  <= en_f;
      cx_q0  <= c_x;
      cy_q0  <= cy;
      cs_q0  <= cs;
      rok_q0 <= row_ok;
      wp_q0  <= s_pix;
      wx_q0  <= s_x;
      wls_q0 <= ls;
    end
  end

  // ---------------------------------------------------------------- stage 2: V0/V1
  reg [3:0]    fx_q, fy_q;
  reg          gxp_q, gyp_q, en_q1;
  reg [XW-1:0] cx_q;
  reg [YW-1:0] cy_q1;
  reg [SB-1:0] cs_q;
  reg [RW-1:0] rok_q;

  wire [31:0] k00 = gr_q[{gyp_q, gxp_q}];
  wire [31:0] k10 = gr_q[{gyp_q, ~gxp_q}];
  wire [31:0] k01 = gr_q[{~gyp_q, gxp_q}];
  wire [31:0] k11 = gr_q[{~gyp_q, ~gxp_q}];

  // Products are taken modulo 2^VW: the true values fit, so the bits are the signed result.
  function [VW-1:0] sext16(input [15:0] v);
    sext16 = {{(VW - 16){v[15]}}, v};
  endfunction
  wire [VW-1:0] wy1 = {{(VW - 5){1'b0}}, 5'd16 - {1'b0, fy_q}};  // 16 - fy
  wire [VW-1:0] wy  = {{(VW - 4){1'b0}}, fy_q};
  wire [VW-1:0] v0x = sext16(k00[15:0]) * wy1 + sext16(k01[15:0]) * wy;
  wire [VW-1:0] v1x = sext16(k10[15:0]) * wy1 + sext16(k11[15:0]) * wy;
  wire [VW-1:0] v0y = sext16(k00[31:16]) * wy1 + sext16(k01[31:16]) * wy;
  wire [VW-1:0] v1y = sext16(k10[31:16]) * wy1 + sext16(k11[31:16]) * wy;

  // ---------------------------------------------------------------- stage 3: S
  reg [3:0]    fx_q2;
  reg          en_q2;
  reg [XW-1:0] cx_q2;
  reg [IW-1:0] ncy_q2;  // -cy
  reg [SB-1:0] cs_q2;
  reg [RW-1:0] rok_q2;
  reg [VW-1:0] v0x_q, v1x_q, v0y_q, v1y_q;  // of the current 16-pixel segment
  reg [SW-1:0] sx_acc_q, sy_acc_q;           // of the previous pixel, see below

  function [SW-1:0] sextv(input [VW-1:0] v);
    sextv = {{(SW - VW){v[VW-1]}}, v};
  endfunction
  // S(fx) = V0*(16-fx) + V1*fx = S(fx-1) + (V1 - V0), S(0) = 16*V0. The accumulators
  // carry the offsets stage 3 would otherwise add: the rounding (+256) and, for Y, the
  // centre row (-cy * 2^13, constant along a segment), so bits [26:13] are ix and iy - cy
  // (floor commutes with a multiple of 2^13); |S| <= 2^23 and cy < 2^12 keep them in
  // range. A disabled stage loads the pass-through position instead (ix = cx, iy = cy,
  // no fraction); en only changes at a frame's first pixel, where fx = 0 reloads.
  localparam [SW-1:0] RND = 27'd256;
  wire [SW-1:0] sx_n = (fx_q2 == 4'd0) ? (sextv(v0x_q) << 4) + RND
                                       : sx_acc_q + sextv(v1x_q) - sextv(v0x_q);
  wire [SW-1:0] sy_n = (fx_q2 == 4'd0) ? (sextv(v0y_q) << 4) + {ncy_q2, 13'd256}
                                       : sy_acc_q + sextv(v1y_q) - sextv(v0y_q);
  wire [SW-1:0] sx_s = en_q2 ? sx_n : {{(SW - 13 - XW){1'b0}}, cx_q2, 13'd0};
  wire [SW-1:0] sy_s = en_q2 ? sy_n : {SW{1'b0}};

  // ---------------------------------------------------------------- stage 4: taps
  reg [SB-1:0] cs_q3;
  reg [SB+1:0] csm_q3, csp_q3;  // cs - NR, cs + NR (signed)
  reg [RW-1:0] rok_q3;

  // Q.4 source position: ix, ax; row offset iy - cy and ay (accumulators above).
  wire [IW-1:0]  ix  = sx_acc_q[IW+12:13];
  wire [3:0]     ax  = sx_acc_q[12:9];
  wire [DYW-1:0] dy0 = {{(DYW - IW){sy_acc_q[IW+12]}}, sy_acc_q[IW+12:13]};
  wire [3:0]     ay  = sy_acc_q[12:9];
  /* verilator lint_off UNUSEDSIGNAL */  // the low bits are below the Q.4 step
  wire [8:0]     unused_acc = {sx_acc_q[8:0] ^ sy_acc_q[8:0]};
  /* verilator lint_on UNUSEDSIGNAL */

  // Columns: ix and ix+1 inside 0..width-1.
  wire [IW-1:0] ix1  = ix + 1'b1;
  wire [IW-1:0] wide_w = {{(IW - XW){1'b0}}, width};
  wire          c0ok = !ix[IW-1] && (ix < wide_w);
  wire          c1ok = !ix1[IW-1] && (ix1 < wide_w);

  // Rows: iy and iy+1 within R of the centre row and inside the frame (row_ok). Both
  // look rok up by dy0 itself (a DB-bit two's complement index; no add of R first).
  localparam DB = $clog2(R + 1) + 1;
  localparam integer RI = R;  // signed, whatever type an override gave R
  wire           in0 = ($signed(dy0) >= -$signed(RD)) && ($signed(dy0) <= $signed(RD));
  wire           in1 = ($signed(dy0) >= -$signed(RD) - 1) && ($signed(dy0) < $signed(RD));
  wire [(1 << DB) - 1:0] rok0, rok1;  // [k]: rows dy0 = k and dy0 + 1 = k + 1 (k signed)
  genvar k;
  generate
    for (k = 0; k < (1 << DB); k = k + 1) begin : g_rok
      localparam integer SK = (k < (1 << (DB - 1))) ? k : k - (1 << DB);
      if (SK >= -RI && SK <= RI) begin : g_in0
        assign rok0[k] = rok_q3[SK + RI];
      end else begin : g_out0
        assign rok0[k] = 1'b0;
      end
      if (SK + 1 >= -RI && SK + 1 <= RI) begin : g_in1
        assign rok1[k] = rok_q3[SK + 1 + RI];
      end else begin : g_out1
        assign rok1[k] = 1'b0;
      end
    end
  endgenerate
  wire           r0ok = in0 && rok0[dy0[DB-1:0]];
  wire           r1ok = in1 && rok1[dy0[DB-1:0]];

  // Slot of row iy (meaningful when r0ok or r1ok): cs + dy0 modulo NR, the three
  // candidates in parallel.
  wire [DYW-1:0] t0  = {{(DYW - SB){1'b0}}, cs_q3} + dy0;
  wire [DYW-1:0] t0m = {{(DYW - SB - 2){csm_q3[SB+1]}}, csm_q3} + dy0;
  wire [DYW-1:0] t0p = {{(DYW - SB - 2){csp_q3[SB+1]}}, csp_q3} + dy0;
  /* verilator lint_off UNUSEDSIGNAL */  // a wrapped slot fits SB bits
  wire [DYW-1:0] t0w = t0[DYW-1] ? t0p : !t0m[DYW-1] ? t0m : t0;
  /* verilator lint_on UNUSEDSIGNAL */
  wire [SB-1:0]  slot0 = t0w[SB-1:0];

  // Bank {row parity, column parity}: which tap it serves and where that tap is. Rows
  // iy, iy+1 (slots slot0, slot0+1 mod NR, NR even) and columns ix, ix+1 have opposite
  // parities; a bank word holds a slot pair (slot >> 1) and a column pair (col >> 1):
  // the odd one of each is slot0 >> 1 and ix >> 1, the even one (slot0 + 1) >> 1 (mod
  // R+1) and (ix + 1) >> 1.
  wire          rp = slot0[0];  // row parity of tap row iy
  wire          cp = ix[0];     // column parity of tap column ix
  wire [SB-2:0] hs0 = slot0[SB-1:1];
  wire [SB-2:0] hs_e = !rp ? hs0 : (hs0 == LAST_HS) ? {(SB-1){1'b0}} : hs0 + 1'b1;
  wire [SB-2:0] hs_o = hs0;
  wire [CHW-1:0] hc_e = ix1[CHW:1];
  wire [CHW-1:0] hc_o = ix[CHW:1];
  wire          rv_e = rp ? r1ok : r0ok;
  wire          rv_o = rp ? r0ok : r1ok;
  wire          cv_e = cp ? c1ok : c0ok;
  wire          cv_o = cp ? c0ok : c1ok;

  // Bank address of a written pixel (slot, col). Only col >> 1 addresses a bank; high
  // bits are zero for in-image columns. No valid input: its one use, the line-buffer
  // write, always addresses the entering pixel's own slot and column (taps outside the
  // image are masked in haddr).
  /* verilator lint_off UNUSEDSIGNAL */
  function [BAW-1:0] baddr(input [SB-1:0] slot, input [IW-1:0] col);
    /* verilator lint_off WIDTH */
    baddr = (slot >> 1) * HALFW_B + col[CHW:1];
    /* verilator lint_on WIDTH */
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */
  function [BAW-1:0] haddr(input [SB-2:0] hslot, input [CHW-1:0] hcol, input ok);
    /* verilator lint_off WIDTH */
    haddr = ok ? hslot * HALFW_B + hcol : {BAW{1'b0}};
    /* verilator lint_on WIDTH */
  endfunction

  wire [4:0] ax1 = 5'd16 - {1'b0, ax};
  wire [4:0] ay1 = 5'd16 - {1'b0, ay};

  // ---------------------------------------------------------------- stage 5: read
  reg [SB-2:0]  hs_e_q, hs_o_q;  // slot pairs of the even / odd tap row
  reg [CHW-1:0] hc_e_q, hc_o_q;  // column pairs of the even / odd tap column
  reg [3:0]     ok_q;            // bank reads that hit a valid tap
  wire [BAW-1:0] ra[0:3];
  assign ra[0] = haddr(hs_e_q, hc_e_q, ok_q[0]);  // bank {0,0}
  assign ra[1] = haddr(hs_e_q, hc_o_q, ok_q[1]);  // bank {0,1}
  assign ra[2] = haddr(hs_o_q, hc_e_q, ok_q[2]);  // bank {1,0}
  assign ra[3] = haddr(hs_o_q, hc_o_q, ok_q[3]);  // bank {1,1}
  reg [8:0]     w00_q, w10_q, w01_q, w11_q;
  reg [3:0]     tv_q;  // tap valid: {11, 01, 10, 00}
  reg           rp_q, cp_q;

  // Line-buffer writes, delayed to the read ce of the same beat.
  reg [7:0]     wp_q, wp_q2, wp_q3, wp_q4;
  reg [1:0]     wb_q2, wb_q3, wb_q4;
  reg [BAW-1:0] wa_q2, wa_q3, wa_q4;
  reg [XW-1:0]  wx_q;
  reg [SB-1:0]  wls_q;
  wire [BAW-1:0] wa1 = baddr(wls_q, {{(IW - XW){1'b0}}, wx_q});

  wire [7:0] lb_rd[0:3];
  generate
    for (b = 0; b < 4; b = b + 1) begin : g_lb
      localparam [1:0] BI = b;
      sm_sdp_ram #(
          .DATA_W(8),
          .DEPTH (BDEPTH)
      ) u_ram (
          .clk  (clk),
          .we   (ce && (wb_q4 == BI)),
          .waddr(wa_q4),
          .wdata(wp_q4),
          .re   (ce),
          .raddr(ra[b]),
          .rdata(lb_rd[b])
      );
    end
  endgenerate

  // ---------------------------------------------------------------- stage 6: taps
  reg [8:0] w00_q2, w10_q2, w01_q2, w11_q2;
  reg [3:0] tv_q2;
  reg       rp_q2, cp_q2;

  wire [7:0]  t00 = tv_q2[0] ? lb_rd[{rp_q2, cp_q2}] : 8'd0;
  wire [7:0]  t10 = tv_q2[1] ? lb_rd[{rp_q2, ~cp_q2}] : 8'd0;
  wire [7:0]  t01 = tv_q2[2] ? lb_rd[{~rp_q2, cp_q2}] : 8'd0;
  wire [7:0]  t11 = tv_q2[3] ? lb_rd[{~rp_q2, ~cp_q2}] : 8'd0;

  // ---------------------------------------------------------------- stage 7: blend
  reg [8:0] w00_q3, w10_q3, w01_q3, w11_q3;
  reg [7:0] p00, p10, p01, p11;
  // weights sum to 256, so the blend is at most 255*256 + 128 (16 bits)
  /* verilator lint_off UNUSEDSIGNAL */  // bits 7:0 are below the result
  wire [16:0] blend = {9'd0, p00} * {8'd0, w00_q3} + {9'd0, p10} * {8'd0, w10_q3} +
                      {9'd0, p01} * {8'd0, w01_q3} + {9'd0, p11} * {8'd0, w11_q3} + 17'd128;
  /* verilator lint_on UNUSEDSIGNAL */

  // ---------------------------------------------------------------- registers
  sm_side_delay #(.DEPTH(8)) u_side (.clk(clk), .rst_n(rst_n), .ce(ce), .d(c_side), .q(m_side));
  always @(posedge clk) begin
    if (!rst_n) begin
      ls_q    <= {SB{1'b0}};
      cy_q    <= {YW{1'b0}};
      bank_q  <= 1'b0;
      en_q    <= 1'b0;
    end else if (ce) begin
      ls_q    <= ls;
      cy_q    <= cy;
      bank_q  <= bank_f;
      en_q    <= en_f;
    end
  end

  always @(posedge clk) begin
    if (ce) begin
      // stage 1 -> 2
      fx_q  <= fx_q0;
      fy_q  <= fy_q0;
      gxp_q <= gxp_q0;
      gyp_q <= gyp_q0;
      en_q1 <= en_q0;
      cx_q  <= cx_q0;
      cy_q1 <= cy_q0;
      cs_q  <= cs_q0;
      rok_q <= rok_q0;
      wp_q  <= wp_q0;
      wx_q  <= wx_q0;
      wls_q <= wls_q0;
      // stage 2 -> 3
      if (fx_q == 4'd0) begin
        v0x_q <= v0x;
        v1x_q <= v1x;
        v0y_q <= v0y;
        v1y_q <= v1y;
      end
      fx_q2  <= fx_q;
      en_q2  <= en_q1;
      cx_q2  <= cx_q;
      ncy_q2 <= -{{(IW - YW){1'b0}}, cy_q1};
      cs_q2  <= cs_q;
      rok_q2 <= rok_q;
      wp_q2  <= wp_q;
      wa_q2  <= wa1;
      wb_q2  <= {wls_q[0], wx_q[0]};
      // stage 3 -> 4
      sx_acc_q <= sx_s;
      sy_acc_q <= sy_s;
      cs_q3    <= cs_q2;
      csm_q3   <= {2'b00, cs_q2} - NRS;
      csp_q3   <= {2'b00, cs_q2} + NRS;
      rok_q3   <= rok_q2;
      wp_q3    <= wp_q2;
      wa_q3    <= wa_q2;
      wb_q3    <= wb_q2;
      // stage 4 -> 5
      hs_e_q  <= hs_e;
      hs_o_q  <= hs_o;
      hc_e_q  <= hc_e;
      hc_o_q  <= hc_o;
      ok_q    <= {rv_o && cv_o, rv_o && cv_e, rv_e && cv_o, rv_e && cv_e};
      w00_q   <= {4'd0, ax1} * {4'd0, ay1};
      w10_q   <= {5'd0, ax} * {4'd0, ay1};
      w01_q   <= {4'd0, ax1} * {5'd0, ay};
      w11_q   <= {5'd0, ax} * {5'd0, ay};
      tv_q    <= {c1ok && r1ok, c0ok && r1ok, c1ok && r0ok, c0ok && r0ok};
      rp_q    <= rp;
      cp_q    <= cp;
      wp_q4   <= wp_q3;
      wa_q4   <= wa_q3;
      wb_q4   <= wb_q3;
      // stage 5 -> 6
      w00_q2 <= w00_q;
      w10_q2 <= w10_q;
      w01_q2 <= w01_q;
      w11_q2 <= w11_q;
      tv_q2  <= tv_q;
      rp_q2  <= rp_q;
      cp_q2  <= cp_q;
      // stage 6 -> 7
      p00    <= t00;
      p10    <= t10;
      p01    <= t01;
      p11    <= t11;
      w00_q3 <= w00_q2;
      w10_q3 <= w10_q2;
      w01_q3 <= w01_q2;
      w11_q3 <= w11_q2;
      // stage 7 -> out
      m_pix  <= blend[15:8];
    end
  end
endmodule
`default_nettype wire
