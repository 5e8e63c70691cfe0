`default_nettype none
`include "sm_defs.vh"
// The beat sideband of a pipeline, DEPTH ce stages deep. The sideband is the control
// state of the stages beside it: it is reset, so no phantom or stale real beat leaves a
// block after reset, while the data beside it needs no reset (it means nothing without
// a real beat).
module sm_side_delay #(
    parameter DEPTH = 1  // ce stages from d to q (1..64)
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [`SM_SIDE_W-1:0] d,
    output wire [`SM_SIDE_W-1:0] q
);
  localparam W = `SM_SIDE_W;

  generate
    `SM_BAD_PARAM(g_bad_depth, DEPTH < 1 || DEPTH > 64, ("sm_side_delay: DEPTH (%0d) must be 1..64", DEPTH))
  endgenerate

  reg [DEPTH*W-1:0] sr;  // stage k (0 = nearest d) at [k*W +: W]
  integer k;
  always @(posedge clk) begin
    if (!rst_n) begin
      sr <= {(DEPTH * W) {1'b0}};
    end else if (ce) begin
      sr[0 +: W] <= d;
      for (k = 1; k < DEPTH; k = k + 1) sr[k*W +: W] <= sr[(k-1)*W +: W];
    end
  end
  assign q = sr[(DEPTH-1)*W +: W];
endmodule
`default_nettype wire
