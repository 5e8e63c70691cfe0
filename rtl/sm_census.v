`default_nettype none
`include "sm_defs.vh"
// Census transform of both rectified images (docs/algorithm.md, section 3).
// One sm_linebuf holds the CENSUS-1 previous rows of both cameras ({right, left} per
// word), so a full window column arrives per beat; a CENSUS x CENSUS window slides over
// it and every neighbour is compared with the centre in parallel. The window's CENSUS
// columns live in a circular buffer of LUT-RAM (sm_colwin) that every beat writes once
// and reads at every column's address, where a shifting register window would need
// one flip-flop per bit and column.
//
// Latency: the output beat after the ce of input beat n is the pixel of input beat
// n - (R*width + R) - 2 (R = (CENSUS-1)/2): the window delay of sm_win_ctrl plus
// two register stages (line-buffer read, window shift) before the output register.
module sm_census #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter CENSUS    = 15    // census window side (odd, 3..15)
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          ce,
    input  wire [XW-1:0] width,    // active width
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [7:0]    s_left,   // rectified left pixel
    input  wire [7:0]    s_right,  // rectified right pixel
    output wire [`SM_SIDE_W-1:0] m_side,
    output reg  [CB-1:0] m_cl,     // left census vector, bit k = neighbour k < centre
    output reg  [CB-1:0] m_cr,     // right census vector
    output reg  [7:0]    m_left,   // left centre pixel, for the aggregation weights
    output reg  [7:0]    m_right   // right centre pixel, for the cost's intensity term
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam CB = CENSUS * CENSUS - 1;
  localparam R  = (CENSUS - 1) / 2;
  localparam C  = CENSUS;

  generate
    `SM_BAD_PARAM(g_bad_census, CENSUS < `SM_CENSUS_MIN || CENSUS > `SM_CENSUS_MAX || CENSUS % 2 == 0,
                  ("sm_census: CENSUS (%0d) must be odd, %0d..%0d", CENSUS, `SM_CENSUS_MIN, `SM_CENSUS_MAX))
  endgenerate

  // ---- window control for the entering beat --------------------------------------
  wire [XW-1:0] s_x;
  wire [`SM_SIDE_W-1:0] c_side;
  wire [XW-1:0] c_x;
  wire [C-1:0]  row_ok;
  wire [C-1:0]  col_ok;
  sm_win_ctrl #(
      .MAX_WIDTH(MAX_WIDTH), .D_ROWS(R), .D_COLS(R),
      .R_UP(R), .R_DN(R), .R_L(R), .R_R(R)
  ) u_ctrl (
      .clk(clk), .rst_n(rst_n), .ce(ce), .width(width), .s_side(s_side),
      .s_x(s_x), .c_side(c_side), .c_x(c_x), .row_ok(row_ok), .col_ok(col_ok)
  );
  wire unused_cx = &c_x;  // the masks already carry the column position

  // ---- stage 1: line-buffer read of the entering column ----------------------------
  wire [(C-1)*16-1:0] lb_dout;  // rows live-1 .. live-(C-1), {right, left} each
  wire [15:0]         lb_live;  // the entering pixel, aligned with the line-buffer read
  sm_linebuf #(.MAX_WIDTH(MAX_WIDTH), .DATA_W(16), .ROWS(C - 1)) u_lb (
      .clk(clk), .ce(ce), .col(s_x), .din({s_right, s_left}), .dout(lb_dout),
      .live(lb_live)
  );
  reg [C-1:0] row_ok_q, row_ok_q2;
  reg [C-1:0] col_ok_q, col_ok_q2;

  // ---- stage 2: the window. Column j (C-1 = entered last) of row r (centre + r - R),
  // all C columns in a circular buffer of LUT-RAM (sm_colwin).
  localparam CWW = C * 16;  // one column of both images, row r at [r*16 +: 16]
  wire [CWW-1:0]   newcol;
  wire [C*CWW-1:0] awin;  // by age: age a at [a*CWW +: CWW]
  wire [C*CWW-1:0] win;   // column j at [j*CWW +: CWW], age C-1-j
  genvar r, j;
  generate
    // row C-1 is the live row, row C-2-k the line buffer's row live-1-k
    for (r = 0; r < C - 1; r = r + 1) begin : g_newrow
      assign newcol[r*16 +: 16] = lb_dout[(C-2-r)*16 +: 16];
    end
    assign newcol[(C-1)*16 +: 16] = lb_live;
    for (j = 0; j < C; j = j + 1) begin : g_col
      assign win[j*CWW +: CWW] = awin[(C-1-j)*CWW +: CWW];
    end
  endgenerate
  sm_colwin #(.W(CWW), .N(C)) u_win (
      .clk(clk), .rst_n(rst_n), .ce(ce), .col(newcol), .win(awin)
  );

  // ---- stage 3: compare against the centre ----------------------------------------
  // A neighbour outside the image takes the nearest inside pixel (coordinates clamped,
  // row and column independently). Its bit is then the bit of that inside window
  // position, compared with the same centre, so the clamp selects comparison bits
  // instead of 8-bit pixels (sm_edge_clamp): rows first (a row outside the image takes
  // the bits of the first, or last, row inside), then columns of those row-clamped bits.
  // The centre comes from flip-flops: read from the LUT-RAM, its 16 bits fanned out to
  // all comparators behind the read, and placed and routed that was the block's slowest
  // path (docs/synthesis.md). A ce makes the column of age R-1 the centre column.
  reg  [15:0]    ctr_q;  // the window's centre pixel, {right, left}
  always @(posedge clk) begin
    if (ce) ctr_q <= awin[(R-1)*CWW + R*16 +: 16];
  end
  wire [7:0]     ctr_l = ctr_q[7:0];
  wire [7:0]     ctr_r = ctr_q[15:8];
  wire [C*C-1:0] lt_l, lt_r;  // window position (r, j) at bit r*C + j
  wire [C*C-1:0] rc_l, rc_r;  // row-clamped bits
  wire [C*C-1:0] cc_l, cc_r;  // row- and column-clamped bits
  wire [CB-1:0]  cl_bits;
  wire [CB-1:0]  cr_bits;
  generate
    for (r = 0; r < C; r = r + 1) begin : g_cmp_row
      for (j = 0; j < C; j = j + 1) begin : g_cmp_col
        if (r == R && j == R) begin : g_ctr
          // The centre against itself: a constant, which the clamps copy into the
          // positions outside the image (synthesis no longer sees it equal to ctr_q).
          assign lt_l[r*C + j] = 1'b0;
          assign lt_r[r*C + j] = 1'b0;
        end else begin : g_nb
          assign lt_l[r*C + j] = win[j*CWW + r*16 +: 8] < ctr_l;
          assign lt_r[r*C + j] = win[j*CWW + r*16 + 8 +: 8] < ctr_r;
        end
      end
    end
    for (j = 0; j < C; j = j + 1) begin : g_rclamp
      wire [C-1:0] col_l, col_r, q_l, q_r;  // column j by row
      for (r = 0; r < C; r = r + 1) begin : g_gather
        assign col_l[r]       = lt_l[r*C + j];
        assign col_r[r]       = lt_r[r*C + j];
        assign rc_l[r*C + j]  = q_l[r];
        assign rc_r[r*C + j]  = q_r[r];
      end
      sm_edge_clamp #(.N(C)) u_l (.ok(row_ok_q2), .bits(col_l), .q(q_l));
      sm_edge_clamp #(.N(C)) u_r (.ok(row_ok_q2), .bits(col_r), .q(q_r));
    end
    for (r = 0; r < C; r = r + 1) begin : g_cclamp
      sm_edge_clamp #(.N(C)) u_l (.ok(col_ok_q2), .bits(rc_l[r*C +: C]), .q(cc_l[r*C +: C]));
      sm_edge_clamp #(.N(C)) u_r (.ok(col_ok_q2), .bits(rc_r[r*C +: C]), .q(cc_r[r*C +: C]));
    end
    // raster order with the centre skipped; the centre's own bit (always 0) is dropped
    assign cl_bits = {cc_l[C*C-1:R*C+R+1], cc_l[R*C+R-1:0]};
    assign cr_bits = {cc_r[C*C-1:R*C+R+1], cc_r[R*C+R-1:0]};
  endgenerate
  wire unused_ctr = cc_l[R*C+R] | cc_r[R*C+R] | (|win[R*CWW + R*16 +: 16]);  // in ctr_q

  always @(posedge clk) begin
    if (ce) begin
      row_ok_q  <= row_ok;
      col_ok_q  <= col_ok;
      row_ok_q2 <= row_ok_q;
      col_ok_q2 <= col_ok_q;
      m_cl   <= cl_bits;
      m_cr   <= cr_bits;
      m_left <= ctr_l;
      m_right <= ctr_r;
    end
  end

  sm_side_delay #(.DEPTH(3)) u_side (.clk(clk), .rst_n(rst_n), .ce(ce), .d(c_side), .q(m_side));
endmodule
`default_nettype wire
