`default_nettype none
`include "sm_defs.vh"
// The intensity term of the matching cost (docs/algorithm.md, section 4):
// t = min(|a - b| >> AD_SHIFT, AD_MAX) for L lanes, one left pixel a against L right
// pixels. Census alone cannot tell levels apart on a surface whose census codes repeat
// (a flat wall, a regular texture); the pixel's own brightness can, and a small cap keeps
// the census dominant where the two cameras' brightness differs (measured on the 14
// scenes: docs/evaluation.md, "Intensity term").
//
// Combinational. The right pixels come in level order (sm_cost's pixel delay line); the
// terms leave in bit-plane order (bit k of lane l at [k*L + l]), the order sm_cost adds
// them to the Hamming counts in (sm_cost_addsat).
module sm_ad_term #(
    parameter L        = 1,  // lanes
    parameter AD_SHIFT = 2,  // |a - b| is divided by 2^AD_SHIFT (0..7)
    parameter AD_MAX   = 7   // and capped here (1..15; sm_cost leaves this block out at 0)
) (
    input  wire [7:0]      a,  // left pixel, every lane
    input  wire [8*L-1:0]  b,  // right pixel of lane l at [8*l +: 8]
    output wire [TW*L-1:0] t   // bit k of lane l's term at [k*L + l]
);
  localparam TW = $clog2(AD_MAX + 1);
  /* verilator lint_off WIDTH */
  localparam [7:0] MAX_V = AD_MAX;
  /* verilator lint_on WIDTH */

  generate
    `SM_BAD_PARAM(g_bad_shift, AD_SHIFT < 0 || AD_SHIFT > 7,
                  ("sm_ad_term: AD_SHIFT (%0d) must be 0..7", AD_SHIFT))
    `SM_BAD_PARAM(g_bad_max, AD_MAX < 1 || AD_MAX > 15, ("sm_ad_term: AD_MAX (%0d) must be 1..15", AD_MAX))
    `SM_BAD_PARAM(g_bad_l, L < 1, ("sm_ad_term: L (%0d) must be at least 1", L))
  endgenerate

  genvar l, k;
  generate
    for (l = 0; l < L; l = l + 1) begin : g_lane
      wire [7:0] bl = b[8*l +: 8];
      // Two subtractions side by side, picked by the compare: no negation after the
      // subtraction, so the carry chains run in parallel.
      wire [7:0] diff = (a >= bl) ? a - bl : bl - a;
      wire [7:0] sh   = diff >> AD_SHIFT;
      wire [7:0] term = (sh > MAX_V) ? MAX_V : sh;
      for (k = 0; k < TW; k = k + 1) begin : g_bit
        assign t[k*L + l] = term[k];
      end
      wire unused_term_top = |(term >> TW);  // zero: term <= AD_MAX < 2^TW
    end
  endgenerate
endmodule
`default_nettype wire
