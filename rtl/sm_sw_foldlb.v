`default_nettype none
// Cost line buffer of the folded support-weight aggregation (sm_sw_aggregate with
// PU < DISP): one word per (column, level group) holding that group's ROWS previous
// row steps, so a column's F groups are F words of a deeper, narrower memory (the same
// bits as sm_linebuf's one word per column, and the same block RAMs' worth) and each
// step reads exactly the group it computes.
//
// The read / shift / write-back of sm_linebuf, advanced by a step enable instead of ce:
// the word read on a step is written back on the next clock (steps or not) with the
// step's live row in front. Consecutive steps address different words (the next group,
// or the next column), so the write-back never races a read of the same word.
module sm_sw_foldlb #(
    parameter DEPTH  = 2560,  // words: columns x 2^ceil(log2(groups))
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
    if (ROWS < 2) begin : g_bad_rows
      initial $error("sm_sw_foldlb: ROWS (%0d) must be at least 2", ROWS);
    end
    if (DEPTH < 2 || DATA_W < 1) begin : g_bad_size
      initial $error("sm_sw_foldlb: DEPTH (%0d) / DATA_W (%0d) too small", DEPTH, DATA_W);
    end
  endgenerate

  // Contents are not reset: sm_win_ctrl masks every row that is not part of the frame.
  reg [WW-1:0]     mem [0:DEPTH-1];
  reg [WW-1:0]     rd_q;    // registered read: the block RAM's output register
  reg [AW-1:0]     addr_q;  // word in rd_q, written back on the next clock
  reg [DATA_W-1:0] din_q;
  reg              wb_q;    // a write-back is due

  always @(posedge clk) begin
    if (wb_q) mem[addr_q] <= {rd_q[WW-DATA_W-1:0], din_q};
    if (en) begin
      rd_q   <= mem[addr];
      addr_q <= addr;
      din_q  <= din;
    end
  end
  always @(posedge clk) begin
    if (!rst_n) wb_q <= 1'b0;
    else wb_q <= en;
  end

  assign col = {rd_q, din_q};
endmodule
`default_nettype wire
