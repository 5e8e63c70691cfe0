`default_nettype none
`include "sm_defs.vh"
// The last N columns of a sliding window (sm_census: CENSUS columns of pixels;
// sm_sw_aggregate: SW columns of per-level costs) in a circular buffer of LUT-RAM
// instead of a shift register of flip-flops (at the paper configuration this turns
// 3,600 census flip-flops and 19,000 aggregation flip-flops into LUT-RAM). Every ce
// writes the entering column over the oldest one, whose read at the write address
// still sees the old word during that ce.
//
// win[a*W +: W] is the column that entered a + 1 ce ago. Reads are combinational
// (distributed RAM), so the window changes one clock after the ce that writes it. Each
// read port has its own address register, a counter kept (wptr - 1 - a) mod N, so the
// RAM address comes straight from flip-flops (an address computed from the write
// pointer put an adder and a mux before every read, on the aggregator's longest path).
module sm_colwin #(
    parameter W = 16,  // bits of one column
    parameter N = 3    // columns in the window (3..64)
) (
    input  wire           clk,
    input  wire           rst_n,  // resets the pointers only
    input  wire           ce,
    input  wire [W-1:0]   col,    // the entering column
    output wire [N*W-1:0] win
);
  localparam PTW = $clog2(N);  // circular-buffer index

  generate
    `SM_BAD_PARAM(g_bad_n, N < 3 || N > 64, ("sm_colwin: N (%0d) must be 3..64", N))
    `SM_BAD_PARAM(g_bad_w, W < 1, ("sm_colwin: W (%0d) must be at least 1", W))
  endgenerate

  /* verilator lint_off WIDTH */  // small constants truncated to the index width
  localparam [PTW-1:0] PLAST = N - 1;
  /* verilator lint_on WIDTH */
  // Yosys maps a memory this shallow to flip-flops by its own cost model; the attribute
  // asks for the LUT-RAM this buffer was written for.
  (* ram_style = "distributed" *)
  reg [W-1:0]   mem [0:N-1];
  reg [PTW-1:0] wptr_q;
  always @(posedge clk) begin
    if (ce) mem[wptr_q] <= col;
  end
  always @(posedge clk) begin
    if (!rst_n) wptr_q <= {PTW{1'b0}};
    else if (ce) wptr_q <= (wptr_q == PLAST) ? {PTW{1'b0}} : wptr_q + 1'b1;
  end

  // the column that entered a + 1 ce ago is at (wptr_q - 1 - a) mod N; the oldest at
  // the write address
  genvar a;
  generate
    for (a = 0; a < N; a = a + 1) begin : g_col
      if (a == N - 1) begin : g_wr
        assign win[a*W +: W] = mem[wptr_q];
      end else begin : g_rd
        /* verilator lint_off WIDTH */  // small constants truncated to the index width
        localparam [PTW-1:0] BACK = N - 1 - a;  // = -(1 + a) mod N
        /* verilator lint_on WIDTH */
        reg [PTW-1:0] rptr_q;  // = (wptr_q + BACK) mod N
        always @(posedge clk) begin
          if (!rst_n) rptr_q <= BACK;
          else if (ce) rptr_q <= (rptr_q == PLAST) ? {PTW{1'b0}} : rptr_q + 1'b1;
        end
        assign win[a*W +: W] = mem[rptr_q];
      end
    end
  endgenerate
endmodule
`default_nettype wire
