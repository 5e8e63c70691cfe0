`default_nettype none
`include "sm_defs.vh"
// Brightness control of both cameras (docs/algorithm.md, section 1):
//   out = clamp(((in * gain + 128) >> 8) + offset, 0, 255)
// Two beats of latency: the product is registered before the offset and clamp so the
// multiplier can map onto a DSP slice. gain/offset are taken from the register inputs on
// the input sof beat and held for the whole frame, so a register write mid-frame only
// affects the next frame.
module sm_brightness (
    input  wire       clk,
    input  wire       rst_n,
    input  wire       ce,
    input  wire [9:0] gain_l,    // Q2.8, 256 = 1.0
    input  wire [9:0] gain_r,
    input  wire [8:0] offset_l,  // signed, -256..255
    input  wire [8:0] offset_r,
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [7:0] s_left,
    input  wire [7:0] s_right,
    output wire [`SM_SIDE_W-1:0] m_side,
    output reg  [7:0] m_left,
    output reg  [7:0] m_right
);
  localparam [9:0] GAIN_ONE = 10'd256;

  wire in_sof = s_side[`SM_SIDE_SOF];

  // Frame parameters: the live register values on sof, the latched ones after.
  reg  [9:0] gain_l_q, gain_r_q;
  reg  [8:0] off_l_q, off_r_q;
  wire [9:0] gain_l_f = in_sof ? gain_l : gain_l_q;
  wire [9:0] gain_r_f = in_sof ? gain_r : gain_r_q;
  wire [8:0] off_l_f  = in_sof ? offset_l : off_l_q;
  wire [8:0] off_r_f  = in_sof ? offset_r : off_r_q;

  // Stage 1: products; the offset travels with its beat so a new frame's sof entering
  // behind it cannot change it.
  // Bits 6:0 of the product never reach the result, only bit 7 (the rounding bit).
  reg [10:0] prod_l_q, prod_r_q;  // product >> 7
  /* verilator lint_off UNUSEDSIGNAL */  // low product bits below the rounding bit
  wire [17:0] prod_l = s_left * gain_l_f;
  wire [17:0] prod_r = s_right * gain_r_f;
  /* verilator lint_on UNUSEDSIGNAL */
  reg [8:0]  off_l_q2, off_r_q2;

  // Stage 2: round, offset, clamp. ((p + 128) >> 8) is at most 1020 (10 bits); with the
  // 9-bit signed offset the sum lies in -256..1275, 12 bits signed.
  wire [9:0]         sc_l = prod_l_q[10:1] + {9'd0, prod_l_q[0]};
  wire [9:0]         sc_r = prod_r_q[10:1] + {9'd0, prod_r_q[0]};
  wire signed [11:0] sum_l = $signed({2'b00, sc_l}) + {{3{off_l_q2[8]}}, off_l_q2};
  wire signed [11:0] sum_r = $signed({2'b00, sc_r}) + {{3{off_r_q2[8]}}, off_r_q2};

  sm_side_delay #(.DEPTH(2)) u_side (.clk(clk), .rst_n(rst_n), .ce(ce), .d(s_side), .q(m_side));

  function [7:0] clamp8(input signed [11:0] v);
    clamp8 = v[11] ? 8'd0 : (|v[10:8]) ? 8'd255 : v[7:0];
  endfunction

  always @(posedge clk) begin
    if (!rst_n) begin
      gain_l_q <= GAIN_ONE;
      gain_r_q <= GAIN_ONE;
      off_l_q  <= 9'd0;
      off_r_q  <= 9'd0;
    end else if (ce) begin
      gain_l_q <= gain_l_f;
      gain_r_q <= gain_r_f;
      off_l_q  <= off_l_f;
      off_r_q  <= off_r_f;
    end
  end

  always @(posedge clk) begin
    if (ce) begin
      prod_l_q <= prod_l[17:7];
      prod_r_q <= prod_r[17:7];
      off_l_q2 <= off_l_f;
      off_r_q2 <= off_r_f;
      m_left   <= clamp8(sum_l);
      m_right  <= clamp8(sum_r);
    end
  end
endmodule
`default_nettype wire
