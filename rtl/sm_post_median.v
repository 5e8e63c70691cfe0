`default_nettype none
`include "sm_defs.vh"
// Windowed median of the disparity stream (docs/algorithm.md, section 7): the
// (2*RY+1) x (2*RX+1) window of sort keys (valid ? d + 1 : 0) is ranked in parallel and
// the element of middle rank is the output. Window pixels outside the frame take the
// centre's key, so the element count is fixed and no sorter has to shrink at borders.
// The three post-processing filters are this module at three window shapes.
//
// Latency: like sm_census, the output beat after the ce of input beat n is the pixel of
// input beat n - (RY*width + RX) - 2 (window delay, line-buffer read, window shift).
module sm_post_median #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter DISP      = 128,  // disparity levels 0..DISP-1
    parameter RY        = 2,    // window rows above and below the centre
    parameter RX        = 0     // window columns left and right of the centre
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          ce,
    input  wire [XW-1:0] width,    // active width
    input  wire          enable,   // 0: pass the centre through (same latency)
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [15:0]   s_disp,   // bit 15 valid, low bits disparity
    output wire [`SM_SIDE_W-1:0] m_side,
    output reg  [15:0]   m_disp
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam DW = $clog2(DISP);
  localparam KW = DW + 1;             // sort key: 0 = invalid, d + 1 otherwise
  localparam PW = DW + 1;             // a pixel as kept: {valid, d}
  localparam NR = 2 * RY + 1;         // window rows
  localparam NC = 2 * RX + 1;         // window columns
  localparam N  = NR * NC;            // window elements
  localparam MID = (N - 1) / 2;       // rank of the median
  localparam RW = $clog2(N);          // rank counter width

  generate
    `SM_BAD_PARAM(g_bad_disp, DISP < `SM_DISP_MIN || DISP > `SM_DISP_MAX || DISP % 2 != 0,
                  ("sm_post_median: DISP (%0d) must be even, %0d..%0d", DISP, `SM_DISP_MIN, `SM_DISP_MAX))
    `SM_BAD_PARAM(g_bad_win, RY < 0 || RY > 3 || RX < 0 || RX > 3 || N < 3,
                  ("sm_post_median: window RY=%0d RX=%0d outside 0..3 or too small", RY, RX))
  endgenerate

  // ---- window control for the entering beat --------------------------------------
  wire [XW-1:0] s_x;
  wire [`SM_SIDE_W-1:0] c_side;
  wire [XW-1:0] c_x;
  wire [NR-1:0] row_ok;
  wire [NC-1:0] col_ok;
  sm_win_ctrl #(
      .MAX_WIDTH(MAX_WIDTH), .D_ROWS(RY), .D_COLS(RX),
      .R_UP(RY), .R_DN(RY), .R_L(RX), .R_R(RX)
  ) u_ctrl (
      .clk(clk), .rst_n(rst_n), .ce(ce), .width(width), .s_side(s_side),
      .s_x(s_x), .c_side(c_side), .c_x(c_x), .row_ok(row_ok), .col_ok(col_ok)
  );
  wire unused_cx = &c_x;  // the masks already carry the column position

  // ---- stage 1: line-buffer read of the entering column ----------------------------
  // The stream's bits between the valid bit and the level are zero (docs/algorithm.md,
  // section 7), so the window and the line buffer keep {valid, d}: at DISP 128 that
  // halves the line buffer (vga: 2 -> 1 RAMB36 for four rows of 640 columns).
  wire [PW-1:0] s_pix = {s_disp[15], s_disp[DW-1:0]};
  wire unused_mid = ^s_disp[14:DW];
  wire [PW*NR-1:0] col_in;  // the entering column, row NR-1 = live row
  wire [PW-1:0]    lb_live;  // the entering beat, aligned with the line-buffer read
  generate
    if (RY > 0) begin : g_lb
      wire [PW*(NR-1)-1:0] lb_dout;  // rows live-1 .. live-(NR-1)
      sm_linebuf #(.MAX_WIDTH(MAX_WIDTH), .DATA_W(PW), .ROWS(NR - 1)) u_lb (
          .clk(clk), .ce(ce), .col(s_x), .din(s_pix), .dout(lb_dout), .live(lb_live)
      );
      genvar a;
      for (a = 0; a < NR - 1; a = a + 1) begin : g_rows
        assign col_in[PW*(NR-2-a) +: PW] = lb_dout[PW*a +: PW];
      end
    end else begin : g_no_lb
      wire unused_sx = &s_x;  // single row: no line buffer to address
      reg [PW-1:0] live_q;
      always @(posedge clk) if (ce) live_q <= s_pix;
      assign lb_live = live_q;
    end
  endgenerate
  assign col_in[PW*(NR-1) +: PW] = lb_live;

  reg [NR-1:0] row_ok_q;
  reg [NC-1:0] col_ok_q;

  // ---- stage 2: the window, win[r*NC + j] = row (centre + r - RY), column (centre + j - RX)
  reg [PW-1:0] win [0:N-1];

  // Sort keys: {valid, valid ? d : 0} orders like the specification's key (valid ? d + 1
  // : 0) and maps one to one onto it, so ranks and the median are the same, and the
  // output needs no decrement: the median is invalid when its top bit is clear, its
  // disparity is the low bits. The border-masked keys of the window of the next ce and
  // every pairwise comparison of them are registered with the window, so the rank stage
  // starts from comparison bits.
  function [KW-1:0] key_of(input [DW:0] vd);  // {valid, d}
    key_of = {vd[DW], vd[DW] ? vd[DW-1:0] : {DW{1'b0}}};
  endfunction
  wire [PW-1:0] nwin [0:N-1];  // the window after this ce's shift
  wire [KW-1:0] nkey [0:N-1];  // its keys, border rule applied with the masks it will have
  genvar r, j, i;
  generate
    for (r = 0; r < NR; r = r + 1) begin : g_nr
      for (j = 0; j < NC; j = j + 1) begin : g_nc
        if (j < NC - 1) begin : g_shift
          assign nwin[r*NC + j] = win[r*NC + j + 1];
        end else begin : g_enter
          assign nwin[r*NC + j] = col_in[PW*r +: PW];
        end
        assign nkey[r*NC + j] = (row_ok_q[r] & col_ok_q[j])
                              ? key_of(nwin[r*NC + j])
                              : key_of(nwin[RY*NC + RX]);
      end
    end
  endgenerate

  // le_q[i*(i-1)/2 + j] = key[j] <= key[i] for j < i; the other order is its complement
  localparam NP = N * (N - 1) / 2;
  reg [KW-1:0] key_q [0:N-1];
  reg [NP-1:0] le_q;
  wire [NP-1:0] le_n;
  generate
    for (i = 1; i < N; i = i + 1) begin : g_le
      for (j = 0; j < i; j = j + 1) begin : g_pair
        assign le_n[i*(i-1)/2 + j] = nkey[j] <= nkey[i];
      end
    end
  endgenerate

  // ---- stage 3: rank every element, pick the middle one ------------------------------
  // lt[j*N + i]: element j is lower than element i in the order (key, index); ties go to
  // the lower index, so every element has a distinct rank and exactly one holds rank MID.
  wire [N*N-1:0] lt;
  generate
    for (i = 0; i < N; i = i + 1) begin : g_rank
      for (j = 0; j < N; j = j + 1) begin : g_cmp
        if (j < i) begin : g_lo
          assign lt[j*N + i] = le_q[i*(i-1)/2 + j];
        end else if (j > i) begin : g_hi
          assign lt[j*N + i] = ~le_q[j*(j-1)/2 + i];
        end else begin : g_self
          assign lt[j*N + i] = 1'b0;
        end
      end
    end
  endgenerate

  // Rank of element i = ones among lt[j*N + i], j = 0..N-1: a balanced tree of ripple
  // adders built from bit-level logic (no '+', so the counts map to plain LUTs instead
  // of carry chains). The N counts are formed side by side in bit-plane order (plane f
  // of all N counts in one N-bit vector): per element the same adders as a count of its
  // own, but Verilator evaluates the N of them with one word operation per gate.
  localparam CW = RW + 1;
  function [CW*N-1:0] ranks(input [N*N-1:0] v);  // plane f of the counts at [f*N +: N]
    integer k, h, f;
    reg [N*CW*N-1:0] acc;  // number k, plane f at [(k*CW + f)*N +: N]
    reg [N-1:0] x, y, c;
    begin
      for (k = 0; k < N; k = k + 1) begin
        acc[k*CW*N +: N] = v[k*N +: N];
        for (f = 1; f < CW; f = f + 1) acc[(k*CW + f)*N +: N] = {N{1'b0}};
      end
      for (h = 1; h < N; h = h * 2)
        for (k = 0; k + h < N; k = k + 2 * h) begin
          c = {N{1'b0}};
          for (f = 0; f < CW; f = f + 1) begin
            x = acc[(k*CW + f)*N +: N];
            y = acc[((k + h)*CW + f)*N +: N];
            acc[(k*CW + f)*N +: N] = x ^ y ^ c;
            c = (x & y) | (x & c) | (y & c);
          end
        end
      ranks = acc[0 +: CW*N];
    end
  endfunction
  /* verilator lint_off WIDTH */  // MID is a 32-bit localparam below 2^RW
  localparam [CW-1:0] MIDV = MID;
  /* verilator lint_on WIDTH */
  wire [CW*N-1:0] rank_p = ranks(lt);
  reg  [N-1:0]    is_mid;  // rank == MID, plane by plane
  integer f2;
  always @* begin
    is_mid = {N{1'b1}};
    for (f2 = 0; f2 < CW; f2 = f2 + 1)
      is_mid = is_mid & (MIDV[f2] ? rank_p[f2*N +: N] : ~rank_p[f2*N +: N]);
  end
  wire [PW-1:0] ctr_p = win[RY*NC + RX];
  wire [15:0]   ctr = {ctr_p[DW], {(15-DW){1'b0}}, ctr_p[DW-1:0]};

  reg [KW-1:0] med;
  integer e;
  always @* begin
    med = {KW{1'b0}};
    for (e = 0; e < N; e = e + 1) med = med | (is_mid[e] ? key_q[e] : {KW{1'b0}});
  end
  wire [15:0] med_pix = med[DW] ? {1'b1, {(15-DW){1'b0}}, med[DW-1:0]} : 16'd0;

  wire [`SM_SIDE_W-1:0] side_q2;
  sm_side_delay #(.DEPTH(2)) u_side (.clk(clk), .rst_n(rst_n), .ce(ce), .d(c_side), .q(side_q2));
  sm_side_delay #(.DEPTH(1)) u_side_out (.clk(clk), .rst_n(rst_n), .ce(ce), .d(side_q2), .q(m_side));

  // The enable is taken with the frame's first centre at this stage, so every pixel of
  // a frame sees the same setting even when the register changes mid-frame.
  reg  en_q;
  wire en = side_q2[`SM_SIDE_SOF] ? enable : en_q;

  integer a2;
  always @(posedge clk) begin
    if (ce) begin
      row_ok_q  <= row_ok;
      col_ok_q  <= col_ok;
      // shift the window one column left; the entering column lands at j = NC-1
      for (a2 = 0; a2 < N; a2 = a2 + 1) begin
        win[a2]   <= nwin[a2];
        key_q[a2] <= nkey[a2];
      end
      le_q <= le_n;
      m_disp <= en ? med_pix : ctr;
    end
  end

  // the enable is control state like the sideband: reset with it
  always @(posedge clk) begin
    if (!rst_n) en_q <= 1'b0;
    else if (ce) en_q <= en;
  end
endmodule
`default_nettype wire
