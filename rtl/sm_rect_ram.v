`default_nettype none
`include "sm_defs.vh"
// Simple dual-port memory of the rectifier (line-buffer banks and grid banks): one
// write port, one registered read port, no reset, so Yosys maps it to block or
// distributed RAM. Writes and reads have separate enables because the grid is written
// over AXI4-Lite while the pipeline (ce) may be stalled.
module sm_rect_ram #(
    parameter DATA_W = 8,   // bits per word
    parameter DEPTH  = 256  // words
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
    `SM_BAD_PARAM(g_bad_depth, DEPTH < 2, ("sm_rect_ram: DEPTH (%0d) must be at least 2", DEPTH))
  endgenerate

  reg [DATA_W-1:0] mem [0:DEPTH-1];

  always @(posedge clk) begin
    if (we) mem[waddr] <= wdata;
  end

  always @(posedge clk) begin
    if (re) rdata <= mem[raddr];
  end
endmodule
`default_nettype wire
