`default_nettype none
`include "sm_defs.vh"
// Post-processing filter F0: recursive band filter (docs/algorithm.md, section 7; model
// post_band). Top to bottom, a = this filter's own output at (x, y-1), c = the input at
// (x, y), d(p) = the low DW bits: when a and c are valid, |d(c) - d(a)| > 1 and one of
// the input rows y+1 .. y+K inside the frame is valid and within 1 of d(a), the output
// is a, otherwise c (row 0: c). Output words as the medians': 0x8000 | d or 0x0000.
//
// Storage: one memory word per column, read on the ce of the entering beat (row y+K)
// and written back on the next ce, holding the K input rows y+K-1 .. y as {valid, d}
// (the stream's bits between them are zero, docs/algorithm.md section 7: 72 bits a word
// instead of 136 at K 8, DISP 128, i.e. 2 RAMB36 instead of 4 at 640 columns) and, above
// them, the filter's output of the row above the centre, also {valid, d}. The decision
// of (x, y) is taken from that read and written back into the same word, where the next row's
// decision at column x reads it one row later: the recursion closes through the memory.
//
// Latency: the output beat after the ce of input beat n is the pixel of input beat
// n - K*width - 1 (sm_win_ctrl delay of K rows, memory read, output register).
module sm_post_band #(
    parameter MAX_WIDTH = 320,  // widest active line (memory words)
    parameter DISP      = 128,  // disparity levels 0..DISP-1
    parameter K         = 8     // look-ahead rows below the centre (1..16)
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          ce,
    input  wire [XW-1:0] width,    // active width, at least 2
    input  wire          enable,   // 0: pass the centre through (same latency)
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [15:0]   s_disp,   // bit 15 valid, low bits disparity
    output wire [`SM_SIDE_W-1:0] m_side,
    output reg  [15:0]   m_disp
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam DW = $clog2(DISP);
  localparam AW = $clog2(MAX_WIDTH);   // memory address; columns are below MAX_WIDTH
  localparam OW = DW + 1;              // a pixel as kept: {valid, d}
  localparam LW = OW * K;              // the K input rows of a column
  localparam WW = LW + OW;             // memory word

  generate
    `SM_BAD_PARAM(g_bad_disp, DISP < `SM_DISP_MIN || DISP > `SM_DISP_MAX || DISP % 2 != 0,
                  ("sm_post_band: DISP (%0d) must be even, %0d..%0d", DISP, `SM_DISP_MIN, `SM_DISP_MAX))
    `SM_BAD_PARAM(g_bad_k, K < 1 || K > 16, ("sm_post_band: K (%0d) must be 1..16", K))
    `SM_BAD_PARAM(g_bad_mw, MAX_WIDTH < 2,
                  ("sm_post_band: MAX_WIDTH (%0d) must be at least 2", MAX_WIDTH))
  endgenerate

  // ---- window control: centre K rows above the entering beat, rows y-1 .. y+K -------
  wire [XW-1:0] s_x;
  wire [`SM_SIDE_W-1:0] c_side;
  wire [XW-1:0] c_x;
  wire [K+1:0]  row_ok;  // bit 1+j: row y+j is in the centre's frame, j = -1..K
  wire          col_ok;
  sm_win_ctrl #(
      .MAX_WIDTH(MAX_WIDTH), .D_ROWS(K), .D_COLS(0),
      .R_UP(1), .R_DN(K), .R_L(0), .R_R(0)
  ) u_ctrl (
      .clk(clk), .rst_n(rst_n), .ce(ce), .width(width), .s_side(s_side),
      .s_x(s_x), .c_side(c_side), .c_x(c_x), .row_ok(row_ok), .col_ok(col_ok)
  );
  wire unused_ctrl = ^{c_x, col_ok, row_ok[1]};  // one column, the centre is in its frame
  wire unused_mid = ^s_disp[14:DW];  // zero in the stream

  wire [AW-1:0] addr = s_x[AW-1:0];
  generate
    if (XW > AW) begin : g_unused_msb
      wire unused_sx_msb = s_x[XW-1];  // a column never reaches MAX_WIDTH
    end
  endgenerate

  // ---- stage 1: memory read of the entering column ---------------------------------
  // Contents are not reset: sm_win_ctrl masks every row outside the centre's frame.
  reg [WW-1:0]  mem [0:MAX_WIDTH-1];
  reg [WW-1:0]  rd_q;     // registered read: the block RAM's output register
  reg [AW-1:0]  col_q;    // address of the word in rd_q, written back on the next ce
  reg [OW-1:0]  live_q;   // the entering beat: row y+K, {valid, d}
  reg           up_ok_q;  // row y-1 is in the centre's frame
  reg [K-1:0]   dn_ok_q;  // bit j-1: row y+j is in the centre's frame

  // rows of the centre's column after the read: row y+j at j = 0..K
  wire [OW-1:0] row_w [0:K];
  genvar j;
  generate
    for (j = 0; j < K; j = j + 1) begin : g_rows
      assign row_w[j] = rd_q[OW*(K-1-j) +: OW];  // memory row k holds row y+K-1-k
    end
  endgenerate
  assign row_w[K] = live_q;
  wire [OW-1:0] ctr   = row_w[0];
  wire [OW-1:0] above = rd_q[LW +: OW];          // {valid, d} of the output at (x, y-1)
  wire          a_v   = above[DW] & up_ok_q;
  wire [DW-1:0] a_d   = above[DW-1:0];

  // |d(p) - d(a)| <= 1, without carry chains: p == a, p == a + 1 or a == p + 1.
  // p == q + 1 <=> some bit t has q[t] = 0, p[t] = 1, the bits below are all 1 in q and
  // all 0 in p, and the bits above are equal.
  function near1(input [DW-1:0] p, input [DW-1:0] q);
    integer t;
    reg hi_eq, up, dn;
    // hm = {DW{1'b1}} << t marks bit t and above: "the bits below t are all 0 in v" is
    // (v & ~hm) == 0, "all 1" is (v | hm) == all ones. Written without a vector temporary,
    // which Verilator made a static shared by the K + 1 calls (MULTIDRIVEN).
    begin
      up = 1'b0;
      dn = 1'b0;
      for (t = 0; t < DW; t = t + 1) begin
        hi_eq = (((p ^ q) >> t) >> 1) == {DW{1'b0}};
        up    = up | (hi_eq & p[t] & ~q[t] & ((p & ~({DW{1'b1}} << t)) == {DW{1'b0}})
                     & ((q | ({DW{1'b1}} << t)) == {DW{1'b1}}));
        dn    = dn | (hi_eq & q[t] & ~p[t] & ((q & ~({DW{1'b1}} << t)) == {DW{1'b0}})
                     & ((p | ({DW{1'b1}} << t)) == {DW{1'b1}}));
      end
      near1 = (p == q) | up | dn;
    end
  endfunction

  // one of rows y+1 .. y+K in the frame, valid and within 1 of a
  wire [K-1:0] back;
  generate
    for (j = 1; j <= K; j = j + 1) begin : g_back
      assign back[j-1] = dn_ok_q[j-1] & row_w[j][DW] & near1(row_w[j][DW-1:0], a_d);
    end
  endgenerate
  wire          take_a = a_v & ctr[DW] & ~near1(ctr[DW-1:0], a_d) & (|back);
  wire [OW-1:0] res    = take_a ? above : {ctr[DW], ctr[DW] ? ctr[DW-1:0] : {DW{1'b0}}};
  wire [15:0]   res_w  = res[DW] ? {1'b1, {(15-DW){1'b0}}, res[DW-1:0]} : 16'd0;
  wire [15:0]   ctr_w  = {ctr[DW], {(15-DW){1'b0}}, ctr[DW-1:0]};  // disabled: the centre

  // the word written back: every input row one step older, the live row in front, the
  // centre's result as the next row's row above
  wire [WW-1:0] wr_word;
  generate
    if (K == 1) begin : g_one
      assign wr_word = {res, live_q};
    end else begin : g_shift
      assign wr_word = {res, rd_q[LW-OW-1:0], live_q};
    end
  endgenerate

  wire [`SM_SIDE_W-1:0] side_q;
  sm_side_delay #(.DEPTH(1)) u_side (.clk(clk), .rst_n(rst_n), .ce(ce), .d(c_side), .q(side_q));
  sm_side_delay #(.DEPTH(1)) u_side_out (.clk(clk), .rst_n(rst_n), .ce(ce), .d(side_q), .q(m_side));

  // The enable is taken with the frame's first centre at the output stage, so every
  // pixel of a frame sees the same setting even when the register changes mid-frame.
  reg  en_q;
  wire en = side_q[`SM_SIDE_SOF] ? enable : en_q;

  always @(posedge clk) begin
    if (ce) begin
      mem[col_q] <= wr_word;
      rd_q       <= mem[addr];
      col_q      <= addr;
      live_q     <= {s_disp[15], s_disp[DW-1:0]};
      up_ok_q    <= row_ok[0];
      dn_ok_q    <= row_ok[K+1:2];
      m_disp     <= en ? res_w : ctr_w;
    end
  end

  // the enable is control state like the sideband: reset with it
  always @(posedge clk) begin
    if (!rst_n) en_q <= 1'b0;
    else if (ce) en_q <= en;
  end
endmodule
`default_nettype wire
