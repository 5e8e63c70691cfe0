`default_nettype none
`include "sm_defs.vh"
// Output ring of the folded support-weight aggregation (sm_sw_aggregate with
// PU < DISP): the PU-level results of the F groups of a beat arrive one group per
// clock, at a fixed distance from the ce that started the beat, and must be presented
// together, on a ce, DELAY ce later. The next beats' groups arrive before that
// (how many depends on the ce gaps), so every beat gets its own slot in a ring of
// LUT-RAM: one memory per group (written only by its group), 2^ceil(log2(DELAY + 1))
// slots deep, read at the slot of the beat DELAY ce back. A 32-deep LUT-RAM holds a
// slot of every group in 2/3 LUT per bit, less than the F:1 or 2:1 multiplexers a
// flip-flop double buffer would need.
//
// The caller guarantees that the last group of a beat is written before the ce that
// presents it (sm_sw_aggregate: (DELAY - 1) * F clocks >= its pipeline depth).
module sm_sw_foldout #(
    parameter W     = 96,  // bits of one group's result
    parameter F     = 8,   // groups (2..)
    parameter DELAY = 5    // ce from the one that starts a beat to the one presenting it
) (
    input  wire           clk,
    input  wire           rst_n,  // resets the slot pointers only
    input  wire           ce,
    input  wire           en,     // din holds group grp of the next beat in order
    input  wire [FGW-1:0] grp,
    input  wire [W-1:0]   din,
    output reg  [F*W-1:0] dout    // group g at [g*W +: W]; changes on ce only
);
  localparam FGW = $clog2(F);
  localparam SB  = $clog2(DELAY + 1);  // slot index: DELAY + 1 beats may be in the ring

  generate
    `SM_BAD_PARAM(g_bad_f, F < 2, ("sm_sw_foldout: F (%0d) must be at least 2", F))
    `SM_BAD_PARAM(g_bad_delay, DELAY < 1, ("sm_sw_foldout: DELAY (%0d) must be at least 1", DELAY))
  endgenerate

  /* verilator lint_off WIDTH */  // small constants truncated to the index widths
  localparam [FGW-1:0] GLAST = F - 1;
  localparam [SB-1:0]  RINIT = (1 << SB) - DELAY;  // = -DELAY mod 2^SB
  /* verilator lint_on WIDTH */

  // The beat started by ce k writes slot k mod 2^SB; ce k reads slot (k - DELAY).
  reg [SB-1:0] wslot_q, rslot_q;
  always @(posedge clk) begin
    if (!rst_n) begin
      wslot_q <= {SB{1'b0}};
      rslot_q <= RINIT;
    end else begin
      if (en && grp == GLAST) wslot_q <= wslot_q + 1'b1;
      if (ce) rslot_q <= rslot_q + 1'b1;
    end
  end

  wire [F*W-1:0] rd;  // every group's word of the slot presented next
  always @(posedge clk) begin
    if (ce) dout <= rd;
  end

  genvar g;
  generate
    for (g = 0; g < F; g = g + 1) begin : g_grp
      /* verilator lint_off WIDTH */
      localparam [FGW-1:0] G = g;
      /* verilator lint_on WIDTH */
      (* ram_style = "distributed" *)
      reg [W-1:0] mem [0:(1<<SB)-1];
      always @(posedge clk) begin
        if (en && grp == G) mem[wslot_q] <= din;
      end
      assign rd[g*W +: W] = mem[rslot_q];
    end
  endgenerate
endmodule
`default_nettype wire
