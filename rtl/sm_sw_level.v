`default_nettype none
`include "sm_defs.vh"
// One disparity level of the support-weight aggregation (docs/algorithm.md, section 5):
// the weighted sum of the SW x SW window costs of this level, times the reciprocal of
// the weight sum, rounded and saturated. sm_sw_aggregate holds one per level; the
// weighted sums of all levels are one bit heap there (sm_bitheap), which leaves two
// numbers per level, added here. The reciprocal is per pixel and shared by every level.
//
// Latency 3 ce from row_a/row_b to agg (registers araw_q, prod_q, agg):
//   ce a  A_raw = row_a + row_b          (a carry chain)
//   ce b  A_raw * RECIP                  (recip arrives one ce after the rows)
//   ce c  round, shift by 12, saturate: the output register
// (A fourth, delay-only output register would cost CW flip-flops a level, 768 at the
// paper configuration; the saturation's register already ends the path.)
module sm_sw_level #(
    parameter CW = 6,   // shifted / aggregated cost width
    parameter SW = 5,   // window side: SW * SW positions
    parameter RW = 13   // RECIP width: RECIP(1) = 4096
) (
    input  wire             clk,
    input  wire             ce,
    input  wire [AW-1:0]    row_a,  // A_raw = row_a + row_b (modulo 2^AW: it fits)
    input  wire [AW-1:0]    row_b,
    input  wire [RW-1:0]    recip,  // RECIP(weight sum) of the pixel of araw_q
    output reg  [CW-1:0]    agg
);
  localparam CMAX = (1 << CW) - 1;           // largest cost the width allows
  localparam NQ   = SW * SW;                 // window positions
  localparam AW   = $clog2(4 * NQ * CMAX + 1);  // A_raw
  localparam WMAX = 4 * NQ;                  // largest weight sum
  // A_raw <= CMAX * wsum and wsum * RECIP(wsum) <= 4096 + wsum/2, so the product fits
  // in PRW bits: only those are kept (the rest are provably 0).
  localparam PRW  = $clog2(CMAX * (4096 + WMAX / 2) + 1);
  localparam QW   = PRW + 1 - 12;            // (product + 2048) >> 12
  localparam [QW-1:0] OMAX = {{(QW - CW) {1'b0}}, {CW{1'b1}}};

  generate
    `SM_BAD_PARAM(g_bad_cw, CW < 1 || CW > 8, ("sm_sw_level: CW (%0d) must be 1..8", CW))
    `SM_BAD_PARAM(g_bad_sw, SW < 1, ("sm_sw_level: SW (%0d) must be at least 1", SW))
    `SM_BAD_PARAM(g_bad_qw, QW < CW,
                  ("sm_sw_level: product width %0d too narrow for CW %0d", PRW, CW))
  endgenerate

  wire [AW-1:0] araw = row_a + row_b;

  reg  [AW-1:0]    araw_q;
  reg  [PRW-1:0]   prod_q;
  wire [AW+RW-1:0] prod = araw_q * recip;
  wire [PRW:0]     rnd = {1'b0, prod_q} + 2048;
  wire [QW-1:0]    qv = rnd[PRW:12];
  // low bits dropped by the rounding shift; the product's top bits are 0 by the bound
  wire unused_bits = &{rnd[11:0], prod[AW+RW-1:PRW]};

  always @(posedge clk) begin
    if (ce) begin
      araw_q <= araw;
      prod_q <= prod[PRW-1:0];
      agg    <= (qv > OMAX) ? OMAX[CW-1:0] : qv[CW-1:0];
    end
  end
endmodule
`default_nettype wire
