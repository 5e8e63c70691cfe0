`default_nettype none
`include "sm_defs.vh"
// The matching cost of L lanes from their Hamming counts h and intensity terms t
// (docs/algorithm.md, section 4): min(h + (t << COST_SHIFT), CB), or CB where the lane's
// right pixel is left of the image (ok low). The term sits at the aggregation's scale
// (it shifts the cost right by COST_SHIFT, which then adds exactly t), and the cap keeps
// the cost inside CB, so every width after sm_cost is the census-only one.
//
// Bit-plane order in and out (bit f of lane l at [f*L + l], sm_popcount's order): the
// addition is a ripple of full adders on whole planes and the cap a compare against the
// constant CB from the top plane down: a few bitwise operations on L-bit vectors, which
// the simulator evaluates word by word. Combinational; sm_cost registers the result.
module sm_cost_addsat #(
    parameter L          = 1,    // lanes
    parameter HW         = 8,    // width of h and of the cost: clog2(CB + 1)
    parameter TW         = 3,    // width of t
    parameter COST_SHIFT = 2,    // plane of h that t's bit 0 is added to
    parameter CB         = 224   // the cap: census bits, the cost of a level off the image
) (
    input  wire [HW*L-1:0] h,
    input  wire [TW*L-1:0] t,
    input  wire [L-1:0]    ok,    // the lane's right pixel is inside the image
    output wire [HW*L-1:0] cost
);
  localparam TS = TW + COST_SHIFT;                 // width of t << COST_SHIFT
  localparam SW = ((HW > TS) ? HW : TS) + 1;       // the sum before the cap
  /* verilator lint_off WIDTH */
  localparam [SW-1:0] CB_V = CB;
  /* verilator lint_on WIDTH */

  generate
    `SM_BAD_PARAM(g_bad_cb, CB < 1 || CB >= (1 << HW), ("sm_cost_addsat: CB (%0d) must fit HW (%0d) bits", CB, HW))
  endgenerate

  // The sum, plane by plane: planes below COST_SHIFT pass, then full adders.
  reg [SW*L-1:0] s;
  always @* begin : a_sum
    integer f;
    reg [L-1:0] c, x, y;
    c = {L{1'b0}};
    for (f = 0; f < SW; f = f + 1) begin
      x = (f < HW) ? h[f*L +: L] : {L{1'b0}};
      y = (f >= COST_SHIFT && f - COST_SHIFT < TW) ? t[(f - COST_SHIFT)*L +: L] : {L{1'b0}};
      s[f*L +: L] = x ^ y ^ c;
      c = (x & y) | (c & (x ^ y));
    end
  end

  // s > CB, from the top plane down: gt where an earlier plane was equal and this one has
  // a 1 over CB's 0.
  reg [L-1:0] gt;
  always @* begin : a_cmp
    integer f;
    reg [L-1:0] eq;
    eq = {L{1'b1}};
    gt = {L{1'b0}};
    for (f = SW - 1; f >= 0; f = f - 1) begin
      if (CB_V[f]) eq = eq & s[f*L +: L];
      else begin
        gt = gt | (eq & s[f*L +: L]);
        eq = eq & ~s[f*L +: L];
      end
    end
  end

  wire [L-1:0] cap = gt | ~ok;
  genvar f;
  generate
    for (f = 0; f < HW; f = f + 1) begin : g_out
      if (CB_V[f]) begin : g_one
        assign cost[f*L +: L] = s[f*L +: L] | cap;
      end else begin : g_zero
        assign cost[f*L +: L] = s[f*L +: L] & ~cap;
      end
    end
  endgenerate
  wire unused_top = |s[SW*L-1:HW*L];  // set only with gt
endmodule
`default_nettype wire
