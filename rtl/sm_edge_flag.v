`default_nettype none
`include "sm_defs.vh"
// Edge flags of the edge-dependent occlusion penalty (docs/algorithm.md, section 6,
// "Edge-dependent penalty"): e(x) = 1 where 1 <= x < W and |L(x) - L(x-1)| > EDGE_T,
// from the left pixel that leaves sm_cost with the beat's matching costs, delivered
// to sm_dp with the same beat's aggregated costs.
//
// The aggregation delays a beat by ROWS * width + COLS beats (a whole number of rows
// plus a constant, sm_sw_aggregate's header), so the flags go through a circular
// buffer of one bit per beat whose read pointer trails the write pointer by that many
// beats, less the two pipeline steps below and less one more: sm_dp takes the flag of
// the beat after the one it samples (`m_edge` one beat ahead), so that it can register
// each level pair's penalty for the next ce.
//   ce m      |s_left - previous s_left| and the start-of-row bit registered
//   ce m + 1  e compared with EDGE_T and written at wp; rp computed for the next read
//   then      read at rp into m_edge on the ce before the DP samples the beat before it
// The buffer is not reset: after reset the first ROWS rows of beats are virtual (the
// pipeline fill), and a row's flags are written before the DP reads them.
module sm_edge_flag #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter ROWS      = 2,    // whole rows of the aggregation's delay ((SW - 1) / 2)
    parameter COLS      = 8     // beats of the aggregation's delay beyond ROWS rows
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          ce,
    input  wire [XW-1:0] width,   // active width; changes only between flushed frames
    input  wire [7:0]    edge_t,  // EDGE_T of the frame whose sof comes next on s_side
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [7:0]    s_left,
    output reg           m_edge   // e of the beat the DP samples on the ce after next
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam DEPTH_MIN = ROWS * MAX_WIDTH + COLS;  // longest delay, plus one entry
  localparam AW = $clog2(DEPTH_MIN);
  localparam DW = $clog2(ROWS * MAX_WIDTH + COLS + 1);  // bits of the delay

  generate
    `SM_BAD_PARAM(g_bad_delay, ROWS < 1 || COLS < 0,
                  ("sm_edge_flag: ROWS (%0d) must be at least 1, COLS (%0d) at least 0", ROWS, COLS))
    `SM_BAD_PARAM(g_bad_short, ROWS * 16 + COLS < 4,
                  ("sm_edge_flag: a delay of %0d beats is too short for the read pipeline", ROWS * 16 + COLS))
  endgenerate

  // Read-to-write distance: the delay less the comparison step, the read step and the
  // beat of look-ahead. A sum of ROWS widths, not a product, so that no multiplier is
  // built; registered, since width holds for whole frames.
  localparam integer GAP0_I = COLS - 3;
  localparam [DW-1:0] GAP0 = GAP0_I[DW-1:0];
  reg [DW-1:0] gap_q;
  integer k;
  reg [DW-1:0] gap;
  always @* begin
    gap = GAP0;
    for (k = 0; k < ROWS; k = k + 1) gap = gap + {{(DW - XW) {1'b0}}, width};
  end
  always @(posedge clk) gap_q <= gap;

  // ---- the flag of each beat -------------------------------------------------------
  reg [7:0] prev_q;   // the previous beat's pixel
  reg [7:0] diff_q;   // |s_left - prev_q| of the beat of the last ce
  reg       sol_q;    // that beat starts a row: its flag is 0
  reg [7:0] edge_t_q;
  wire [8:0] d_lr = {1'b0, s_left} - {1'b0, prev_q};
  wire [7:0] d_abs = d_lr[8] ? prev_q - s_left : d_lr[7:0];
  always @(posedge clk) begin
    if (ce) begin
      prev_q <= s_left;
      diff_q <= d_abs;
      sol_q  <= s_side[`SM_SIDE_SOL];
      // sof is column 0, whose flag is 0 whatever EDGE_T: latched in time for column 1
      if (s_side[`SM_SIDE_REAL] && s_side[`SM_SIDE_SOF]) edge_t_q <= edge_t;
    end
  end
  wire e = !sol_q && (diff_q > edge_t_q);
  wire unused_tag = ^s_side[`SM_SIDE_TAG];  // EDGE_T arrives already selected for the frame

  // ---- the delay: one bit per beat -----------------------------------------------
  reg          mem [0:(1 << AW) - 1];
  reg [AW-1:0] wp_q;
  reg [AW-1:0] rp_q;
  always @(posedge clk) begin
    if (!rst_n) begin
      wp_q <= {AW{1'b0}};
    end else if (ce) begin
      wp_q <= wp_q + 1'b1;
    end
  end
  /* verilator lint_off WIDTH */  // the distance is below 2^AW: truncated to the address
  wire [AW-1:0] gap_a = gap_q;
  /* verilator lint_on WIDTH */
  always @(posedge clk) begin
    if (ce) begin
      mem[wp_q] <= e;
      rp_q      <= wp_q + 1'b1 - gap_a;
      m_edge    <= mem[rp_q];
    end
  end
  generate
    if (DW > AW) begin : g_unused_gap
      wire unused_gap = ^gap_q[DW-1:AW];
    end
  endgenerate
endmodule
`default_nettype wire
