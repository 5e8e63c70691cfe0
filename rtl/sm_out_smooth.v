`default_nettype none
`include "sm_defs.vh"
// The output words' window stage (docs/algorithm.md 9.7, model/smooth.cpp): edge-preserving
// smoothing of the Q.4 disparity and the stream's confidence. A valid centre's value q
// becomes q + floor(S / K + 1/2): K counts the valid pixels of its 5x5 window inside the
// frame whose value is within thr of q (the centre among them), S sums their differences
// from q. A single pixel's fraction is noisy; its neighbours on the same surface average
// the noise out, and the threshold keeps the mean from crossing a depth edge. How many
// neighbours agree is evidence too: the confidence byte e of the word (9.3) becomes
// 16 (e[7] + e[6] + e[5]) + e[4:0] + 3 K + 2 K8, K8 the window pixels within 8 (1/2 px).
// The valid bit passes unchanged; invalid words pass as they are (their bits 30:24, the
// speckle stage's bit and the failed rules, travel in the confidence's line buffer, which
// an invalid pixel does not use).
//
// The division is a multiplication: floor(U / 2K) = (U * ceil(2^19 / 2K)) >> 19 for every
// U below 2^13 and K <= 25, with U = 2S + K + 128K > 0 (the bias 64 * 2K makes the
// numerator positive for thr <= 63). One small multiplier (a DSP) instead of a divider.
//
// Latency: the output beat after the ce of input beat n is the pixel of input beat
// n - (2*width + 2) - 5 (window delay; line-buffer read, window, sums, numerator and
// confidence, product, word).
module sm_out_smooth #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter DISP      = 128   // disparity levels (the Q.4 value's width)
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [XW-1:0]         width,   // active width
    input  wire                  enable,  // 0: the Q.4 values pass unchanged (same latency)
    input  wire [5:0]            thr,     // greatest |difference| (1/16 px) a window pixel may have
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [31:0]           s_word,  // {1, 7'b0, confidence, Q.4} or {0, speckle, fails, 24'b0}
    output wire [`SM_SIDE_W-1:0] m_side,
    output reg  [31:0]           m_word
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam DW = $clog2(DISP);
  localparam QW = DW + 4;   // Q.4 value (at most 16 (DISP - 1) + 15)
  localparam PW = QW + 1;   // a window pixel: {valid, q}
  localparam R  = 2;        // window rows / columns each side of the centre
  localparam NR = 2 * R + 1;
  localparam N  = NR * NR;
  localparam C  = R * NR + R;  // the centre's index in the window
  localparam TB = 7;        // a kept difference (|d| <= 63) biased by 63: 0..126
  localparam SW = 12;       // sum of the N - 1 biased differences: at most 24 * 126
  localparam KW = 5;        // pixels in the mean, 1..25
  localparam UW = 13;       // the numerator U = 2S + 129K: below 2^13 (docs/algorithm.md 9.7)
  localparam RCW = 19;      // reciprocal ceil(2^18 / K), K = 1 .. 25

  generate
    `SM_BAD_PARAM(g_bad_disp, DISP < `SM_DISP_MIN || DISP > `SM_DISP_MAX || DISP % 2 != 0,
                  ("sm_out_smooth: DISP (%0d) must be even, %0d..%0d", DISP, `SM_DISP_MIN, `SM_DISP_MAX))
  endgenerate

  // ---- window control for the entering beat --------------------------------------
  wire [XW-1:0] s_x;
  wire [`SM_SIDE_W-1:0] c_side;
  wire [XW-1:0] c_x;
  wire [NR-1:0] row_ok;
  wire [NR-1:0] col_ok;
  sm_win_ctrl #(
      .MAX_WIDTH(MAX_WIDTH), .D_ROWS(R), .D_COLS(R), .R_UP(R), .R_DN(R), .R_L(R), .R_R(R)
  ) u_ctrl (
      .clk(clk), .rst_n(rst_n), .ce(ce), .width(width), .s_side(s_side),
      .s_x(s_x), .c_side(c_side), .c_x(c_x), .row_ok(row_ok), .col_ok(col_ok)
  );
  wire unused_cx = &c_x;  // the masks already carry the column position

  // ---- stage 1: line-buffer reads of the entering column ----------------------------
  // The window keeps {valid, q} of all four rows; the confidence is needed only at the
  // centre, two rows up, so its own buffer holds two rows (vga: 2 RAMB36 for both instead
  // of 3 for whole words).
  wire [PW-1:0] s_pix = {s_word[31], s_word[QW-1:0]};
  // the centre's byte: its confidence, or an invalid word's failed rules
  wire [7:0] s_byte = s_word[31] ? s_word[23:16] : {1'b0, s_word[30:24]};
  wire unused_word = ^{s_word[30], s_word[15:QW]};
  wire [PW*(NR-1)-1:0] lb_dout;  // rows live-1 .. live-4
  wire [15:0]          lbc_dout;  // confidence of rows live-1, live-2
  wire [PW-1:0]        lb_live;   // the live row, aligned with the line-buffer read
  sm_linebuf #(.MAX_WIDTH(MAX_WIDTH), .DATA_W(PW), .ROWS(NR - 1)) u_lb (
      .clk(clk), .ce(ce), .col(s_x), .din(s_pix), .dout(lb_dout), .live(lb_live)
  );
  wire [7:0] lbc_live;  // the live row's confidence: only the centre's is used
  sm_linebuf #(.MAX_WIDTH(MAX_WIDTH), .DATA_W(8), .ROWS(R)) u_lbc (
      .clk(clk), .ce(ce), .col(s_x), .din(s_byte), .dout(lbc_dout), .live(lbc_live)
  );
  wire [PW*NR-1:0] col_in;  // the entering column, row NR-1 = live row
  genvar a;
  generate
    for (a = 0; a < NR - 1; a = a + 1) begin : g_rows
      assign col_in[PW*(NR-2-a) +: PW] = lb_dout[PW*a +: PW];
    end
  endgenerate
  assign col_in[PW*(NR-1) +: PW] = lb_live;
  wire [7:0] conf_in = lbc_dout[8 +: 8];  // the centre row's confidence
  wire unused_lbc = ^{lbc_dout[7:0], lbc_live};
  reg [NR-1:0] row_ok_q, col_ok_q;

  // ---- stage 2: the window, win[r*NR + j] = row (centre + r - R), column (centre + j - R);
  // the confidences of columns centre .. centre + R of the centre row; and each
  // neighbour's difference from the centre, kept (within thr, valid, inside the frame)
  // or not.
  reg  [PW-1:0] win [0:N-1];
  reg  [7:0]    cw [0:R];
  wire [PW-1:0] nwin [0:N-1];  // the window after this ce's shift
  wire [7:0]    ncw [0:R];
  wire [`SM_SIDE_W-1:0] side_q1;  // the centre of nwin
  sm_side_delay #(.DEPTH(1)) u_side1 (.clk(clk), .rst_n(rst_n), .ce(ce), .d(c_side), .q(side_q1));
  // thr and enable are taken with the frame's first centre, so every pixel of a frame
  // sees the same setting even when the register changes mid-frame
  reg  [5:0] thr_q;
  reg        en_q;
  wire [5:0] thr_f = side_q1[`SM_SIDE_SOF] ? thr : thr_q;
  wire       en_f  = side_q1[`SM_SIDE_SOF] ? enable : en_q;
  wire [PW-1:0] ctr = nwin[C];
  wire [N*TB-1:0] nterm;  // biased kept differences (63 when left out); the centre's unused
  wire [N-1:0]    nkeep;
  wire [N-1:0]    nnear;  // kept by the confidence's second count: within 8
  genvar r, j;
  generate
    for (j = 0; j <= R; j = j + 1) begin : g_cw
      if (j < R) begin : g_shift
        assign ncw[j] = cw[j+1];
      end else begin : g_enter
        assign ncw[j] = conf_in;
      end
    end
    for (r = 0; r < NR; r = r + 1) begin : g_nr
      for (j = 0; j < NR; j = j + 1) begin : g_nc
        if (j < NR - 1) begin : g_shift
          assign nwin[r*NR + j] = win[r*NR + j + 1];
        end else begin : g_enter
          assign nwin[r*NR + j] = col_in[PW*r +: PW];
        end
        // d + thr in 0 .. 2 thr <=> |d| <= thr; then d + 63 is the biased term
        wire [QW:0] d   = {1'b0, nwin[r*NR + j][QW-1:0]} - {1'b0, ctr[QW-1:0]};
        wire [QW:0] dt  = d + {{(QW - 5) {1'b0}}, thr_f};
        wire        in  = dt <= {{(QW - 6) {1'b0}}, thr_f, 1'b0};
        wire        avail = row_ok_q[r] & col_ok_q[j] & nwin[r*NR + j][QW];
        wire        ok  = avail & in;
        wire [QW:0] d8  = d + 8;
        wire [QW:0] b   = d + 63;
        assign nkeep[r*NR + j] = ok;
        assign nnear[r*NR + j] = avail & (d8 <= 16);
        assign nterm[(r*NR + j)*TB +: TB] = ok ? b[TB-1:0] : 7'd63;
        wire unused_b = ^b[QW:TB];
      end
    end
  endgenerate
  wire unused_ctr_term = ^{nterm[C*TB +: TB], nkeep[C], nnear[C]};

  // the N - 1 neighbours' terms, keep bits and near bits, centre left out
  reg [(N-1)*TB-1:0] term_q;
  reg [N-2:0]        keep_q, near_q;
  // the centre word {en, valid, confidence, q} beside each later stage
  localparam CTW = 1 + 1 + 8 + QW;
  reg [CTW-1:0] ctr1_q, ctr2_q, ctr3_q, ctr4_q;

  // ---- stage 3: sum of the terms and the two pixel counts ---------------------------
  wire [SW-1:0] sum_n;
  wire [KW-1:0] cnt_n, near_n;
  sm_sw_addtree #(.N(N - 1), .IW(TB), .OW(SW)) u_sum (.terms(term_q), .sum(sum_n));
  sm_sw_addtree #(.N(N - 1), .IW(1), .OW(KW)) u_cnt (.terms(keep_q), .sum(cnt_n));
  sm_sw_addtree #(.N(N - 1), .IW(1), .OW(KW)) u_near (.terms(near_q), .sum(near_n));
  reg [SW-1:0] sum_q;
  reg [KW-1:0] k_q, kn_q;  // with the centre

  // ---- stage 4: numerator U = 2S + 129K (S = sum - 63 (N-1)), reciprocal, confidence --
  wire [RCW-1:0] rtab [0:31];
  genvar t;
  generate
    for (t = 0; t < 32; t = t + 1) begin : g_rtab
      if (t >= 1 && t <= N) begin : g_k
        localparam integer RC = ((1 << 18) + t - 1) / t;
        assign rtab[t] = RC[RCW-1:0];
      end else begin : g_none  // no window has that many pixels
        assign rtab[t] = {RCW{1'b0}};
      end
    end
  endgenerate
  /* verilator lint_off WIDTH */  // 129 K and the bias fit UW by the bound above
  wire [UW-1:0] u_n = {sum_q, 1'b0} + {k_q, 2'b00, k_q} - 2 * 63 * (N - 1);
  /* verilator lint_on WIDTH */
  reg [UW-1:0]  u_q;
  reg [RCW-1:0] rc_q;
  // the stream's confidence: at most 48 + 31 + 75 + 50 = 204
  wire [7:0] e2 = ctr2_q[QW +: 8];
  wire [1:0] flags = {1'b0, e2[7]} + {1'b0, e2[6]} + {1'b0, e2[5]};
  wire [7:0] conf_n = {2'b00, flags, 4'b0000} + {3'b000, e2[4:0]} + {2'b00, k_q, 1'b0} + {3'b000, k_q}
                    + {2'b00, kn_q, 1'b0};

  // ---- stage 5: the product; its bits 25:19 are floor(U / 2K) = offset + 64 ---------
  reg [UW+RCW-1:0] p_q;
  wire [6:0] quo = p_q[25:19];
  wire unused_p = ^{p_q[UW+RCW-1:26], p_q[18:0]};

  /* verilator lint_off WIDTH */  // the mean stays within the window's values: no wrap
  wire [QW-1:0] q_out = ctr4_q[QW-1:0] + quo - 64;
  /* verilator lint_on WIDTH */
  wire c4_en = ctr4_q[CTW-1], c4_valid = ctr4_q[CTW-2];

  wire [`SM_SIDE_W-1:0] side_q5;
  sm_side_delay #(.DEPTH(4)) u_side5 (.clk(clk), .rst_n(rst_n), .ce(ce), .d(side_q1), .q(side_q5));
  sm_side_delay #(.DEPTH(1)) u_side6 (.clk(clk), .rst_n(rst_n), .ce(ce), .d(side_q5), .q(m_side));

  integer e;
  always @(posedge clk) begin
    if (ce) begin
      row_ok_q <= row_ok;
      col_ok_q <= col_ok;
      for (e = 0; e < N; e = e + 1) win[e] <= nwin[e];
      for (e = 0; e <= R; e = e + 1) cw[e] <= ncw[e];
      term_q   <= {nterm[N*TB-1:(C+1)*TB], nterm[C*TB-1:0]};
      keep_q   <= {nkeep[N-1:C+1], nkeep[C-1:0]};
      near_q   <= {nnear[N-1:C+1], nnear[C-1:0]};
      ctr1_q <= {en_f, ctr[QW], ncw[0], ctr[QW-1:0]};
      sum_q  <= sum_n;
      k_q    <= cnt_n + 1'b1;
      kn_q   <= near_n + 1'b1;
      ctr2_q <= ctr1_q;
      u_q    <= u_n;
      rc_q   <= rtab[k_q];
      ctr3_q <= {ctr2_q[CTW-1 -: 2], ctr2_q[CTW-2] ? conf_n : e2, ctr2_q[QW-1:0]};
      p_q    <= u_q * rc_q;
      ctr4_q <= ctr3_q;
      m_word <= !c4_valid ? {1'b0, ctr4_q[QW +: 7], 24'd0}
              : {1'b1, 7'd0, ctr4_q[QW +: 8], {(16 - QW) {1'b0}}, c4_en ? q_out : ctr4_q[QW-1:0]};
    end
  end

  // the frame's settings are control state like the sideband: reset with it
  always @(posedge clk) begin
    if (!rst_n) begin
      thr_q <= 6'd0;
      en_q  <= 1'b0;
    end else if (ce) begin
      thr_q <= thr_f;
      en_q  <= en_f;
    end
  end
endmodule
`default_nettype wire
