`default_nettype none
`include "sm_defs.vh"
// Bit-plane order to lane order: P planes of L lanes (plane p, lane l at [p*L + l]) to
// L lanes of P bits (lane l at [l*P +: P]). Pure wiring, every output bit is one input
// bit; written as 8 x 8 bit transposes so that Verilator moves 8 lanes with a few word
// operations instead of one bit at a time (sm_sw_aggregate's two heap rows: 3,328 bits
// a clock at the paper configuration; bit by bit, Verilator built them as one long
// serial chain of shifts and ORs).
//
// The planes of 8 lanes form an 8 x 8 bit matrix in one 64-bit word (row = plane,
// column = lane); three swap stages (Hacker's Delight, section 7-3) transpose it into
// the 8 lanes' values side by side. Planes and lanes are padded to multiples of 8.
module sm_plane2lane #(
    parameter P = 8,   // bits per lane (planes), 1..4096
    parameter L = 128  // lanes, 1..4096
) (
    input  wire [P*L-1:0] planes,  // bit p of lane l at [p*L + l]
    output wire [L*P-1:0] lanes    // lane l at [l*P +: P]
);
  localparam NPB = (P + 7) / 8;  // blocks of 8 planes
  localparam NLG = (L + 7) / 8;  // groups of 8 lanes

  generate
    `SM_BAD_PARAM(g_bad_p, P < 1 || P > 4096, ("sm_plane2lane: P (%0d) must be 1..4096", P))
    `SM_BAD_PARAM(g_bad_l, L < 1 || L > 4096, ("sm_plane2lane: L (%0d) must be 1..4096", L))
  endgenerate

  // Bit (r*8 + c) goes to bit (c*8 + r): each stage swaps the off-diagonal quarters of
  // the 2 x 2, 4 x 4 and 8 x 8 sub-matrices; masks and shifts only, so in hardware the
  // function is a fixed permutation of wires.
  function [63:0] tr8(input [63:0] x);
    reg [63:0] y, z;
    begin
      y   = (x & 64'hAA55AA55AA55AA55) | ((x & 64'h00AA00AA00AA00AA) << 7) |
            ((x >> 7) & 64'h00AA00AA00AA00AA);
      z   = (y & 64'hCCCC3333CCCC3333) | ((y & 64'h0000CCCC0000CCCC) << 14) |
            ((y >> 14) & 64'h0000CCCC0000CCCC);
      tr8 = (z & 64'hF0F0F0F00F0F0F0F) | ((z & 64'h00000000F0F0F0F0) << 28) |
            ((z >> 28) & 64'h00000000F0F0F0F0);
    end
  endfunction

  genvar p, g, b, r, j;
  generate
    for (p = 0; p < 8 * NPB; p = p + 1) begin : g_pp  // plane p, lanes padded to 8*NLG
      wire [8*NLG-1:0] v;
      if (p >= P) begin : g_zero
        assign v = {8 * NLG{1'b0}};
      end else if (8 * NLG == L) begin : g_full
        assign v = planes[p*L +: L];
      end else begin : g_pad
        assign v = {{(8 * NLG - L) {1'b0}}, planes[p*L +: L]};
      end
    end
    for (g = 0; g < NLG; g = g + 1) begin : g_lg
      localparam LG = (L - 8 * g < 8) ? L - 8 * g : 8;  // lanes in this group
      for (b = 0; b < NPB; b = b + 1) begin : g_pb
        localparam NP = (P - 8 * b < 8) ? P - 8 * b : 8;  // planes in this block
        wire [63:0] m;  // row r = plane 8*b + r, column j = lane 8*g + j
        for (r = 0; r < 8; r = r + 1) begin : g_row
          assign m[r*8 +: 8] = g_pp[8*b + r].v[8*g +: 8];
        end
        wire [63:0] mt = tr8(m);  // lane 8*g + j at [j*8 +: 8]
        for (j = 0; j < 8; j = j + 1) begin : g_lane
          if (j < LG) begin : g_out
            assign lanes[(8*g + j)*P + 8*b +: NP] = mt[j*8 +: NP];
            if (NP < 8) begin : g_padp
              wire unused_padp = |mt[j*8 + NP +: 8 - NP];  // padding planes: 0
            end
          end else begin : g_padl
            wire unused_padl = |mt[j*8 +: 8];  // padding lanes: 0
          end
        end
      end
    end
  endgenerate
endmodule
`default_nettype wire
