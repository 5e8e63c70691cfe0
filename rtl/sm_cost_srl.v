`default_nettype none
`include "sm_defs.vh"
// One census bit of sm_cost's folded right-census delay line: L chained segments of
// DEPTH taps each, read at a common tap address. Each segment is a shift register with
// an indexed read, the pattern Yosys' xilinx_srl -variable maps to one SRL16E/SRLC32E
// (DEPTH <= 32), so reading a segment at F taps costs one LUT and no F:1 multiplexer.
//
// q[l] = the bit shifted into segment l addr + 1 shifts ago. Segment 0 shifts in d,
// segment l > 0 shifts in q[l-1]: sm_cost holds addr at DEPTH - 1 on every shift, so
// that is segment l-1's oldest bit, the one leaving it, and the L segments act as one
// delay line of L*DEPTH taps. The outputs are one bit per segment, so sm_cost gets its
// popcount lanes of one census bit as one vector (its bit-plane order) without a
// transpose.
module sm_cost_srl #(
    parameter L     = 16,  // chained segments (popcount lanes)
    parameter DEPTH = 8    // taps per segment (2..256)
) (
    input  wire          clk,
    input  wire          shift,  // shift every segment by one (sm_cost: its ce)
    input  wire [AW-1:0] addr,   // tap 0..DEPTH-1; DEPTH - 1 whenever shift is high
    input  wire          d,
    output wire [L-1:0]  q
);
  localparam AW = $clog2(DEPTH);

  generate
    `SM_BAD_PARAM(g_bad_depth, DEPTH < 2 || DEPTH > 256,
                  ("sm_cost_srl: DEPTH (%0d) must be 2..256", DEPTH))
    `SM_BAD_PARAM(g_bad_l, L < 1, ("sm_cost_srl: L (%0d) must be at least 1", L))
  endgenerate

  wire [L-1:0] d_seg;  // what each segment shifts in
  genvar l;
  generate
    for (l = 0; l < L; l = l + 1) begin : g_seg
      if (l == 0) begin : g_first
        assign d_seg[l] = d;
      end else begin : g_chain
        assign d_seg[l] = q[l-1];
      end
      reg [DEPTH-1:0] sr;
      always @(posedge clk) begin
        if (shift) sr <= {sr[DEPTH-2:0], d_seg[l]};
      end
      // An address past DEPTH - 1 (DEPTH not a power of two) is never applied.
      assign q[l] = sr[addr];
    end
  endgenerate
endmodule
`default_nettype wire
