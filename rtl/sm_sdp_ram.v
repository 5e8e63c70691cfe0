`default_nettype none
`include "sm_defs.vh"
// Simple dual-port memory: one write port, one registered read port, no reset, so
// synthesis infers block or distributed RAM (the DP's decision words and trace stack,
// the rectifier's line-buffer and grid banks). Writes and reads have separate enables
// because a write port may run while the pipeline (ce) is stalled (the rectifier's grid
// is written over AXI4-Lite). The users never read an address in the clock it is
// written, so the read-during-write behaviour does not matter.
module sm_sdp_ram #(
    parameter DATA_W = 32,  // bits per word
    parameter DEPTH  = 512  // words
) (
    input  wire              clk,
    input  wire              we,
    input  wire [AW-1:0]     waddr,
    input  wire [DATA_W-1:0] wdata,
    input  wire              re,
    input  wire [AW-1:0]     raddr,
    output reg  [DATA_W-1:0] rdata
);
  localparam AW = (DEPTH > 1) ? $clog2(DEPTH) : 1;

  generate
    `SM_BAD_PARAM(g_bad, DATA_W < 1 || DEPTH < 2,
                  ("sm_sdp_ram: DATA_W (%0d) must be >= 1, DEPTH (%0d) >= 2", DATA_W, DEPTH))
  endgenerate

  // Toggle coverage counts the logic, not the words a memory holds (the usual default of
  // simulators' toggle coverage for arrays); its address and data ports are counted.
  /* verilator coverage_off */
  reg [DATA_W-1:0] mem [0:DEPTH-1];
  /* verilator coverage_on */

  always @(posedge clk) begin
    if (we) mem[waddr] <= wdata;
  end

  always @(posedge clk) begin
    if (re) rdata <= mem[raddr];
  end
endmodule
`default_nettype wire
