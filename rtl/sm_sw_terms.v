`default_nettype none
`include "sm_defs.vh"
// Weighted cost bits of the support-weight window (docs/algorithm.md, section 5), the bit
// heap's input for L levels side by side: the weighted cost of window position q is its
// cost shifted by 0, 1 or 2 (weight 1, 2, 4) or 0, so bit g of it is cost plane g, g-1 or
// g-2 of that position, chosen by the position's code (one LUT per bit). sm_sw_aggregate
// uses it for all DISP levels (unfolded) or for the PU levels of one group (folded).
// Purely combinational.
module sm_sw_terms #(
    parameter L  = 128,  // levels side by side (bit-plane order)
    parameter CW = 6,    // cost planes of one position
    parameter SW = 5     // window side: SW * SW positions
) (
    input  wire [NQ*2-1:0]      code,   // code of row k, column c at [(k*SW + c)*2 +: 2]
    input  wire [SW*COLW-1:0]   win,    // column c at [c*COLW +: COLW], row k at [k*LVW +: LVW]
                                        // of it, plane b of a position at [b*L +: L]
    output wire [TP*NQ*L-1:0]   terms   // bit g of position q at [(g*NQ + q)*L +: L]
);
  localparam NQ   = SW * SW;  // window positions
  localparam TP   = CW + 2;   // bit planes of one weighted cost
  localparam LVW  = L * CW;   // cost planes of one position
  localparam COLW = SW * LVW; // one window column

  generate
    `SM_BAD_PARAM(g_bad, L < 1 || CW < 1 || SW < 1,
                  ("sm_sw_terms: L (%0d), CW (%0d) and SW (%0d) must be at least 1", L, CW, SW))
  endgenerate

  genvar k, c, g;
  generate
    for (k = 0; k < SW; k = k + 1) begin : g_trow
      for (c = 0; c < SW; c = c + 1) begin : g_tcol
        localparam Q = k*SW + c;  // window position, as the codes
        wire [1:0] cd = code[Q*2 +: 2];
        wire [L-1:0] m1 = {L{cd == 2'd1}};
        wire [L-1:0] m2 = {L{cd == 2'd2}};
        wire [L-1:0] m4 = {L{cd == 2'd3}};
        wire [LVW-1:0] cp = win[c*COLW + k*LVW +: LVW];  // its CW cost planes
        // Bit g takes plane g (weight 1), g - 1 (weight 2) and g - 2 (weight 4) where
        // those planes exist; one branch per combination, so no constant-zero wires.
        for (g = 0; g < TP; g = g + 1) begin : g_bit
          localparam H1 = g < CW;                // plane g exists
          localparam H2 = g >= 1 && g <= CW;     // plane g - 1 exists
          localparam H4 = g >= 2;                // plane g - 2 exists (g <= CW + 1 always)
          localparam LSB = (g*NQ + Q) * L;       // this bit of this position in terms
          if (H1 && H2 && H4) begin : g_124
            assign terms[LSB +: L] = (cp[g*L +: L] & m1) | (cp[(g-1)*L +: L] & m2) |
                                     (cp[(g-2)*L +: L] & m4);
          end else if (H1 && H2) begin : g_12
            assign terms[LSB +: L] = (cp[g*L +: L] & m1) | (cp[(g-1)*L +: L] & m2);
          end else if (H1) begin : g_1
            assign terms[LSB +: L] = cp[g*L +: L] & m1;
          end else if (H2 && H4) begin : g_24
            assign terms[LSB +: L] = (cp[(g-1)*L +: L] & m2) | (cp[(g-2)*L +: L] & m4);
          end else if (H2) begin : g_2
            assign terms[LSB +: L] = cp[(g-1)*L +: L] & m2;
          end else begin : g_4
            assign terms[LSB +: L] = cp[(g-2)*L +: L] & m4;
          end
        end
      end
    end
  endgenerate
endmodule
`default_nettype wire
