`default_nettype none
// The last N columns of a sliding window (sm_census: CENSUS columns of pixels;
// sm_sw_aggregate: SW columns of per-level costs). The newest column is a register;
// the N-1 older ones sit in a circular buffer of LUT-RAM instead of a shift register
// of flip-flops (at the paper configuration this turns 3,600 census flip-flops and
// 19,000 aggregation flip-flops into LUT-RAM). Every ce writes the column leaving the
// register over the oldest one, whose read at the write address still sees the old
// word during that ce.
//
// win[a*W +: W] is the column that entered a + 1 ce ago (a = 0: the register).
// Reads are combinational (distributed RAM); latency 1 ce for the newest column.
module sm_colwin #(
    parameter W = 16,  // bits of one column
    parameter N = 3    // columns in the window (3..64)
) (
    input  wire           clk,
    input  wire           rst_n,  // clears the write pointer only
    input  wire           ce,
    input  wire [W-1:0]   col,    // the entering column
    output wire [N*W-1:0] win
);
  localparam NOLD = N - 1;        // older columns
  localparam PTW  = $clog2(NOLD); // circular-buffer index

  generate
    if (N < 3 || N > 64) begin : g_bad_n
      initial $error("sm_colwin: N (%0d) must be 3..64", N);
    end
    if (W < 1) begin : g_bad_w
      initial $error("sm_colwin: W (%0d) must be at least 1", W);
    end
  endgenerate

  /* verilator lint_off WIDTH */  // small constants truncated to the index width
  localparam [PTW-1:0] PLAST = NOLD - 1;
  /* verilator lint_on WIDTH */
  reg [W-1:0] newest_q;
  // Yosys maps a memory this shallow to flip-flops by its own cost model; the attribute
  // asks for the LUT-RAM this buffer was written for.
  (* ram_style = "distributed" *)
  reg [W-1:0]   old_mem [0:NOLD-1];
  reg [PTW-1:0] wptr_q;
  always @(posedge clk) begin
    if (ce) begin
      newest_q        <= col;
      old_mem[wptr_q] <= newest_q;
    end
  end
  always @(posedge clk) begin
    if (!rst_n) wptr_q <= {PTW{1'b0}};
    else if (ce) wptr_q <= (wptr_q == PLAST) ? {PTW{1'b0}} : wptr_q + 1'b1;
  end

  // column of age a >= 1 at (wptr_q - a) mod NOLD; the oldest at the write address
  assign win[0 +: W] = newest_q;
  genvar a;
  generate
    for (a = 1; a < N; a = a + 1) begin : g_old
      if (a == NOLD) begin : g_wr
        assign win[a*W +: W] = old_mem[wptr_q];
      end else begin : g_rd
        /* verilator lint_off WIDTH */  // small constants truncated to the index width
        localparam [PTW-1:0] BACK = NOLD - a;  // = -a mod NOLD
        wire [PTW:0]   sum  = {1'b0, wptr_q} + BACK;
        wire [PTW-1:0] addr = (sum >= NOLD) ? sum - NOLD : sum[PTW-1:0];
        /* verilator lint_on WIDTH */
        assign win[a*W +: W] = old_mem[addr];
      end
    end
  endgenerate
endmodule
`default_nettype wire
