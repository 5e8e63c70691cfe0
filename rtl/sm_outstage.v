`default_nettype none
`include "sm_defs.vh"
// The output stage (docs/algorithm.md section 9): sub-pixel disparity, validity and
// confidence in the 32-bit output word {1, 7'b0, confidence, 16 d_out + fraction}, or
// {0, 0, failed rules, 24'b0} for an invalid pixel.
//
//   aggregated costs --+-> sm_dp ------------------------------> read-out (d, matched, gap, fill)
//   (s_side, s_cost)   +-> sm_wta --> u_rec (3 rows) ----------> record of x      \
//                      +-> sm_right_wta --> u_lr (3 rows) -----> lr of x - d     --> sm_outfields
//                                                                                     |
//   post filters F0..F3 (post_side, post_disp) <-- u_fields (BAND_K + 7 rows) <-------+
//                      +--> sm_outword --> m_side, m_word
//
// The WTA record and the right-view WTA levels are written as the costs stream in and
// read when the DP's read-out emits the pixel, two rows later; the fields sm_outfields
// forms there wait in u_fields until the post filters emit the pixel. sm_line_store
// matches rows by counting SOL beats on both sides, so no latency formula couples the
// blocks. Row stores: the record and lr are read at most two rows and S + 2 beats after
// they are written and rewritten three rows later (the DP's read-out of pixel x comes on
// the entering beat S + 2 + x of two rows down, sm_dp); the fields are read after the
// post filters' BAND_K + 5 rows and a few beats, and rewritten BAND_K + 7 rows later.
// s_cfg: the output registers (sm_outfields' layout) of the frame whose rows the DP
// emits next; latched at the DP read-out's start of frame.
module sm_outstage #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter DISP      = 128,  // disparity levels
    parameter CW        = 6,    // aggregated cost width
    parameter PU        = DISP, // levels per clock (sm_wta, sm_right_wta fold like sm_dp)
    parameter BAND_K    = 8     // look-ahead rows of the band filter F0 (sizes u_fields)
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [XW-1:0]         width,
    input  wire [`SM_SIDE_W-1:0] s_side,     // the DP's input beat
    input  wire [DISP*CW-1:0]    s_cost,
    input  wire [`SM_SIDE_W-1:0] dp_side,    // the DP's read-out
    input  wire [15:0]           dp_disp,
    input  wire                  dp_matched,
    input  wire [7:0]            dp_gap,
    input  wire [DW-1:0]         dp_fill_bg,
    input  wire [CFG_W-1:0]      s_cfg,
    input  wire [`SM_SIDE_W-1:0] post_side,  // the post filters' output
    input  wire [15:0]           post_disp,
    output wire [`SM_SIDE_W-1:0] m_side,
    output wire [31:0]           m_word
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam DW = $clog2(DISP);
  localparam CFG_W = 49;
  localparam FIELDS_W = 2 * DW + 16;
  localparam REC_W = 7 * CW + DW;  // {band, cmax, c2, dw}; c1 = band[2]

  // ---- beside the DP: the WTA record and the right-view WTA ----
  wire [`SM_SIDE_W-1:0] wta_side, rw_side;
  wire [DW-1:0]   wta_dw, rw_lr;
  wire [CW-1:0]   wta_c1, wta_c2, wta_cmax;
  wire [5*CW-1:0] wta_band;
  sm_wta #(.DISP(DISP), .CW(CW), .PU(PU)) u_wta (
      .clk(clk), .rst_n(rst_n), .ce(ce), .s_side(s_side), .s_cost(s_cost),
      .m_side(wta_side), .m_dw(wta_dw), .m_c1(wta_c1), .m_c2(wta_c2), .m_cmax(wta_cmax), .m_band(wta_band)
  );
  wire unused_c1 = ^wta_c1;  // = band[2]
  // the row stores' writers need only their streams' SOL
  wire unused_wsides = ^{wta_side[4:3], wta_side[1:0], rw_side[4:3], rw_side[1:0], f_side[4:3], f_side[1:0]};
  sm_right_wta #(.MAX_WIDTH(MAX_WIDTH), .DISP(DISP), .CW(CW), .PU(PU)) u_rwta (
      .clk(clk), .rst_n(rst_n), .ce(ce), .width(width), .s_side(s_side), .s_cost(s_cost),
      .m_side(rw_side), .m_lr(rw_lr)
  );

  // ---- read at the DP's read-out ----
  wire [XW-1:0]    x_dp, x_lr_unused;
  wire [REC_W-1:0] rec;
  wire [DW-1:0]    lr;
  wire [DW-1:0]    d_dp = dp_disp[DW-1:0];
  wire unused_dp = ^dp_disp[15:DW];
  sm_line_store #(.DATA_W(REC_W), .MAX_WIDTH(MAX_WIDTH), .LINES(3)) u_rec (
      .clk(clk), .rst_n(rst_n), .ce(ce), .w_sol(wta_side[`SM_SIDE_SOL]),
      .w_data({wta_band, wta_cmax, wta_c2, wta_dw}), .r_sol(dp_side[`SM_SIDE_SOL]), .r_x(x_dp), .r_col(x_dp),
      .r_data(rec)
  );
  /* verilator lint_off WIDTH */  // x - d wraps below 0: the row's x < d pixels read anything
  wire [XW-1:0] x_lr = x_dp - d_dp;
  /* verilator lint_on WIDTH */
  sm_line_store #(.DATA_W(DW), .MAX_WIDTH(MAX_WIDTH), .LINES(3)) u_lr (
      .clk(clk), .rst_n(rst_n), .ce(ce), .w_sol(rw_side[`SM_SIDE_SOL]), .w_data(rw_lr),
      .r_sol(dp_side[`SM_SIDE_SOL]), .r_x(x_lr_unused), .r_col(x_lr), .r_data(lr)
  );
  wire unused_rx = ^x_lr_unused;

  // the read-out beat registered beside the stores' words; the frame's registers latched
  // at its first pixel
  reg  [`SM_SIDE_W-1:0] r_side;
  reg  [XW-1:0]         r_x;
  reg  [DW-1:0]         r_d, r_fill;
  reg                   r_matched;
  reg  [7:0]            r_gap;
  reg  [CFG_W-1:0]      cfg_q;
  always @(posedge clk) begin
    if (!rst_n) r_side <= {`SM_SIDE_W{1'b0}};
    else if (ce) r_side <= dp_side;
    if (ce) begin
      r_x       <= x_dp;
      r_d       <= d_dp;
      r_fill    <= dp_fill_bg;
      r_matched <= dp_matched;
      r_gap     <= dp_gap;
      if (dp_side[`SM_SIDE_REAL] && dp_side[`SM_SIDE_SOF]) cfg_q <= s_cfg;
    end
  end
  wire [CFG_W-1:0] cfg = cfg_q;  // the ce of the frame's first pixel loads both

  wire [`SM_SIDE_W-1:0] f_side;
  wire [FIELDS_W-1:0]   fields;
  sm_outfields #(.MAX_WIDTH(MAX_WIDTH), .DISP(DISP), .CW(CW)) u_fields (
      .clk(clk), .rst_n(rst_n), .ce(ce), .s_side(r_side), .s_x(r_x), .s_d(r_d), .s_matched(r_matched),
      .s_gap(r_gap), .s_fill_bg(r_fill), .s_dw(rec[DW-1:0]), .s_c1(rec[DW+4*CW +: CW]), .s_c2(rec[DW +: CW]),
      .s_cmax(rec[DW+CW +: CW]), .s_band(rec[DW+2*CW +: 5*CW]), .s_lr(lr), .s_cfg(cfg),
      .m_side(f_side), .m_fields(fields)
  );

  // ---- after the post filters ----
  wire [XW-1:0]       x_post;
  wire [FIELDS_W-1:0] p_fields;
  sm_line_store #(.DATA_W(FIELDS_W), .MAX_WIDTH(MAX_WIDTH), .LINES(BAND_K + 7)) u_fstore (
      .clk(clk), .rst_n(rst_n), .ce(ce), .w_sol(f_side[`SM_SIDE_SOL]), .w_data(fields),
      .r_sol(post_side[`SM_SIDE_SOL]), .r_x(x_post), .r_col(x_post), .r_data(p_fields)
  );
  reg [`SM_SIDE_W-1:0] p_side;
  reg [15:0]           p_disp;
  always @(posedge clk) begin
    if (!rst_n) p_side <= {`SM_SIDE_W{1'b0}};
    else if (ce) p_side <= post_side;
    if (ce) p_disp <= post_disp;
  end
  sm_outword #(.MAX_WIDTH(MAX_WIDTH), .DISP(DISP)) u_word (
      .clk(clk), .rst_n(rst_n), .ce(ce), .s_side(p_side), .s_disp(p_disp), .s_fields(p_fields),
      .m_side(m_side), .m_word(m_word)
  );
endmodule
`default_nettype wire
