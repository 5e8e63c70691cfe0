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
  localparam TW  = $clog2(AD_MAX + 1);
  localparam SHW = 8 - AD_SHIFT;  // width of |a - b| >> AD_SHIFT

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
      // subtraction, so the carry chains run in parallel. Only the bits the shift keeps go
      // on, and the term is TW bits wide: no wire here is constant by construction.
      wire [7:0]     diff = (a >= bl) ? a - bl : bl - a;
      wire [SHW-1:0] sh   = diff[7:AD_SHIFT];
      wire [TW-1:0]  term;
      if ((1 << SHW) - 1 > AD_MAX) begin : g_cap  // then SHW >= TW: AD_MAX >= 2^(TW-1)
        /* verilator lint_off WIDTH */
        localparam [SHW-1:0] MAX_V = AD_MAX;
        /* verilator lint_on WIDTH */
        assign term = (sh > MAX_V) ? MAX_V[TW-1:0] : sh[TW-1:0];
      end else if (TW > SHW) begin : g_wide  // the shifted difference never exceeds the cap
        assign term = {{(TW - SHW) {1'b0}}, sh};
      end else begin : g_fit
        assign term = sh;
      end
      for (k = 0; k < TW; k = k + 1) begin : g_bit
        assign t[k*L + l] = term[k];
      end
      if (AD_SHIFT > 0) begin : g_low
        wire unused_low = |diff[AD_SHIFT-1:0];  // below the term's resolution
      end
    end
  endgenerate
endmodule
`default_nettype wire
