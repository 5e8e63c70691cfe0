`default_nettype none
`include "sm_defs.vh"
// Selects a stage's per-frame parameters from sm_frame_hist. The stage latches its
// inputs at its own start of frame (L); the selector follows a beat stream `ev_side`
// whose sof marks each frame once (E) and presents the entry of the frame the stage
// latches next, from a register:
//  - NEXT = 0: E of frame f comes before L of f and after L of f - 1 (an upstream
//    stream, closer than one frame): the entry of the frame last seen at E;
//  - NEXT = 1: E of frame f comes after L of f and before L of f + 1 (the stage's own
//    output, a few beats after its latch): the entry of the frame after it.
// The value is valid two clocks after E and after the entry is written; every stage
// latches far later than that (docs/algorithm.md, "Per-frame parameters").
module sm_frame_sel #(
    parameter PW   = 8,  // bits of the parameter set
    parameter LSB  = 0,  // first bit of the field this stage uses
    parameter W    = 8,  // bits of that field
    parameter NEXT = 0   // 1: select the frame after the one seen at ev_side
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          ce,
    input  wire [`SM_SIDE_W-1:0] ev_side,
    /* verilator lint_off UNUSEDSIGNAL */  // a stage uses one field of each entry
    input  wire [4*PW-1:0] hist,
    /* verilator lint_on UNUSEDSIGNAL */
    output reg  [W-1:0]  par
);
  generate
    `SM_BAD_PARAM(g_bad_next, NEXT != 0 && NEXT != 1,
                  ("sm_frame_sel: NEXT (%0d) must be 0 or 1", NEXT))
    `SM_BAD_PARAM(g_bad_field, W < 1 || LSB < 0 || LSB + W > PW,
                  ("sm_frame_sel: field [%0d +: %0d] outside the %0d-bit set", LSB, W, PW))
  endgenerate
  localparam [1:0] STEP = NEXT[1:0];

  // Frame tag to select; the first frame after reset has tag 0.
  reg [1:0] tag_q;
  always @(posedge clk) begin
    if (!rst_n) tag_q <= 2'd0;
    else if (ce && ev_side[`SM_SIDE_REAL] && ev_side[`SM_SIDE_SOF]) tag_q <= ev_side[`SM_SIDE_TAG] + STEP;
  end
  // Constant slices and a 4:1 select: an index computed from tag_q would make Yosys
  // build a multiplier (a DSP) and a barrel shifter for what is one LUT per bit.
  wire [W-1:0] e0 = hist[0*PW + LSB +: W];
  wire [W-1:0] e1 = hist[1*PW + LSB +: W];
  wire [W-1:0] e2 = hist[2*PW + LSB +: W];
  wire [W-1:0] e3 = hist[3*PW + LSB +: W];
  always @(posedge clk) begin
    case (tag_q)
      2'd0:    par <= e0;
      2'd1:    par <= e1;
      2'd2:    par <= e2;
      default: par <= e3;
    endcase
  end
  wire unused_sol = ev_side[`SM_SIDE_SOL];  // only real, sof and the frame tag matter
endmodule
`default_nettype wire
