`default_nettype none
`include "sm_defs.vh"
// Balanced adder tree for the support-weight aggregation's weight sum: the sum of N
// unsigned terms in clog2(N) adder levels, so the reduction keeps a short logic depth
// (a chained sum would be N-1 adders deep). Purely combinational; the caller registers.
module sm_sw_addtree #(
    parameter N  = 5,  // number of terms
    parameter IW = 8,  // width of one term
    parameter OW = 11  // width of the sum: must hold the caller's bound on the total
) (
    input  wire [N*IW-1:0] terms,  // term i at [i*IW +: IW]
    output wire [OW-1:0]   sum
);
  // Leaves padded to a power of two with zeros (the zero adders are optimised away).
  localparam P = (N <= 1) ? 1 : (1 << $clog2(N));

  generate
    `SM_BAD_PARAM(g_bad_n, N < 1, ("sm_sw_addtree: N (%0d) must be at least 1", N))
    `SM_BAD_PARAM(g_bad_ow, OW < IW, ("sm_sw_addtree: OW (%0d) must not be below IW (%0d)", OW, IW))
  endgenerate

  // Heap order: node i is node 2i + node 2i+1, the root is node 1, leaves are P..2P-1.
  // One vector holds every level; split_var lets Verilator see the levels as separate
  // signals instead of one that feeds itself.
  wire [2*P*OW-1:OW] node  /*verilator split_var*/;

  genvar i;
  generate
    for (i = 0; i < P; i = i + 1) begin : g_leaf
      if (i >= N) begin : g_pad
        assign node[(P+i)*OW +: OW] = {OW{1'b0}};
      end else if (OW > IW) begin : g_ext
        assign node[(P+i)*OW +: OW] = {{(OW - IW) {1'b0}}, terms[i*IW +: IW]};
      end else begin : g_same
        assign node[(P+i)*OW +: OW] = terms[i*IW +: IW];
      end
    end
    for (i = 1; i < P; i = i + 1) begin : g_node
      assign node[i*OW +: OW] = node[2*i*OW +: OW] + node[(2*i+1)*OW +: OW];
    end
  endgenerate

  assign sum = node[OW +: OW];
endmodule
`default_nettype wire
