`default_nettype none
`include "sm_defs.vh"
// What the object labeller reads of an output word (docs/algorithm.md 8 and 9.4): its
// valid bit and its Q.4 value rounded to a level, (q4 + 8) >> 4 (at most DISP - 1: q4 <=
// 16 (DISP - 1)), registered so the adder stays out of the labeller's paths. The side
// leaves with it, a beat after it came.
module sm_obj_level #(
    parameter DISP = 128  // disparity levels (the Q.4 value's width)
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [31:0]           s_word,
    output reg  [`SM_SIDE_W-1:0] m_side,
    output reg  [15:0]           m_disp  // {valid, level}
);
  localparam DW = $clog2(DISP);
  localparam QW = DW + 4;
  wire [QW:0] q_round = {1'b0, s_word[QW-1:0]} + 8;
  wire unused_round = ^{q_round[QW], q_round[3:0], s_word[30:QW]};
  always @(posedge clk) begin
    if (!rst_n) m_side <= {`SM_SIDE_W{1'b0}};
    else if (ce) m_side <= s_side;
    if (ce) m_disp <= {s_word[31], {(15 - DW) {1'b0}}, q_round[QW-1:4]};
  end
endmodule
`default_nettype wire
