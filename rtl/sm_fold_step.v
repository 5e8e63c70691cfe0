`default_nettype none
`include "sm_defs.vh"
// Sub-step counter of a folded block (docs/algorithm.md "Folded datapath"): a beat's F
// sub-steps run on the F clocks after the ce that precedes it (the next ce samples the
// beat; the input is held until then). A ce restarts the count for the beat entering
// next, and reset starts it for the first beat, so that beat's ce must come at least F
// clocks after rst_n rises. sm_dp, sm_wta and sm_right_wta count with it, so the rule
// and its check are written once.
//   m_run   a sub-step executes on this clock edge
//   m_g     its number: 0, 1, .., F-1 (DOWN = 0) or F-1, .., 0 (DOWN = 1)
//   m_start the count restarts on this edge (reset or ce): a block's own counters beside
//           m_g load their first value on m_start and step on m_step
//   m_step  m_run and not m_start
// Outside synthesis a ce that cuts the sub-steps short is reported: the ce pacing of
// sm_top (a ce at most every F clocks) would be broken. The first ce after reset is
// exempt, since it samples the garbage beat before the stream starts.
module sm_fold_step #(
    parameter F    = 2,  // sub-steps per beat (2..256)
    parameter DOWN = 0   // 1: the sub-steps count down from F-1
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          ce,
    output wire          m_start,
    output wire          m_step,
    output reg           m_run,
    output reg  [GW-1:0] m_g
);
  localparam GW = (F > 1) ? $clog2(F) : 1;
  /* verilator lint_off WIDTH */  // constants truncated to the counter width
  localparam [GW-1:0] G_FIRST = DOWN ? F - 1 : 0;
  localparam [GW-1:0] G_LAST = DOWN ? 0 : F - 1;
  localparam [GW-1:0] G_STEP = DOWN ? -1 : 1;  // all ones: minus one
  /* verilator lint_on WIDTH */

  generate
    `SM_BAD_PARAM(g_bad_f, F < 2 || F > 256, ("sm_fold_step: F (%0d) must be 2..256", F))
    `SM_BAD_PARAM(g_bad_down, DOWN != 0 && DOWN != 1, ("sm_fold_step: DOWN (%0d) must be 0 or 1", DOWN))
  endgenerate

  assign m_start = !rst_n || ce;
  assign m_step  = m_run && !m_start;
  always @(posedge clk) begin
    if (m_start) begin
      m_g   <= G_FIRST;
      m_run <= 1'b1;
    end else if (m_run) begin
      m_g   <= m_g + G_STEP;
      m_run <= (m_g != G_LAST);
    end
  end

`ifndef SYNTHESIS
  reg seen_q;  // a ce since reset
  always @(posedge clk) begin
    if (!rst_n) seen_q <= 1'b0;
    else if (ce) seen_q <= 1'b1;
    if (rst_n && ce && seen_q && m_run && m_g != G_LAST)
      $error("%m: ce at sub-step %0d, the last is %0d (F = %0d): the beat's sub-steps cut short", m_g, G_LAST, F);
  end
`endif
endmodule
`default_nettype wire
