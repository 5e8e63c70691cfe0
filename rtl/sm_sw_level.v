`default_nettype none
// One disparity level of the support-weight aggregation (docs/algorithm.md, section 5):
// the weighted sum of the SW x SW window costs of this level, times the reciprocal of
// the weight sum, rounded and saturated. sm_sw_aggregate holds one per level; the
// weights (codes) and the reciprocal are per pixel and shared by every level.
//
// Latency 4 ce from code/cost to agg (registers araw_q, prod_q, sat_q, agg):
//   ce a  A_raw = sum of w * C over the window (shift and mask, one adder tree)
//   ce b  A_raw * RECIP                  (recip arrives one ce after code/cost)
//   ce c  round, shift by 12, saturate
//   ce d  output register
module sm_sw_level #(
    parameter CW = 6,   // shifted / aggregated cost width
    parameter SW = 5,   // window side: SW * SW positions
    parameter RW = 13   // RECIP width: RECIP(1) = 4096
) (
    input  wire             clk,
    input  wire             ce,
    input  wire [NQ*2-1:0]  wsh,    // position q: log2 of its weight, at [2q +: 2]
    input  wire [NQ*PW-1:0] wmask,  // position q: all ones if its weight is not 0
    input  wire [NQ*CW-1:0] cost,   // shifted cost of position q at [q*CW +: CW]
    input  wire [RW-1:0]    recip,  // RECIP(weight sum) of the pixel of araw_q
    output reg  [CW-1:0]    agg
);
  localparam CMAX = (1 << CW) - 1;           // largest cost the width allows
  localparam NQ   = SW * SW;                 // window positions
  localparam PW   = CW + 2;                  // one weighted cost: C << 2 at most
  localparam RSW  = $clog2(4 * SW * CMAX + 1);  // sum of one window row
  localparam AW   = $clog2(4 * NQ * CMAX + 1);  // A_raw
  localparam WMAX = 4 * NQ;                  // largest weight sum
  // A_raw <= CMAX * wsum and wsum * RECIP(wsum) <= 4096 + wsum/2, so the product fits
  // in PRW bits: only those are kept (the rest are provably 0).
  localparam PRW  = $clog2(CMAX * (4096 + WMAX / 2) + 1);
  localparam QW   = PRW + 1 - 12;            // (product + 2048) >> 12
  localparam [QW-1:0] OMAX = {{(QW - CW) {1'b0}}, {CW{1'b1}}};

  generate
    if (CW < 1 || CW > 8) begin : g_bad_cw
      initial $error("sm_sw_level: CW (%0d) must be 1..8", CW);
    end
    if (SW < 1) begin : g_bad_sw
      initial $error("sm_sw_level: SW (%0d) must be at least 1", SW);
    end
    if (QW < CW) begin : g_bad_qw
      initial $error("sm_sw_level: product width %0d too narrow for CW %0d", PRW, CW);
    end
  endgenerate

  // Row sums, then their sum: two small trees per row beat one flat tree of SW*SW
  // terms in Yosys' mapping (narrower adders, all on carry chains). split_var: Verilator
  // keeps every term and row sum as a variable of its own instead of a read-modify-write
  // of one packed vector per term (the 128 levels' terms are most of its work per clock).
  wire [SW*RSW-1:0] rsum  /*verilator split_var*/;
  genvar k, c;
  generate
    for (k = 0; k < SW; k = k + 1) begin : g_row
      wire [SW*PW-1:0] terms  /*verilator split_var*/;
      for (c = 0; c < SW; c = c + 1) begin : g_term
        localparam Q = k*SW + c;  // window position
        // weight 1 << wsh, or 0: a shift and a mask (one LUT per bit, as a 4:1 mux)
        assign terms[c*PW +: PW] = wmask[Q*PW +: PW] &
                                   ({2'b00, cost[Q*CW +: CW]} << wsh[Q*2 +: 2]);
      end
      sm_sw_addtree #(.N(SW), .IW(PW), .OW(RSW)) u_row (
          .terms(terms), .sum(rsum[k*RSW +: RSW]));
    end
  endgenerate
  wire [AW-1:0] araw;
  sm_sw_addtree #(.N(SW), .IW(RSW), .OW(AW)) u_sum (.terms(rsum), .sum(araw));

  reg  [AW-1:0]    araw_q;
  reg  [PRW-1:0]   prod_q;
  reg  [CW-1:0]    sat_q;
  wire [AW+RW-1:0] prod = araw_q * recip;
  wire [PRW:0]     rnd = {1'b0, prod_q} + 2048;
  wire [QW-1:0]    qv = rnd[PRW:12];
  // low bits dropped by the rounding shift; the product's top bits are 0 by the bound
  wire unused_bits = &{rnd[11:0], prod[AW+RW-1:PRW]};

  always @(posedge clk) begin
    if (ce) begin
      araw_q <= araw;
      prod_q <= prod[PRW-1:0];
      sat_q  <= (qv > OMAX) ? OMAX[CW-1:0] : qv[CW-1:0];
      agg    <= sat_q;
    end
  end
endmodule
`default_nettype wire
