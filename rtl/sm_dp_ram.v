`default_nettype none
`include "sm_defs.vh"
// Simple dual-port memory of the DP (decision words, trace results): one write port,
// one registered read port, no reset, so synthesis infers block RAM. The users never
// read an address in the clock it is written (double buffering), so the
// read-during-write behaviour does not matter.
module sm_dp_ram #(
    parameter DATA_W = 32,  // word width
    parameter ADDR_W = 9    // address width (depth 2^ADDR_W)
) (
    input  wire              clk,
    input  wire              we,
    input  wire [ADDR_W-1:0] waddr,
    input  wire [DATA_W-1:0] wdata,
    input  wire              re,
    input  wire [ADDR_W-1:0] raddr,
    output reg  [DATA_W-1:0] rdata
);
  generate
    `SM_BAD_PARAM(g_bad, DATA_W < 1 || ADDR_W < 1,
                  ("sm_dp_ram: DATA_W (%0d) and ADDR_W (%0d) must be >= 1", DATA_W, ADDR_W))
  endgenerate

  reg [DATA_W-1:0] mem[0:(1<<ADDR_W)-1];
  always @(posedge clk) begin
    if (we) mem[waddr] <= wdata;
  end
  always @(posedge clk) begin
    if (re) rdata <= mem[raddr];
  end
endmodule
`default_nettype wire
