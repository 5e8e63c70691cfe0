`default_nettype none
`include "sm_defs.vh"
// A stage's per-frame parameters (docs/algorithm.md, "Per-frame parameters"). The
// register file's shadow copy changes at every frame start, but a frame spends up to
// FLUSH_ROWS narrow rows in the pipeline, longer than one frame of 16 rows: a stage far
// down the pipeline that read the shadow copy at its own start of frame could see the
// values of the next frame, or of the one after. So each such stage keeps its field of
// the last four frames' shadow values, one entry per frame tag (sideband ftag), written
// with the frame's first beat at the first stage (wr_side), and reads the entry of its
// own frame.
//
// The entries are a 4-word LUT-RAM (written on a clock edge, read combinationally): a
// flip-flop history shared by all stages held every field four times (760 flip-flops at
// the paper configuration) and each stage still needed a 4:1 select per bit; the LUT-RAM
// is the select.
//
// The stage latches its inputs at its own start of frame (L); the selector follows a beat
// stream `ev_side` whose sof marks each frame once (E) and presents the entry of the frame
// the stage latches next, from a register:
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
    input  wire [`SM_SIDE_W-1:0] wr_side,  // the first stage's entering beat
    /* verilator lint_off UNUSEDSIGNAL */  // a stage uses one field of the set
    input  wire [PW-1:0] wr_par,   // shadow values: the frame whose sof is entering now
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire [`SM_SIDE_W-1:0] ev_side,
    output reg  [W-1:0]  par
);
  generate
    `SM_BAD_PARAM(g_bad_next, NEXT != 0 && NEXT != 1,
                  ("sm_frame_sel: NEXT (%0d) must be 0 or 1", NEXT))
    `SM_BAD_PARAM(g_bad_field, W < 1 || LSB < 0 || LSB + W > PW,
                  ("sm_frame_sel: field [%0d +: %0d] outside the %0d-bit set", LSB, W, PW))
  endgenerate
  localparam [1:0] STEP = NEXT[1:0];

  // Data only: an entry is written at its frame's first beat, before any stage reads it.
  (* ram_style = "distributed" *)
  reg [W-1:0] ent [0:3];
  always @(posedge clk) begin
    if (ce && wr_side[`SM_SIDE_REAL] && wr_side[`SM_SIDE_SOF]) ent[wr_side[`SM_SIDE_TAG]] <= wr_par[LSB +: W];
  end

  // Frame tag to select; the first frame after reset has tag 0.
  reg [1:0] tag_q;
  always @(posedge clk) begin
    if (!rst_n) tag_q <= 2'd0;
    else if (ce && ev_side[`SM_SIDE_REAL] && ev_side[`SM_SIDE_SOF]) tag_q <= ev_side[`SM_SIDE_TAG] + STEP;
  end
  always @(posedge clk) par <= ent[tag_q];
  wire unused_sol = ev_side[`SM_SIDE_SOL] | wr_side[`SM_SIDE_SOL];  // only real, sof and the tag matter
endmodule
`default_nettype wire
