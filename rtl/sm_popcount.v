`default_nettype none
`include "sm_defs.vh"
// Pipelined population count of a ^ b (docs/algorithm.md, section 4: the Hamming
// distance of two census vectors), for L independent lanes side by side (sm_cost: one
// lane per disparity level). A plain $countones, or a binary adder tree, costs 2-3 LUTs
// per bit in Yosys; this is a compressor tree sized for 6-input LUTs, one per lane:
//  - leaves fold the XOR into the first counter: three bit pairs (six inputs) give a
//    2-bit count, one LUT6 per output bit;
//  - then the 6:3 counter stages of sm_bitheap on the bit heap of the leaves' counts,
//    until no column holds more than two bits;
//  - a final two-row adder, a ripple of full adders on whole bit planes (in sm_bitheap:
//    only the planes and carries the heap's final shape can set).
// The counts come out in bit-plane order too (sm_cost passes them on in that order).
// The heap's shape is computed by constant functions from N, so any N works.
//
// Bit-plane order: the inputs and every heap hold bit i of all L lanes together, at
// [i*L +: L] (for L = 1 that is the plain order); the leaves take the input bits q,
// q + NG, q + 2*NG. The logic of a lane is the same as with one instance per lane, but
// every stage becomes a few bitwise operations on long vectors, which Verilator
// evaluates word by word (bit by bit and lane by lane, the paper configuration's 128
// levels made sm_cost ~2/3 of the simulation time).
//
// Latency 2 ce: the two rows left after compression are registered, then their sum.
module sm_popcount #(
    parameter N = 224,  // bits to count (1..1023)
    parameter L = 1     // lanes (1..1024)
) (
    input  wire            clk,
    input  wire            ce,
    input  wire [N*L-1:0]  a,    // bit i of lane l at [i*L + l]
    input  wire [N*L-1:0]  b,
    output wire [OW*L-1:0] cnt   // bit f of lane l at [f*L + l]: popcount(a ^ b), 2 ce later
);
  localparam OW  = $clog2(N + 1);
  localparam NG  = (N + 2) / 3;  // leaf groups of three pairs
  generate
    `SM_BAD_PARAM(g_bad_n, N < 1 || N > 1023, ("sm_popcount: N (%0d) must be 1..1023", N))
    `SM_BAD_PARAM(g_bad_l, L < 1 || L > 1024, ("sm_popcount: L (%0d) must be 1..1024", L))
  endgenerate

  // ---- leaves: 2-bit counts of three XOR'ed pairs ----------------------------------
  // Group q takes input bits q, q + NG and q + 2*NG (bits past N count as 0). The
  // leaves are not registered: at 6-input LUTs, leaves and sm_bitheap's NS stages are 1 + NS
  // levels (5 for N = 225), and the two rows left after them are 2*OW bits a lane
  // against 2*NG leaf bits (the paper configuration's 128 lanes: 2,048 flip-flops
  // instead of 19,200).
  // x_q: input bits q*NG .. q*NG + NG - 1 of a ^ b, zero past N. Formed group by group
  // rather than as one padded a ^ b that is then sliced: Verilator copies every
  // intermediate long vector, and the leaves are the widest stage.
  genvar q;
  generate
    for (q = 0; q < 3; q = q + 1) begin : g_x
      localparam NR = (N - q * NG >= NG) ? NG : (N - q * NG > 0) ? N - q * NG : 0;
      wire [NG*L-1:0] xk;
      if (NR == NG) begin : g_full
        assign xk = a[q*NG*L +: NG*L] ^ b[q*NG*L +: NG*L];
      end else if (NR > 0) begin : g_part
        assign xk = {{((NG - NR) * L) {1'b0}}, a[q*NG*L +: NR*L] ^ b[q*NG*L +: NR*L]};
      end else begin : g_none
        assign xk = {NG * L{1'b0}};
      end
    end
  endgenerate
  wire [NG*L-1:0] x0 = g_x[0].xk;
  wire [NG*L-1:0] x1 = g_x[1].xk;
  wire [NG*L-1:0] x2 = g_x[2].xk;
  // The leaves' heap: weight 1 of every group, then weight 2 (one vector, assigned in
  // two halves: Verilator would build a concatenation of the two every clock).
  wire [2*NG*L-1:0] leaves;
  wire [NG*L-1:0]   x01 = x0 ^ x1;
  assign leaves[0 +: NG*L]    = x01 ^ x2;
  assign leaves[NG*L +: NG*L] = (x0 & x1) | (x2 & x01);

  // ---- compression: the heap of the leaves' bits (NG of weight 1, NG of weight 2) --
  /* verilator coverage_off */  // a constant function: runs at elaboration only
  function [32*OW-1:0] leaf_heights(input integer ng);
    integer c;
    begin
      leaf_heights = {32 * OW{1'b0}};
      for (c = 0; c < OW && c < 2; c = c + 1) leaf_heights[c*32 +: 32] = ng;
    end
  endfunction
  /* verilator coverage_on */
  localparam [32*OW-1:0] H0 = leaf_heights(NG);
  // The pipeline register and the final two-row adder are inside sm_bitheap (REG, ADD):
  // only it knows which planes of the second row and which carries can be set.
  localparam LB = (OW > 1) ? 2 * NG : NG;  // heap bits a lane (N = 1: bit 1 is always 0)
  wire [OW*L-1:0] sum_p;  // bit-plane order
  // The rows themselves are summed in the heap: lint sinks, no logic (row b holds the
  // planes the heap's shape keeps at 0, so they would count as toggle points here).
  /* verilator coverage_off */
  wire [OW*L-1:0] unused_row_a, unused_row_b;
  /* verilator coverage_on */
  sm_bitheap #(.NC(OW), .H0(H0), .L(L), .REG(1), .ADD(1)) u_heap (
      .clk(clk), .ce(ce), .bits(leaves[0 +: LB*L]), .row_a(unused_row_a),
      .row_b(unused_row_b), .sum(sum_p));
  generate
    if (OW == 1) begin : g_one
      wire unused_leaf1 = |leaves[NG*L +: NG*L];
    end
  endgenerate

  reg [OW*L-1:0] cnt_q;
  always @(posedge clk) begin
    if (ce) cnt_q <= sum_p;
  end
  assign cnt = cnt_q;
endmodule
`default_nettype wire
