`default_nettype none
`include "sm_defs.vh"
// Sub-pixel fit of the output stage (docs/algorithm.md section 9.1; model fit_q4 in
// model/subpix.hpp): the offset of the minimum of the fit through (-1, cm), (0, c0),
// (1, cp) in 1/16 px,
//   num = cm - cp
//   den = 2 (cm - 2 c0 + cp)          (fit 0, parabola)
//       = 2 max(cm - c0, cp - c0)     (fit 1, equiangular)
//   f   = 0 if den <= 0, else sign(num) min(8, floor((32 |num| + den) / (2 den)))
// i.e. 16 |num| / den rounded half away from zero, clamped to half a level. With
// e = den / 2 the quotient is floor((16 |num| + e) / (2 e)): a CW+5-bit dividend, a
// CW+2-bit divisor and a 4-bit quotient (sm_udiv, which saturates at 15; the clamp to 8
// is then q[3]).
// Pipeline (one ce per stage, LATENCY = 7):
//   1  sign = cm < cp, |cm - cp|, e = cm + cp - 2 c0 (fit 0) or max(cm, cp) - c0 (fit 1)
//   2  16 |num| + e and 2 e; e <= 0 (no fit) makes the dividend 0 and the divisor odd,
//      so the quotient is 0 (and -0 = 0): no flag needs to travel beside the division
//   3..6  sm_udiv, one quotient bit per stage; the sign travels beside it
//   7  m = min(8, q), f = sign ? -m : m
// Data registers have no reset; the sideband (s_side -> m_side) is reset and delayed by
// LATENCY ce's in sm_side_delay. Everything visible changes only on ce.
module sm_subpix_fit #(
    parameter CW = 6  // cost width (1..8)
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [CW-1:0]         s_cm,    // A(d - 1)
    input  wire [CW-1:0]         s_c0,    // A(d)
    input  wire [CW-1:0]         s_cp,    // A(d + 1)
    input  wire                  s_fit,   // 0 parabola, 1 equiangular (subpix_fit)
    output wire [`SM_SIDE_W-1:0] m_side,
    output reg  [4:0]            m_frac   // f, two's complement, -8..8
);
  localparam LATENCY = 7;   // ce's from s_* to m_*
  localparam EW = CW + 2;   // e, signed: |e| <= 2 (2^CW - 1) (fit 0)
  localparam NW = CW + 5;   // 16 |num| + e <= 18 (2^CW - 1)
  localparam DW = CW + 2;   // 2 e <= 4 (2^CW - 1)
  localparam QW = 4;        // quotient bits: 0..15, clamped to 8 after

  generate
    `SM_BAD_PARAM(g_bad_cw, CW < 1 || CW > 8, ("sm_subpix_fit: CW (%0d) must be 1..8", CW))
  endgenerate

  sm_side_delay #(.DEPTH(LATENCY)) u_side (
      .clk  (clk),
      .rst_n(rst_n),
      .ce   (ce),
      .d    (s_side),
      .q    (m_side)
  );

  // ---- stage 1 -------------------------------------------------------------------
  wire          lt   = s_cm < s_cp;  // num < 0
  wire [CW-1:0] hi   = lt ? s_cp : s_cm;  // max(cm, cp)
  wire [CW-1:0] lo   = lt ? s_cm : s_cp;
  wire [EW-1:0] e0   = {2'b00, s_cm} + {2'b00, s_cp} - {1'b0, s_c0, 1'b0};
  wire [EW-1:0] e1   = {2'b00, hi} - {2'b00, s_c0};
  reg           neg1;
  reg  [CW-1:0] mag1;  // |num|
  reg  [EW-1:0] e;     // den / 2
  always @(posedge clk) begin
    if (ce) begin
      neg1 <= lt;
      mag1 <= hi - lo;
      e    <= s_fit ? e1 : e0;
    end
  end

  // ---- stage 2 -------------------------------------------------------------------
  wire          pos = ~e[EW-1] && e != {EW{1'b0}};  // den > 0
  // e > 0 fits in EW - 1 bits
  wire [NW-1:0] num = {1'b0, mag1, 4'b0000} + {{(NW - EW + 1) {1'b0}}, e[EW-2:0]};
  reg  [NW-1:0] n2;
  reg  [DW-1:0] d2;
  reg           neg2;
  always @(posedge clk) begin
    if (ce) begin
      n2   <= pos ? num : {NW{1'b0}};
      d2   <= {e[EW-2:0], ~pos};  // 2 e; odd (non-zero) when there is no fit
      neg2 <= neg1;
    end
  end

  // ---- stages 3..6: the quotient, the sign beside it -----------------------------
  wire [QW-1:0] q;
  sm_udiv #(.NW(NW), .DW(DW), .QW(QW)) u_div (
      .clk(clk),
      .ce (ce),
      .n  (n2),
      .d  (d2),
      .q  (q)
  );
  reg [QW-1:0] neg_sr;  // the sign, QW ce's
  always @(posedge clk) begin
    if (ce) neg_sr <= {neg_sr[QW-2:0], neg2};
  end

  // ---- stage 7 -------------------------------------------------------------------
  wire [4:0] m = q[3] ? 5'd8 : {2'b00, q[2:0]};
  always @(posedge clk) begin
    if (ce) m_frac <= neg_sr[QW-1] ? 5'd0 - m : m;
  end
endmodule
`default_nettype wire
