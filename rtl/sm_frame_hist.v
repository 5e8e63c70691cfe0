`default_nettype none
`include "sm_defs.vh"
// Per-frame parameter history (docs/algorithm.md, "Per-frame parameters"): the shadow
// register values of the last four frames, one entry per frame tag (sideband ftag).
// The register file's shadow copy changes at every frame start, but a frame spends up to
// FLUSH_ROWS narrow rows in the pipeline, longer than one frame of 16 rows: a stage far
// down the pipeline that read the shadow copy at its own start of frame could see the
// values of the next frame, or of the one after. Each such stage instead reads the entry
// of its own frame through an sm_frame_sel.
module sm_frame_hist #(
    parameter PW = 8  // bits of the parameter set
) (
    input  wire          clk,
    input  wire          ce,
    input  wire [`SM_SIDE_W-1:0] s_side,  // the first stage's entering beat
    input  wire [PW-1:0] s_par,   // shadow values: the frame whose sof is entering now
    output wire [4*PW-1:0] hist   // entry t (frame tag t) at [t*PW +: PW]
);
  // Data only: an entry is written at its frame's first beat, before any stage reads it.
  reg [PW-1:0] par_q[0:3];
  always @(posedge clk)
    if (ce && s_side[`SM_SIDE_REAL] && s_side[`SM_SIDE_SOF]) par_q[s_side[`SM_SIDE_TAG]] <= s_par;

  genvar t;
  generate
    for (t = 0; t < 4; t = t + 1) begin : g_out
      assign hist[t*PW +: PW] = par_q[t];
    end
  endgenerate
  wire unused_sol = s_side[`SM_SIDE_SOL];  // only real, sof and the frame tag matter
endmodule
`default_nettype wire
