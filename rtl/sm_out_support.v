`default_nettype none
`include "sm_defs.vh"
// The row support of the stream's confidence (docs/algorithm.md 9.7, model
// model/row_support.cpp): after the smoothing, a valid word's confidence c becomes
// min(255, c + 5 R), R the words at +-3, +-6, .. +-15 columns in its own row (10 samples,
// inside the row) that are valid with a Q.4 value within 16 (one pixel) of its own. A
// mismatch island of one wrong level is often wider than the smoothing's 5x5 window but
// narrower than the surfaces around it; a few samples further along the row tell it apart
// (sm_output_study --study window-conf: the confidence's AUC 2.11x the oracle's, 2.39x
// without). Invalid words pass as they are. No line memory: a shift register of the row.
//
// The input is a stream of whole rows (every row, real or virtual, starts with sol), so
// the centre is simply the beat REACH beats back, and a sample lies in the centre's row
// exactly when no row start comes between them: the row starts travel beside the words
// instead of a window controller's column compares.
//
// Latency: the output beat after the ce of input beat n is the pixel of input beat
// n - REACH - 2 (window, samples, sum).
module sm_out_support #(
    parameter DISP = 128  // disparity levels (the Q.4 value's width); no width: rows are
                          // told apart by their sol
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [31:0]           s_word,  // {1, 7'b0, confidence, Q.4} or {0, speckle, fails, 24'b0}
    output wire [`SM_SIDE_W-1:0] m_side,
    output reg  [31:0]           m_word
);
  localparam DW     = $clog2(DISP);
  localparam QW     = DW + 4;  // Q.4 value (at most 16 (DISP - 1) + 15)
  localparam STEP   = 3;       // columns between the row's samples
  localparam REACH  = 15;      // the farthest sample, each side of the centre
  localparam NS     = REACH / STEP;   // samples each side
  localparam NW     = 2 * REACH + 1;  // window columns, the centre at REACH
  localparam TOL    = 16;      // a sample supports the centre within one pixel
  localparam WEIGHT = 5;       // the confidence gains 5 per sample (c <= 204: no saturation
                               // in practice; saturated anyway)
  /* verilator lint_off WIDTH */  // small constants in the widths they are compared in
  localparam [QW:0] TOLV  = TOL;
  localparam [QW:0] TOL2V = 2 * TOL;
  localparam [8:0]  WV    = WEIGHT;
  /* verilator lint_on WIDTH */

  generate
    `SM_BAD_PARAM(g_bad_disp, DISP < `SM_DISP_MIN || DISP > `SM_DISP_MAX || DISP % 2 != 0,
                  ("sm_out_support: DISP (%0d) must be even, %0d..%0d", DISP, `SM_DISP_MIN, `SM_DISP_MAX))
  endgenerate

  // ---- stage 1: the row's last NW words and row starts, entry j = centre + j - REACH --
  // Only the centre's word travels whole; the samples are {valid, q} (the synthesis
  // removes the other bits of the older entries, which nothing reads). Packed vectors: an
  // unpacked array shifted word by word gave GCC an aligned-load pattern to miscompile
  // (docs/performance.md, "No loop vectorization in the Verilated code").
  reg [NW*32-1:0] win_q;
  reg [NW-1:1]    sol_q;  // entry 0's row start decides nothing
  wire [`SM_SIDE_W-1:0] side_q1;  // the centre's sideband
  sm_side_delay #(.DEPTH(REACH + 1)) u_side1 (.clk(clk), .rst_n(rst_n), .ce(ce), .d(s_side), .q(side_q1));

  // ---- stage 2: the samples that support the centre -----------------------------------
  wire [31:0] ctr = win_q[REACH*32 +: 32];
  wire [2*NS-1:0] hit;
  genvar i;
  generate
    for (i = 0; i < 2 * NS; i = i + 1) begin : g_sample
      // samples -REACH .. -STEP, then STEP .. REACH
      localparam integer OFF = (i < NS) ? (i - NS) * STEP : (i - NS + 1) * STEP;
      localparam integer J = REACH + OFF;
      // in the centre's row: no row start after the sample up to the centre (left) or
      // after the centre up to the sample (right)
      wire in_row;
      if (OFF < 0) begin : g_left
        assign in_row = ~|sol_q[REACH:J+1];
      end else begin : g_right
        assign in_row = ~|sol_q[J:REACH+1];
      end
      // |q - centre| <= TOL <=> q - centre + TOL in 0 .. 2 TOL
      wire [QW:0] d = {1'b0, win_q[J*32 +: QW]} - {1'b0, ctr[QW-1:0]} + TOLV;
      assign hit[i] = in_row & win_q[J*32 + 31] & (d <= TOL2V);
    end
  endgenerate
  reg [2*NS-1:0] hit_q;
  reg [31:0]     ctr_q;
  wire [`SM_SIDE_W-1:0] side_q2;
  sm_side_delay #(.DEPTH(1)) u_side2 (.clk(clk), .rst_n(rst_n), .ce(ce), .d(side_q1), .q(side_q2));

  // ---- stage 3: R and the confidence ---------------------------------------------------
  wire [3:0] r_n;
  sm_sw_addtree #(.N(2 * NS), .IW(1), .OW(4)) u_cnt (.terms(hit_q), .sum(r_n));
  wire [8:0] conf_n = {1'b0, ctr_q[23:16]} + WV * {5'd0, r_n};
  wire [7:0] conf_sat = conf_n[8] ? 8'd255 : conf_n[7:0];
  sm_side_delay #(.DEPTH(1)) u_side3 (.clk(clk), .rst_n(rst_n), .ce(ce), .d(side_q2), .q(m_side));

  always @(posedge clk) begin
    if (ce) begin
      win_q  <= {s_word, win_q[NW*32-1:32]};
      sol_q  <= {s_side[`SM_SIDE_SOL], sol_q[NW-1:2]};
      hit_q  <= hit;
      ctr_q  <= ctr;
      m_word <= ctr_q[31] ? {ctr_q[31:24], conf_sat, ctr_q[15:0]} : ctr_q;
    end
  end
endmodule
`default_nettype wire
