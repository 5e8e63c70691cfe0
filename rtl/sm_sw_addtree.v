`default_nettype none
// Balanced adder tree for the support-weight aggregation: the sum of N unsigned terms
// in clog2(N) adder levels, so the wide per-level reductions keep a short logic depth
// (a chained sum would be N-1 adders deep). Built by recursion on halves, which keeps
// every level a separate signal (no self-feeding vector for the simulator to untangle).
// Purely combinational; the caller registers.
module sm_sw_addtree #(
    parameter N  = 5,  // number of terms
    parameter IW = 8,  // width of one term
    parameter OW = 11  // width of the sum: must hold the caller's bound on the total
) (
    input  wire [N*IW-1:0] terms,  // term i at [i*IW +: IW]
    output wire [OW-1:0]   sum
);
  localparam NA = (N + 1) / 2;  // terms of the lower half
  localparam NB = N / 2;        // terms of the upper half

  generate
    if (N < 1) begin : g_bad_n
      initial $error("sm_sw_addtree: N (%0d) must be at least 1", N);
    end
    if (OW < IW) begin : g_bad_ow
      initial $error("sm_sw_addtree: OW (%0d) must not be below IW (%0d)", OW, IW);
    end

    if (N == 1) begin : g_leaf
      if (OW > IW) begin : g_ext
        assign sum = {{(OW - IW) {1'b0}}, terms};
      end else begin : g_same
        assign sum = terms;
      end
    end else begin : g_split
      wire [OW-1:0] sum_a, sum_b;
      sm_sw_addtree #(.N(NA), .IW(IW), .OW(OW)) u_a (.terms(terms[NA*IW-1:0]), .sum(sum_a));
      sm_sw_addtree #(.N(NB), .IW(IW), .OW(OW)) u_b (.terms(terms[N*IW-1:NA*IW]), .sum(sum_b));
      assign sum = sum_a + sum_b;
    end
  endgenerate
endmodule
`default_nettype wire
