`default_nettype none
// Census transform of both rectified images (docs/algorithm.md, section 3).
// One sm_linebuf holds the CENSUS-1 previous rows of both cameras ({right, left} per
// word), so a full window column arrives per beat; a CENSUS x CENSUS register window
// slides over it and every neighbour is compared with the centre in parallel.
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
    input  wire [4:0]    s_side,
    input  wire [7:0]    s_left,   // rectified left pixel
    input  wire [7:0]    s_right,  // rectified right pixel
    output reg  [4:0]    m_side,
    output reg  [CB-1:0] m_cl,     // left census vector, bit k = neighbour k < centre
    output reg  [CB-1:0] m_cr,     // right census vector
    output reg  [7:0]    m_left    // left centre pixel, for the aggregation weights
);
  localparam XW = $clog2(MAX_WIDTH + 1);
  localparam CB = CENSUS * CENSUS - 1;
  localparam R  = (CENSUS - 1) / 2;
  localparam C  = CENSUS;

  generate
    if (CENSUS < 3 || CENSUS > 15 || CENSUS % 2 == 0) begin : g_bad_census
      initial $error("sm_census: CENSUS (%0d) must be odd, 3..15", CENSUS);
    end
  endgenerate

  // ---- window control for the entering beat --------------------------------------
  wire [XW-1:0] s_x;
  wire [4:0]    c_side;
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
  sm_linebuf #(.MAX_WIDTH(MAX_WIDTH), .DATA_W(16), .ROWS(C - 1)) u_lb (
      .clk(clk), .ce(ce), .col(s_x), .din({s_right, s_left}), .dout(lb_dout)
  );
  reg [15:0]  live_q;  // the entering pixel, aligned with the line-buffer read
  reg [4:0]   side_q, side_q2;
  reg [C-1:0] row_ok_q, row_ok_q2;
  reg [C-1:0] col_ok_q, col_ok_q2;

  // ---- stage 2: the window, win_l[r][j] = row (centre + r - R), column (centre + j - R)
  reg [7:0] win_l [0:C-1][0:C-1];
  reg [7:0] win_r [0:C-1][0:C-1];

  // ---- stage 3: compare against the centre ----------------------------------------
  wire [7:0]    ctr_l = win_l[R][R];
  wire [7:0]    ctr_r = win_r[R][R];
  wire [CB-1:0] cl_bits;
  wire [CB-1:0] cr_bits;
  genvar r, j;
  generate
    for (r = 0; r < C; r = r + 1) begin : g_row
      for (j = 0; j < C; j = j + 1) begin : g_col
        // raster index with the centre skipped
        localparam K = r * C + j - ((r * C + j > R * C + R) ? 1 : 0);
        if (r != R || j != R) begin : g_bit
          // an outside neighbour counts as equal to the centre: bit 0
          wire ok = row_ok_q2[r] & col_ok_q2[j];
          assign cl_bits[K] = ok & (win_l[r][j] < ctr_l);
          assign cr_bits[K] = ok & (win_r[r][j] < ctr_r);
        end
      end
    end
  endgenerate

  integer a, b;
  always @(posedge clk) begin
    if (ce) begin
      live_q    <= {s_right, s_left};
      row_ok_q  <= row_ok;
      col_ok_q  <= col_ok;
      row_ok_q2 <= row_ok_q;
      col_ok_q2 <= col_ok_q;
      // shift the window one column left; the newest column enters at j = C-1
      for (a = 0; a < C; a = a + 1)
        for (b = 0; b < C - 1; b = b + 1) begin
          win_l[a][b] <= win_l[a][b+1];
          win_r[a][b] <= win_r[a][b+1];
        end
      // row r = C-1 is the live row, row C-2-k is the line buffer's row live-1-k
      win_l[C-1][C-1] <= live_q[7:0];
      win_r[C-1][C-1] <= live_q[15:8];
      for (a = 0; a < C - 1; a = a + 1) begin
        win_l[C-2-a][C-1] <= lb_dout[a*16 +: 8];
        win_r[C-2-a][C-1] <= lb_dout[a*16+8 +: 8];
      end
      m_cl   <= cl_bits;
      m_cr   <= cr_bits;
      m_left <= ctr_l;
    end
  end

  // sideband: control state, reset so no phantom real beat leaves after reset
  always @(posedge clk) begin
    if (!rst_n) begin
      side_q  <= 5'd0;
      side_q2 <= 5'd0;
      m_side  <= 5'd0;
    end else if (ce) begin
      side_q  <= c_side;
      side_q2 <= side_q;
      m_side  <= side_q2;
    end
  end
endmodule
`default_nettype wire
