`default_nettype none
`include "sm_defs.vh"
// Cost line buffer of the folded support-weight aggregation (sm_sw_aggregate with
// PU < DISP): one word per (column, level group) holding that group's ROWS previous
// row steps, so a column's F groups are F words of a deeper, narrower memory (the same
// bits as sm_linebuf's one word per column) and each step reads exactly the group it
// computes.
//
// The read / shift / write-back of sm_linebuf, advanced by a step enable instead of ce:
// the word read on a step is written back on the next clock (steps or not) with the
// step's live row in front. Consecutive steps address different words (the next group,
// or the next column), so the write-back never races a read of the same word.
//
// Depth: a DEPTH that is not a power of two is two power-of-two banks, the largest
// power of two below DEPTH (addresses below it) and the rest rounded up, each its own
// block RAM with its own output register, and one 2:1 choice of their outputs. A single
// memory of DEPTH words would be rounded up to the next power of two by the block RAM
// mapping (320 columns x 16 groups: 8,192 words for 5,120), or cut into many shallow
// slices behind a wide multiplexer; two banks are exact whenever DEPTH has two bits set
// (5,120 = 4,096 + 1,024; 640 columns: 10,240 = 8,192 + 2,048).
module sm_sw_foldlb #(
    parameter DEPTH  = 2560,  // words: addresses 0..DEPTH-1 (columns x 2^ceil(log2(groups)))
    parameter DATA_W = 96,    // bits of one row of one group
    parameter ROWS   = 4      // previous row steps held per word (2..)
) (
    input  wire                       clk,
    input  wire                       rst_n,  // resets the write-back enable only
    input  wire                       en,     // a step: read addr, keep din
    input  wire [AW-1:0]              addr,   // {column, group} of the step
    input  wire [DATA_W-1:0]          din,    // the step's live row
    output wire [(ROWS+1)*DATA_W-1:0] col     // after the step: live row at 0, row
                                              // (live - k) at k*DATA_W
);
  localparam AW = $clog2(DEPTH);
  localparam WW = ROWS * DATA_W;  // memory word

  generate
    `SM_BAD_PARAM(g_bad_rows, ROWS < 2, ("sm_sw_foldlb: ROWS (%0d) must be at least 2", ROWS))
    `SM_BAD_PARAM(g_bad_size, DEPTH < 2 || DATA_W < 1,
                  ("sm_sw_foldlb: DEPTH (%0d) / DATA_W (%0d) too small", DEPTH, DATA_W))
  endgenerate

  reg [AW-1:0]     addr_q;  // word read on the last step, written back on the next clock
  reg [DATA_W-1:0] din_q;
  reg              wb_q;    // a write-back is due
  wire [WW-1:0]    rd;      // the word read on the last step
  always @(posedge clk) begin
    if (en) begin
      addr_q <= addr;
      din_q  <= din;
    end
  end
  always @(posedge clk) begin
    if (!rst_n) wb_q <= 1'b0;
    else wb_q <= en;
  end
  wire [WW-1:0] wdata = {rd[WW-DATA_W-1:0], din_q};

  // Contents are not reset: sm_win_ctrl masks every row that is not part of the frame.
  generate
  if ((1 << AW) == DEPTH) begin : g_one
    reg [WW-1:0] mem [0:DEPTH-1];
    reg [WW-1:0] rd_q;  // registered read: the block RAM's output register
    always @(posedge clk) begin
      if (wb_q) mem[addr_q] <= wdata;
      if (en) rd_q <= mem[addr];
    end
    assign rd = rd_q;
  end else begin : g_two
    localparam D0 = 1 << (AW - 1);                   // bank 0: addresses 0..D0-1
    localparam A1 = (DEPTH - D0 < 2) ? 1 : $clog2(DEPTH - D0);
    localparam D1 = 1 << A1;                         // bank 1: addresses D0..D0+D1-1
    reg [WW-1:0] mem0 [0:D0-1];
    reg [WW-1:0] mem1 [0:D1-1];
    reg [WW-1:0] rd0_q, rd1_q;
    reg          sel_q;  // the word read on the last step is bank 1's
    always @(posedge clk) begin
      if (wb_q && !addr_q[AW-1]) mem0[addr_q[AW-2:0]] <= wdata;
      if (en) rd0_q <= mem0[addr[AW-2:0]];
    end
    always @(posedge clk) begin
      if (wb_q && addr_q[AW-1]) mem1[addr_q[A1-1:0]] <= wdata;
      if (en) rd1_q <= mem1[addr[A1-1:0]];
    end
    always @(posedge clk) begin
      if (en) sel_q <= addr[AW-1];
    end
    assign rd = sel_q ? rd1_q : rd0_q;
  end
  endgenerate

  assign col = {rd, din_q};
endmodule
`default_nettype wire
