`default_nettype none
`include "sm_defs.vh"
// WTA uniqueness ratio of the confidence (docs/algorithm.md section 9.3, bits 4:0; model
// confidence() in model/confidence.hpp):
//   ratio = min(31, floor(32 (c2 - c1) / (c2 + 1)))
// c1 is the least cost of the pixel and c2 a least cost over a subset of its levels (or
// c1 itself: wta_row in model/evidence.cpp), so c1 <= c2 always, and then c2 - c1 < c2 + 1
// makes the quotient at most 31 by itself: a 5-bit quotient of 32 (c2 - c1), CW+5 bits,
// by c2 + 1, CW+1 bits (sm_udiv), that never saturates. c1 > c2 cannot come from the WTA
// (the model would give a negative ratio there); this block then gives 0, the ratio of
// no uniqueness, by dividing 0.
// Pipeline (one ce per stage, LATENCY = 6):
//   1  c2 - c1 (0 when c1 > c2), c2 + 1
//   2..6  sm_udiv, one quotient bit per stage; its last register is m_ratio
// Data registers have no reset; the sideband (s_side -> m_side) is reset and delayed by
// LATENCY ce's in sm_side_delay. Everything visible changes only on ce.
module sm_conf_ratio #(
    parameter CW = 6  // cost width (1..8)
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [CW-1:0]         s_c1,    // least cost
    input  wire [CW-1:0]         s_c2,    // least cost away from the least's level
    output wire [`SM_SIDE_W-1:0] m_side,
    output wire [4:0]            m_ratio  // 0..31
);
  localparam LATENCY = 6;  // ce's from s_* to m_*
  localparam QW = 5;       // quotient bits

  generate
    `SM_BAD_PARAM(g_bad_cw, CW < 1 || CW > 8, ("sm_conf_ratio: CW (%0d) must be 1..8", CW))
  endgenerate

  sm_side_delay #(.DEPTH(LATENCY)) u_side (
      .clk  (clk),
      .rst_n(rst_n),
      .ce   (ce),
      .d    (s_side),
      .q    (m_side)
  );

  // ---- stage 1 -------------------------------------------------------------------
  wire [CW:0] diff = {1'b0, s_c2} - {1'b0, s_c1};  // top bit: c1 > c2
  reg  [CW-1:0] diff1;  // c2 - c1, or 0
  reg  [CW:0]   den1;   // c2 + 1
  always @(posedge clk) begin
    if (ce) begin
      diff1 <= diff[CW] ? {CW{1'b0}} : diff[CW-1:0];
      den1  <= {1'b0, s_c2} + 1'b1;
    end
  end

  // ---- stages 2..6 ---------------------------------------------------------------
  sm_udiv #(.NW(CW + QW), .DW(CW + 1), .QW(QW)) u_div (
      .clk(clk),
      .ce (ce),
      .n  ({diff1, {QW{1'b0}}}),  // 32 (c2 - c1)
      .d  (den1),
      .q  (m_ratio)
  );
endmodule
`default_nettype wire
