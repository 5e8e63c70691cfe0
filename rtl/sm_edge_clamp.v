`default_nettype none
`include "sm_defs.vh"
// Border clamp of one line of census comparison bits (docs/algorithm.md, section 3): a
// position outside the image takes the bit of the nearest position inside, i.e. of the
// first inside position before the centre and of the last one after it. `ok` is a
// contiguous run that holds the centre (the window masks of sm_win_ctrl), so the first
// inside position is the one whose ok bit is set while its neighbour towards the edge
// is clear: a one-hot select, an AND-OR of at most (N+1)/2 terms per side, then a 2:1
// select per bit. Combinational.
module sm_edge_clamp #(
    parameter N = 15  // positions on the line (odd: the centre is (N-1)/2)
) (
    input  wire [N-1:0] ok,    // position inside the image
    input  wire [N-1:0] bits,  // comparison bit of every position
    output wire [N-1:0] q      // bits with the outside positions clamped
);
  localparam R = (N - 1) / 2;

  generate
    `SM_BAD_PARAM(g_bad_n, N < 3 || N % 2 == 0, ("sm_edge_clamp: N (%0d) must be odd, >= 3", N))
  endgenerate

  // One-hot: the first inside position before the centre (only 1..R can be it) and the
  // last one after it (only R..N-2); positions that can never be it get no bit at all.
  wire [R:1]   first;
  wire [N-2:R] last;
  genvar i;
  generate
    for (i = 1; i <= R; i = i + 1) begin : g_first
      assign first[i] = ok[i] & ~ok[i-1];
    end
    for (i = R; i <= N - 2; i = i + 1) begin : g_last
      assign last[i] = ok[i] & ~ok[i+1];
    end
  endgenerate
  wire lo = |(first & bits[R:1]);
  wire hi = |(last & bits[N-2:R]);
  generate
    for (i = 0; i < N; i = i + 1) begin : g_sel
      if (i < R) begin : g_lo
        assign q[i] = ok[i] ? bits[i] : lo;
      end else if (i > R) begin : g_hi
        assign q[i] = ok[i] ? bits[i] : hi;
      end else begin : g_mid
        assign q[i] = bits[i];
      end
    end
  endgenerate
endmodule
`default_nettype wire
