`default_nettype none
`include "sm_defs.vh"
// What the object labeller reads of an output word (docs/algorithm.md 8 and 9.4): its
// valid bit and its Q.4 value rounded to a level, (q4 + 8) >> 4 (at most DISP - 1: q4 <=
// 16 (DISP - 1)), registered so the adder stays out of the labeller's paths. The side
// leaves with it, a beat after it came. The ports carry only those bits: the word's
// other fields and the Q.4 field's bits above the value are no concern of this block.
module sm_obj_level #(
    parameter DISP = 128  // disparity levels (the Q.4 value's width)
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire                  s_valid,  // the word's valid bit
    input  wire [QW-1:0]         s_q4,     // its Q.4 value, 16 d + f
    output reg  [`SM_SIDE_W-1:0] m_side,
    output reg                   m_valid,
    output reg  [DW-1:0]         m_level   // round(q4 / 16)
);
  localparam DW = $clog2(DISP);
  localparam QW = DW + 4;
  // No carry out: q4 + 8 <= 16 (DISP - 1) + 8 < 2^QW.
  wire [QW-1:0] q_round = s_q4 + {{(QW - 4) {1'b0}}, 4'd8};
  wire unused_round = ^q_round[3:0];
  always @(posedge clk) begin
    if (!rst_n) m_side <= {`SM_SIDE_W{1'b0}};
    else if (ce) m_side <= s_side;
    if (ce) begin
      m_valid <= s_valid;
      m_level <= q_round[QW-1:4];
    end
  end
endmodule
`default_nettype wire
