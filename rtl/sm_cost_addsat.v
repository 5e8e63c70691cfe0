`default_nettype none
`include "sm_defs.vh"
// The matching cost of L lanes from their Hamming counts h and intensity terms t, at the
// aggregation's scale (docs/algorithm.md, section 4): C = min((h >> COST_SHIFT) + t,
// CB >> COST_SHIFT), or CB >> COST_SHIFT where the lane's right pixel is left of the
// image (ok low). That is min(h + (t << COST_SHIFT), CB) >> COST_SHIFT exactly (the shift
// is monotone and t << COST_SHIFT has no bits below it), and the aggregation reads
// nothing else: the low COST_SHIFT planes of h are not added, capped or stored.
//
// Bit-plane order in and out (bit f of lane l at [f*L + l], sm_popcount's order): the
// addition is a ripple of full adders on whole planes and the cap a compare against the
// constant CB >> COST_SHIFT from the top plane down: a few bitwise operations on L-bit
// vectors, which the simulator evaluates word by word. Combinational; sm_cost registers
// the result.
module sm_cost_addsat #(
    parameter L          = 1,    // lanes
    parameter HW         = 8,    // width of h: clog2(CB + 1)
    parameter TW         = 3,    // width of t
    parameter COST_SHIFT = 2,    // low planes of h below the cost's resolution
    parameter CB         = 224   // census bits: the largest h, the cost of a level off the image
) (
    input  wire [HW*L-1:0] h,
    input  wire [TW*L-1:0] t,
    input  wire [L-1:0]    ok,    // the lane's right pixel is inside the image
    output wire [CW*L-1:0] cost
);
  localparam CM = CB >> COST_SHIFT;                // the cap
  localparam CW = $clog2(CM + 1);                  // cost width: HW - COST_SHIFT
  localparam SW = ((CW > TW) ? CW : TW) + 1;       // the sum before the cap
  /* verilator lint_off WIDTH */
  localparam [SW-1:0] CM_V = CM;
  /* verilator lint_on WIDTH */

  generate
    `SM_BAD_PARAM(g_bad_cb, CB < 1 || CB >= (1 << HW), ("sm_cost_addsat: CB (%0d) must fit HW (%0d) bits", CB, HW))
    `SM_BAD_PARAM(g_bad_shift, COST_SHIFT < 0 || CM < 1,
                  ("sm_cost_addsat: COST_SHIFT (%0d) leaves no cost bits of CB (%0d)", COST_SHIFT, CB))
    if (COST_SHIFT > 0) begin : g_low
      wire unused_low = |h[0 +: COST_SHIFT*L];  // below the cost's resolution
    end
  endgenerate

  // The sum, plane by plane: full adders on h's planes COST_SHIFT.. and t.
  reg [SW*L-1:0] s;
  always @* begin : a_sum
    integer f;
    reg [L-1:0] c, x, y;
    c = {L{1'b0}};
    for (f = 0; f < SW; f = f + 1) begin
      x = (f + COST_SHIFT < HW) ? h[(f + COST_SHIFT)*L +: L] : {L{1'b0}};
      y = (f < TW) ? t[f*L +: L] : {L{1'b0}};
      s[f*L +: L] = x ^ y ^ c;
      c = (x & y) | (c & (x ^ y));
    end
  end

  // s > CM, from the top plane down: gt where an earlier plane was equal and this one has
  // a 1 over CM's 0.
  reg [L-1:0] gt;
  always @* begin : a_cmp
    integer f;
    reg [L-1:0] eq;
    eq = {L{1'b1}};
    gt = {L{1'b0}};
    for (f = SW - 1; f >= 0; f = f - 1) begin
      if (CM_V[f]) eq = eq & s[f*L +: L];
      else begin
        gt = gt | (eq & s[f*L +: L]);
        eq = eq & ~s[f*L +: L];
      end
    end
  end

  wire [L-1:0] cap = gt | ~ok;
  genvar f;
  generate
    for (f = 0; f < CW; f = f + 1) begin : g_out
      if (CM_V[f]) begin : g_one
        assign cost[f*L +: L] = s[f*L +: L] | cap;
      end else begin : g_zero
        assign cost[f*L +: L] = s[f*L +: L] & ~cap;
      end
    end
  endgenerate
  wire unused_top = |s[SW*L-1:CW*L];  // set only with gt
endmodule
`default_nettype wire
