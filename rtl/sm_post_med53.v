`default_nettype none
`include "sm_defs.vh"
// Post-processing filter: median of 5 rows x 3 columns (filter 3) (docs/algorithm.md, section 7).
// A fixed window shape of sm_post_median; see there for border rule and latency
// (RY = 2, RX = 1).
module sm_post_med53 #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter DISP      = 128   // disparity levels 0..DISP-1
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          ce,
    input  wire [XW-1:0] width,    // active width
    input  wire          enable,   // 0: pass through with the same latency
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [15:0]   s_disp,   // bit 15 valid, low bits disparity
    output wire [`SM_SIDE_W-1:0] m_side,
    output wire [15:0]   m_disp
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  sm_post_median #(.MAX_WIDTH(MAX_WIDTH), .DISP(DISP), .RY(2), .RX(1)) u_med (
      .clk(clk), .rst_n(rst_n), .ce(ce), .width(width), .enable(enable),
      .s_side(s_side), .s_disp(s_disp), .m_side(m_side), .m_disp(m_disp)
  );
endmodule
`default_nettype wire
