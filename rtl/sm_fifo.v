`default_nettype none
`include "sm_defs.vh"
// Synchronous first-word-fall-through FIFO. The storage is one block RAM (one write
// port, registered read with enable, no reset); its read register doubles as the output
// register, so the head is visible on dout while dout_valid is high and rd_en pops it.
// A write reaches dout two clocks later when the FIFO was empty. Capacity is DEPTH + 1
// (the RAM plus the output register).
module sm_fifo #(
    parameter DATA_W = 18,  // entry width in bits
    parameter DEPTH  = 512  // RAM entries, a power of two >= 2
) (
    input  wire              clk,
    input  wire              rst_n,
    input  wire              wr_en,       // ignored while full
    input  wire [DATA_W-1:0] din,
    output wire              full,
    input  wire              rd_en,       // pops the head; ignored while !dout_valid
    output reg  [DATA_W-1:0] dout,
    output reg               dout_valid,
    output wire [LW-1:0]     level        // entries held, 0..DEPTH+1
);
  localparam AW = $clog2(DEPTH);
  localparam LW = AW + 1;  // holds DEPTH + 1

  generate
    `SM_BAD_PARAM(g_bad_depth, DEPTH < 2 || (1 << AW) != DEPTH,
                  ("sm_fifo: DEPTH (%0d) must be a power of two >= 2", DEPTH))
  endgenerate

  reg [DATA_W-1:0] mem [0:DEPTH-1];
  // One extra pointer bit tells full from empty.
  reg [AW:0] wr_ptr_q;
  reg [AW:0] rd_ptr_q;

  wire [AW:0] ram_count = wr_ptr_q - rd_ptr_q;
  wire        ram_has   = (wr_ptr_q != rd_ptr_q);
  assign full = (ram_count == DEPTH[AW:0]);
  wire        wr   = wr_en && !full;
  // Refill the output register when it is empty or being popped. The read address never
  // equals the write address of the same clock: reading needs an entry that is already
  // in the RAM, and writing the slot under rd_ptr needs a full RAM, which blocks writes.
  wire        load = ram_has && (!dout_valid || rd_en);

  assign level = ram_count + {{AW{1'b0}}, dout_valid};

  always @(posedge clk) begin
    if (wr) mem[wr_ptr_q[AW-1:0]] <= din;
  end

  always @(posedge clk) begin
    if (load) dout <= mem[rd_ptr_q[AW-1:0]];
  end

  always @(posedge clk) begin
    if (!rst_n) begin
      wr_ptr_q   <= {(AW+1){1'b0}};
      rd_ptr_q   <= {(AW+1){1'b0}};
      dout_valid <= 1'b0;
    end else begin
      if (wr) wr_ptr_q <= wr_ptr_q + 1'b1;
      if (load) rd_ptr_q <= rd_ptr_q + 1'b1;
      if (load) dout_valid <= 1'b1;
      else if (rd_en) dout_valid <= 1'b0;
    end
  end

`ifndef SYNTHESIS
  // Simulation-only invariants (Verilator --assert builds): the pointers never run more
  // than DEPTH apart (overflow), and the output register is only refilled from an entry
  // that is really in the RAM (underflow).
  always @(posedge clk) begin
    if (rst_n) begin
      if (ram_count > DEPTH[AW:0]) $error("sm_fifo: %0d entries in a %0d-entry RAM", ram_count, DEPTH);
      if (load && !ram_has) $error("sm_fifo: read of an empty RAM");
    end
  end
`endif
endmodule
`default_nettype wire
