`default_nettype none
`include "sm_defs.vh"
// Column window of the folded support-weight aggregation (sm_sw_aggregate with
// PU < DISP): the previous N columns of the window, each as F level groups, in one
// LUT-RAM addressed by {column slot, group}. A step writes group g of the entering
// column and reads group g of the N previous ones; F steps per beat. Against one word
// per column (sm_colwin) the RAM is F times deeper and F times narrower: the depth
// N * 2^ceil(log2 F) fills the 32- or 64-deep LUT-RAM that a depth-N window wastes.
//
// win[k*W +: W] is the group of the column that entered k + 1 beats before the one
// written now; the oldest (k = N - 1) sits at the write address, whose read still sees
// the old word during the step. Reads are combinational (distributed RAM). Each port
// has its own address counter {slot, group}, so every RAM address comes straight from
// flip-flops (as in sm_colwin).
//
// The RAM is split into banks of at most BANK_W bits, each with its own copy of the
// counters: one copy of an address drove the LUT-RAM of all W bits, and placed and routed
// its route across the RAM set the block's clock (docs/synthesis.md). A copy has its own
// feedback, so synthesis does not merge the copies.
module sm_sw_foldwin #(
    parameter W      = 480,  // bits of one group of one column
    parameter N      = 4,    // previous columns held (1..)
    parameter F      = 8,    // groups, i.e. steps per beat (2..)
    parameter BANK_W = 64    // most bits of a group behind one copy of the counters (1..)
) (
    input  wire           clk,
    input  wire           rst_n,  // resets the address counters only
    input  wire           en,     // a step: groups 0 .. F-1 of a beat on consecutive steps
    input  wire [W-1:0]   col,    // this step's group of the entering column
    output wire [N*W-1:0] win
);
  localparam SLW = (N > 1) ? $clog2(N) : 1;  // slot index
  localparam FGW = $clog2(F);                // group index
  localparam ADW = SLW + FGW;
  localparam DEPTH = ((N > 1) ? N : 2) << FGW;  // N = 1: a slot bit that stays 0
  localparam NB    = (W + BANK_W - 1) / BANK_W;  // banks

  generate
    `SM_BAD_PARAM(g_bad_n, N < 1, ("sm_sw_foldwin: N (%0d) must be at least 1", N))
    `SM_BAD_PARAM(g_bad_f, F < 2, ("sm_sw_foldwin: F (%0d) must be at least 2", F))
    `SM_BAD_PARAM(g_bad_w, W < 1, ("sm_sw_foldwin: W (%0d) must be at least 1", W))
    `SM_BAD_PARAM(g_bad_bank, BANK_W < 1, ("sm_sw_foldwin: BANK_W (%0d) must be at least 1", BANK_W))
  endgenerate

  /* verilator lint_off WIDTH */  // small constants truncated to the index widths
  localparam [SLW-1:0] SLAST = N - 1;
  localparam [FGW-1:0] GLAST = F - 1;
  /* verilator lint_on WIDTH */

  // The address after this step's: next group, or group 0 of the next slot.
  function [ADW-1:0] next_addr(input [ADW-1:0] a);
    reg [SLW-1:0] s;
    reg [FGW-1:0] g;
    begin
      s = a[ADW-1:FGW];
      g = a[FGW-1:0];
      if (g == GLAST) next_addr = {(s == SLAST) ? {SLW{1'b0}} : s + 1'b1, {FGW{1'b0}}};
      else next_addr = {s, g + 1'b1};
    end
  endfunction

  genvar b, k;
  generate
    for (b = 0; b < NB; b = b + 1) begin : g_bank
      localparam LO = b * BANK_W;                             // first bit of the bank
      localparam BW = (W - LO < BANK_W) ? W - LO : BANK_W;  // its bits
      // Yosys maps a memory this shallow to flip-flops by its own cost model; the
      // attribute asks for the LUT-RAM this buffer was written for.
      // Toggle coverage counts the logic, not the words (as sm_sdp_ram): its write data
      // and read addresses are counted.
      /* verilator coverage_off */
      (* ram_style = "distributed" *)
      reg [BW-1:0]  mem [0:DEPTH-1];
      /* verilator coverage_on */
      reg [ADW-1:0] waddr_q;  // {slot of the entering column, group}
      always @(posedge clk) begin
        if (en) mem[waddr_q] <= col[LO +: BW];
      end
      always @(posedge clk) begin
        if (!rst_n) waddr_q <= {ADW{1'b0}};
        else if (en) waddr_q <= next_addr(waddr_q);
      end

      for (k = 0; k < N; k = k + 1) begin : g_col
        if (k == N - 1) begin : g_wr
          assign win[k*W + LO +: BW] = mem[waddr_q];
        end else begin : g_rd
          /* verilator lint_off WIDTH */  // small constants truncated to the index width
          localparam [SLW-1:0] BACK = N - 1 - k;  // = -(1 + k) mod N
          /* verilator lint_on WIDTH */
          reg [ADW-1:0] raddr_q;  // {(write slot + BACK) mod N, group}
          always @(posedge clk) begin
            if (!rst_n) raddr_q <= {BACK, {FGW{1'b0}}};
            else if (en) raddr_q <= next_addr(raddr_q);
          end
          assign win[k*W + LO +: BW] = mem[raddr_q];
        end
      end
    end
  endgenerate
endmodule
`default_nettype wire
