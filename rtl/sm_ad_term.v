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

  genvar l, k, i;
  generate
    for (l = 0; l < L; l = l + 1) begin : g_lane
      wire [7:0] bl = b[8*l +: 8];
      // One subtraction (one carry chain, 8 LUTs, instead of a - b and b - a side by
      // side): d = a - b; where it is negative its low byte inverted is m = |d| - 1, so
      // |d| >> AD_SHIFT = (m >> AD_SHIFT) + c, c = 1 exactly when the low AD_SHIFT bits
      // of m are all ones (the + 1 carries past them). |d| <= 255 keeps the sum in SHW
      // bits. Only the bits the shift keeps go on, and the term is TW bits wide: no wire
      // here is constant by construction.
      wire [8:0]     d    = {1'b0, a} - {1'b0, bl};
      wire           neg  = d[8];
      wire [7:0]     m    = neg ? ~d[7:0] : d[7:0];  // |d| - neg
      wire           c;
      if (AD_SHIFT > 0) begin : g_carry
        assign c = neg && (&m[AD_SHIFT-1:0]);
      end else begin : g_inc
        assign c = neg;
      end
      wire [SHW-1:0] q    = m[7:AD_SHIFT];
      wire [TW-1:0]  term;
      if ((1 << SHW) - 1 > AD_MAX) begin : g_cap  // then SHW >= TW: AD_MAX >= 2^(TW-1)
        // min(q + c, AD_MAX) without an SHW-bit adder: q + c > AD_MAX exactly when
        // 2q + c > 2 AD_MAX, and below the cap only the TW low bits of q + c are kept, an
        // increment written as gates (a carry chain would stop the LUT mapper from
        // merging it with the select).
        /* verilator lint_off WIDTH */
        localparam [SHW:0] MAX2_V = 2 * AD_MAX;
        localparam [TW-1:0] MAX_V = AD_MAX;
        /* verilator lint_on WIDTH */
        wire          over = {q, c} > MAX2_V;
        wire [TW-1:0] inc;
        for (i = 0; i < TW; i = i + 1) begin : g_inc_bit
          if (i == 0) begin : g_b0
            assign inc[0] = q[0] ^ c;
          end else begin : g_bi
            assign inc[i] = q[i] ^ (c && (&q[i-1:0]));
          end
        end
        assign term = over ? MAX_V : inc;
        if (SHW > TW) begin : g_hi
          wire unused_hi = |q[SHW-1:TW];  // read by the compare only
        end
      end else begin : g_nocap  // the shifted difference never exceeds the cap
        wire [SHW-1:0] sh = q + {{(SHW - 1) {1'b0}}, c};
        if (TW > SHW) begin : g_wide
          assign term = {{(TW - SHW) {1'b0}}, sh};
        end else begin : g_fit
          assign term = sh;
        end
      end
      for (k = 0; k < TW; k = k + 1) begin : g_bit
        assign t[k*L + l] = term[k];
      end

    end
  endgenerate
endmodule
`default_nettype wire
