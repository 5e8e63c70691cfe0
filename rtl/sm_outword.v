`default_nettype none
`include "sm_defs.vh"
// Output word of the core (docs/algorithm.md 9.4, 9.6; model out_word): the second half of
// the output stage, after the post filters. The first half, at the DP's read-out, turned a
// pixel's evidence into the fields s_fields, which travelled beside the disparity through
// the filters; what is left depends on the level the filters chose, so it is done here:
//   d_out = min(post level, fb)             fb: the background fill, or DISP-1 (none)
//   q4    = 16 fb                           where the fill is taken (no fraction)
//         = 16 d + off                      where the filters kept the DP's level d
//         = 16 post                         a level taken from a neighbour (no fraction)
//           clamped to 0 .. 16 (DISP - 1)
//   valid = post valid, no rule failed, and not (border rule on and x < d_out)
//   conf  = {lr_ok, matched && x >= d_out, agree_ok, ratio}
//   fails = the enabled rules that cleared the pixel, {lr, tex, agree, uniq, border, occ}:
//           the border's here, the others from the ratio's slot where fail is set
//   word  = valid ? {1, 7'b0, conf, q4} : {0, 0, fails, 24'b0}
// Two register stages, so a beat's word leaves on the ce after the one that takes it in
// (latency 1 beat): the level select and the Q.4 sum, then the border compare (the column
// against d_out) and the word, each under the LUT-level budget.
// s_fields = {fb, ratio[4:0], agree_ok, matched, lr_ok, border_en, fail, off[5:0], d}
// (FIELDS_W = 2 DW + 16 bits; off is the signed Q.4 offset from 16 d, -24..24).
module sm_outword #(
    parameter MAX_WIDTH = 320,  // widest active line (the column counter)
    parameter DISP      = 128   // disparity levels
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [15:0]           s_disp,    // post filters' beat: bit 15 valid, low DW bits level
    input  wire [FIELDS_W-1:0]   s_fields,  // the pixel's fields, aligned with s_disp
    output wire [`SM_SIDE_W-1:0] m_side,
    output reg  [31:0]           m_word
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam DW = $clog2(DISP);
  localparam FIELDS_W = 2 * DW + 16;
  localparam QW = DW + 4;  // Q.4 level
  localparam QS = QW + 2;  // 16 d + off with a sign: |off| <= 24 may carry past QW bits
  /* verilator lint_off WIDTH */  // constant of the Q.4 width
  localparam [QS-1:0] Q_MAX = 16 * (DISP - 1);
  /* verilator lint_on WIDTH */

  generate
    `SM_BAD_PARAM(g_bad_disp, DISP < `SM_DISP_MIN || DISP > `SM_DISP_MAX || DISP % 2 != 0,
                  ("sm_outword: DISP (%0d) must be even, %0d..%0d", DISP, `SM_DISP_MIN, `SM_DISP_MAX))
    `SM_BAD_PARAM(g_bad_width, MAX_WIDTH < 2, ("sm_outword: MAX_WIDTH (%0d) must be at least 2", MAX_WIDTH))
  endgenerate

  wire [DW-1:0] f_d      = s_fields[DW-1:0];
  wire [5:0]    f_off    = s_fields[DW +: 6];
  wire          f_fail   = s_fields[DW+6];
  wire          f_border = s_fields[DW+7];
  wire [DW-1:0] f_fb     = s_fields[DW+16 +: DW];
  // conf bits: lr_ok at DW+8, matched at DW+9, agree_ok at DW+10, ratio at DW+11 .. DW+15
  wire          f_lr     = s_fields[DW+8];
  wire          f_match  = s_fields[DW+9];
  wire          f_agree  = s_fields[DW+10];
  wire [4:0]    f_ratio  = s_fields[DW+11 +: 5];  // where f_fail: {lr, tex, agree, uniq, occ}

  wire [DW-1:0] post_d = s_disp[DW-1:0];
  wire          post_v = s_disp[15];
  wire unused_disp = ^s_disp[14:DW];

  // column of the beat on the input
  reg  [XW-1:0] x_q;
  wire [XW-1:0] x_in = s_side[`SM_SIDE_SOL] ? {XW{1'b0}} : x_q + 1'b1;

  // ---- beat 1: the level, the Q.4 value before the clamp ----
  wire          bg = f_fb < post_d;
  wire          keep = post_d == f_d;
  wire [QS-1:0] q_base = {2'b00, bg ? f_fb : keep ? f_d : post_d, 4'b0000};
  wire [QS-1:0] q_off = (bg || !keep) ? {QS{1'b0}} : {{(QS - 6) {f_off[5]}}, f_off};
  reg  [QS-1:0] q_q;  // two's complement: 16 d + off may fall below 0 in principle
  reg  [DW-1:0] dout_q;
  reg  [XW-1:0] x1_q;
  reg           v_q, bord_q, lr_q, match_q, agree_q, fail_q;
  reg  [4:0]    ratio_q;

  always @(posedge clk) begin
    if (ce) begin
      x_q     <= x_in;
      x1_q    <= x_in;
      q_q     <= q_base + q_off;
      dout_q  <= bg ? f_fb : post_d;
      v_q     <= post_v && !f_fail;
      fail_q  <= f_fail;
      bord_q  <= f_border;
      lr_q    <= f_lr;
      match_q <= f_match;
      agree_q <= f_agree;
      ratio_q <= f_ratio;
    end
  end

  // ---- beat 2: the border, the clamp, the word ----
  localparam CMPW = (XW > DW) ? XW : DW;  // compare width
  wire [CMPW-1:0] x_c = {{(CMPW - XW) {1'b0}}, x1_q};
  wire [CMPW-1:0] d_c = {{(CMPW - DW) {1'b0}}, dout_q};
  wire        border = x_c < d_c;
  wire        border_fail = bord_q && border;
  wire        valid = v_q && !border_fail;
  wire [4:0]  rules = fail_q ? ratio_q : 5'd0;
  wire [5:0]  fails = {rules[4:1], border_fail, rules[0]};
  wire [QW-1:0] q4 = q_q[QS-1] ? {QW{1'b0}} : (q_q > Q_MAX) ? Q_MAX[QW-1:0] : q_q[QW-1:0];
  wire [7:0]  conf = {lr_q, match_q && !border, agree_q, ratio_q};
  always @(posedge clk) begin
    if (ce) m_word <= valid ? {1'b1, 7'b0, conf, {(16 - QW) {1'b0}}, q4} : {2'b00, fails, 24'd0};
  end

  sm_side_delay #(.DEPTH(2)) u_side (.clk(clk), .rst_n(rst_n), .ce(ce), .d(s_side), .q(m_side));
endmodule
`default_nettype wire
