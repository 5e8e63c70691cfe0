`default_nettype none
`include "sm_defs.vh"
// A store of the last LINES lines of a beat stream, read back by another stream of the
// same rows further down the pipeline (the output stage: the WTA record and the
// right-view WTA levels read at the DP's read-out, the output fields read after the post
// filters). Both sides count rows by their SOL beats from reset, so row r of the writer
// and row r of the reader -- the same image row, every row of the stream counted, virtual
// ones too -- meet at the same base address (r mod LINES) * MAX_WIDTH, with no latency
// formula to keep in step with the stages between them. The reader may lag the writer by
// up to LINES - 1 rows (minus the columns it reads ahead: the user's sizing, said where it
// is instantiated), and it picks the column itself (r_col: its own column r_x, or another
// one of its row, e.g. x - d).
// Timing: on a ce the writer's beat is written and the reader's address (its row, r_col)
// is read; r_data holds that word from the ce on, i.e. beside the reader's next beat.
module sm_line_store #(
    parameter DATA_W    = 8,    // bits per word
    parameter MAX_WIDTH = 320,  // widest active line (the stride of a row)
    parameter LINES     = 3     // rows kept
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire                  w_sol,   // the writer's beat is the first of a row
    input  wire [DATA_W-1:0]     w_data,
    input  wire                  r_sol,   // the reader's beat is the first of a row
    output wire [XW-1:0]         r_x,     // the reader's column of its beat
    input  wire [XW-1:0]         r_col,   // column of the reader's row to read
    output wire [DATA_W-1:0]     r_data
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam DEPTH = LINES * MAX_WIDTH;
  localparam AW = $clog2(DEPTH);
  /* verilator lint_off WIDTH */  // constants in the address width
  localparam [AW-1:0] STRIDE = MAX_WIDTH;
  localparam [AW-1:0] LAST = (LINES - 1) * MAX_WIDTH;
  /* verilator lint_on WIDTH */

  generate
    `SM_BAD_PARAM(g_bad, DATA_W < 1 || MAX_WIDTH < 2 || LINES < 2,
                  ("sm_line_store: DATA_W (%0d) >= 1, MAX_WIDTH (%0d) >= 2, LINES (%0d) >= 2", DATA_W, MAX_WIDTH,
                   LINES))
  endgenerate

  // Row base and column of each side: the base steps by a stride at every SOL, wrapping
  // after LINES rows; both start one row "before" base 0, so the first SOL of each is row 0.
  reg  [AW-1:0] wbase_q, rbase_q;
  reg  [XW-1:0] wx_q, rx_q;
  wire [AW-1:0] wbase = !w_sol ? wbase_q : (wbase_q == LAST) ? {AW{1'b0}} : wbase_q + STRIDE;
  wire [AW-1:0] rbase = !r_sol ? rbase_q : (rbase_q == LAST) ? {AW{1'b0}} : rbase_q + STRIDE;
  wire [XW-1:0] wx = w_sol ? {XW{1'b0}} : wx_q + 1'b1;
  assign r_x = r_sol ? {XW{1'b0}} : rx_q + 1'b1;
  always @(posedge clk) begin
    if (!rst_n) begin
      wbase_q <= LAST;
      rbase_q <= LAST;
      wx_q    <= {XW{1'b0}};
      rx_q    <= {XW{1'b0}};
    end else if (ce) begin
      wbase_q <= wbase;
      rbase_q <= rbase;
      wx_q    <= wx;
      rx_q    <= r_x;
    end
  end

  /* verilator lint_off WIDTH */  // the column zero-extended to the address width
  wire [AW-1:0] waddr = wbase + wx;
  wire [AW-1:0] raddr = rbase + r_col;
  /* verilator lint_on WIDTH */
  sm_sdp_ram #(
      .DATA_W(DATA_W),
      .DEPTH (DEPTH)
  ) u_ram (
      .clk  (clk),
      .we   (ce),
      .waddr(waddr),
      .wdata(w_data),
      .re   (ce),
      .raddr(raddr),
      .rdata(r_data)
  );
endmodule
`default_nettype wire
