`default_nettype none
`include "sm_defs.vh"
// Line buffer shared by every windowed stage (docs/algorithm.md, "Shared building
// blocks"). One memory word per column holds that column of the ROWS previous row
// steps, so a whole window column comes out of a single block-RAM read. The word read
// on one ce is shifted by one row and written back, with the live row's value in
// front, on the next ce; consecutive beats hit different columns (width >= 2), so the
// write-back never races the read.
module sm_linebuf #(
    parameter MAX_WIDTH = 320,  // widest active line = words of the memory
    parameter DATA_W    = 8,    // bits per pixel and row
    parameter ROWS      = 14    // previous row steps held per column
) (
    input  wire                   clk,
    input  wire                   ce,
    input  wire [XW-1:0]          col,   // column of the entering beat (sm_win_ctrl.s_x)
    input  wire [DATA_W-1:0]      din,   // the entering beat's value (live row)
    output wire [ROWS*DATA_W-1:0] dout,  // after the ce: row (live - 1 - k) at k*DATA_W
    // After the ce: the entering beat's value, the live row of the column in dout. It is
    // the register the write-back needs anyway; a stage that takes its live row from here
    // does not hold a second copy (at the paper configuration the aggregation's is 776 bits).
    output wire [DATA_W-1:0]      live
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam WW = ROWS * DATA_W;  // memory word
  localparam AW = $clog2(MAX_WIDTH);  // memory address; columns are below MAX_WIDTH

  generate
    `SM_BAD_PARAM(g_bad_rows, ROWS < 1, ("sm_linebuf: ROWS (%0d) must be at least 1", ROWS))
    `SM_BAD_PARAM(g_bad_dw, DATA_W < 1, ("sm_linebuf: DATA_W (%0d) must be at least 1", DATA_W))
    `SM_BAD_PARAM(g_bad_mw, MAX_WIDTH < 2,
                  ("sm_linebuf: MAX_WIDTH (%0d) must be at least 2", MAX_WIDTH))
  endgenerate

  // A column never reaches MAX_WIDTH, so when MAX_WIDTH is a power of two the top bit
  // of col is always 0 and the address drops it.
  wire [AW-1:0] addr = col[AW-1:0];
  generate
    if (XW > AW) begin : g_unused_msb
      wire unused_col_msb = col[XW-1];
    end
  endgenerate

  // Contents are not reset: sm_win_ctrl masks every row that is not part of the frame.
  reg [WW-1:0]     mem [0:MAX_WIDTH-1];
  reg [WW-1:0]     rd_q;   // registered read: the block RAM's output register
  reg [AW-1:0]     col_q;  // address of the word in rd_q, written back on the next ce
  reg [DATA_W-1:0] din_q;

  // The word to write back: every row moves one step older, the live value enters.
  wire [WW-1:0] wr_word;
  generate
    if (ROWS == 1) begin : g_one
      assign wr_word = din_q;
    end else begin : g_shift
      assign wr_word = {rd_q[WW-DATA_W-1:0], din_q};
    end
  endgenerate

  always @(posedge clk) begin
    if (ce) begin
      mem[col_q] <= wr_word;
      rd_q       <= mem[addr];
      col_q      <= addr;
      din_q      <= din;
    end
  end

  assign dout = rd_q;
  assign live = din_q;
endmodule
`default_nettype wire
