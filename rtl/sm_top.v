`default_nettype none
`include "sm_defs.vh"
// Census stereo matching IP: AXI4-Stream video in (left and right pixels together),
// pre-processing -> main processing -> post-processing, AXI4-Stream disparity out, an
// object-list packet per frame, and AXI4-Lite registers for every run-time parameter.
//
// Every stage between the input sequencer and the output formatter advances on one
// clock enable (docs/algorithm.md, "Streaming protocol"): ce is high when the sequencer
// has a beat (camera pixel or virtual flush pixel) and the output FIFO can take the
// beat that leaves the pipeline. A continuous camera stream with an always-ready output
// therefore runs at one pixel per clock and never stalls.
module sm_top #(
    parameter MAX_WIDTH   = 320,  // widest active line
    parameter MAX_HEIGHT  = 240,  // tallest active frame
    parameter DISP        = 128,  // disparity levels 0..DISP-1
    parameter CENSUS      = 15,   // census window side
    parameter SW          = 5,    // support-weight window side
    parameter RECT_RADIUS = 18,   // rows above/below an output row the rectifier reads (the reference rig needs 18)
    parameter COST_SHIFT  = 2,    // raw Hamming cost >> COST_SHIFT before aggregation
    parameter AD_SHIFT    = 2,    // cost's intensity term: |left - right| >> AD_SHIFT ...
    parameter AD_MAX      = 7,    // ... capped at AD_MAX (0: census only; docs/algorithm.md 4)
    parameter MAX_OBJECTS = 8,    // objects reported per frame
    parameter LABEL_SLOTS = 64,   // equivalence-table entries of the object labeller
    parameter BAND_K      = 8,    // look-ahead rows of the band filter F0 (1..16)
    // Disparity levels computed per clock in cost, aggregation and DP (docs/algorithm.md,
    // "Folded datapath"): 0 = DISP, one pixel per clock; an even divisor of DISP folds
    // the datapath to DISP / PU clocks per pixel for DISP / PU times less of its logic.
    parameter PU          = 0,
    // The speckle stage (docs/algorithm.md 9.8): rows a word waits for its region's
    // verdict, 0 for none. Its labeller takes about 10 clocks a pixel, so it suits the
    // folded configurations; where it is built, the registers reset into its speckle mode
    // (SPECKLE_EN 1, LR_EN and AGREE_EN 0: sm_axil_regs).
    parameter SPECKLE_ROWS   = 0,
    parameter SPECKLE_LABELS = 1024  // its label-table entries
) (
    input  wire        aclk,
    input  wire        aresetn,
    // camera: tdata = {right, left}, tuser = start of frame, tlast = end of line
    input  wire [15:0] s_axis_tdata,
    input  wire        s_axis_tuser,
    input  wire        s_axis_tlast,
    input  wire        s_axis_tvalid,
    output wire        s_axis_tready,
    // disparity (docs/algorithm.md 9.4): tdata = {1, 7'b0, confidence[7:0], 16 d + fraction},
    // or {0, speckle, failed rules[5:0], 24'b0} for an invalid pixel (bit 30: the speckle
    // stage cleared it, SPECKLE_ROWS > 0)
    output wire [31:0] m_axis_tdata,
    output wire        m_axis_tuser,
    output wire        m_axis_tlast,
    output wire        m_axis_tvalid,
    input  wire        m_axis_tready,
    // object list, one packet per frame (docs/algorithm.md section 8)
    output wire [31:0] m_axis_obj_tdata,
    output wire        m_axis_obj_tlast,
    output wire        m_axis_obj_tvalid,
    input  wire        m_axis_obj_tready,
    // host interface
    input  wire [15:0] s_axil_awaddr,
    input  wire        s_axil_awvalid,
    output wire        s_axil_awready,
    input  wire [31:0] s_axil_wdata,
    input  wire [3:0]  s_axil_wstrb,
    input  wire        s_axil_wvalid,
    output wire        s_axil_wready,
    output wire [1:0]  s_axil_bresp,
    output wire        s_axil_bvalid,
    input  wire        s_axil_bready,
    input  wire [15:0] s_axil_araddr,
    input  wire        s_axil_arvalid,
    output wire        s_axil_arready,
    output wire [31:0] s_axil_rdata,
    output wire [1:0]  s_axil_rresp,
    output wire        s_axil_rvalid,
    input  wire        s_axil_rready
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam YW = `SM_COUNT_W(MAX_HEIGHT);
  localparam CB = CENSUS * CENSUS - 1;
  localparam CW = $clog2((CB >> COST_SHIFT) + 1);
  // Register-file port widths (rtl/regmap.json): grid point = {gy, gx} with a
  // power-of-two row of points, object list word index.
  localparam GXB  = `SM_GRID_AB(MAX_WIDTH);
  localparam GYB  = `SM_GRID_AB(MAX_HEIGHT);
  localparam GAW  = 2 + GYB + GXB;
  localparam OIW  = $clog2(4 + 4 * MAX_OBJECTS);
  localparam PUE  = (PU == 0) ? DISP : PU;  // levels per clock
  localparam F    = DISP / PUE;             // clocks per pixel
  localparam DWD  = $clog2(DISP);           // disparity level bits
  localparam DQW  = DWD + 4;                // the output word's Q.4 value bits
  localparam FCW  = (F > 1) ? $clog2(F) : 1;
  localparam IN_DEPTH = 1 << $clog2(MAX_WIDTH + 32);  // input FIFO (sm_seq's depth rule)
  localparam IN_LW    = $clog2(IN_DEPTH) + 1;         // its level, 0..IN_DEPTH + 1
  // Virtual rows that push a frame's tail out: the row delays of every stage
  // (rectify R+1, census, aggregation, DP 2, band filter BAND_K, medians 2+1+2, smoothing
  // 2) plus their column delays (DP skew DISP/2 and the stage pipelines, < DISP/2 + 64
  // beats, the band filter's 1 beat, the smoothing's 7 and the row support's 17) counted
  // in rows of the narrowest line (16). Extra virtual rows only cost idle time.
  localparam BASE_FLUSH_ROWS = (RECT_RADIUS + 1) + (CENSUS - 1) / 2 + (SW - 1) / 2 + 2 + BAND_K + 5 + 2 +
                               (DISP / 2 + 64 + 1 + 7 + 17 + 15) / 16 + 1;
  // the speckle stage: its rows and its queues' SPECKLE_SLACK + 1 beats
  localparam FLUSH_ROWS = BASE_FLUSH_ROWS + ((SPECKLE_ROWS > 0) ? SPECKLE_ROWS + (`SM_SPECKLE_SLACK + 1 + 15) / 16 : 0);
  // Shortest active frame (the HEIGHT register's minimum, HwConfig::min_height): four
  // frames must outlast the pipeline's FLUSH_ROWS narrow rows (per-frame parameters).
  localparam MIN_HEIGHT = (FLUSH_ROWS / 4 + 1 > 16) ? FLUSH_ROWS / 4 + 1 : 16;


  // ---------------------------------------------------------------- registers
  wire [XW-1:0] cfg_width, host_width;
  wire [YW-1:0] cfg_height, host_height;
  wire [9:0]    cfg_gain_l, cfg_gain_r;
  wire [8:0]    cfg_offset_l, cfg_offset_r;
  wire          cfg_rect_enable, cfg_grid_bank;
  wire [7:0]    cfg_occ, cfg_occ_edge, cfg_edge_t;
  wire [63:0]   cfg_sw_table;
  wire [3:0]    cfg_filter_enable;
  wire [7:0]    cfg_obj_near, cfg_obj_tol;
  wire [15:0]   cfg_obj_min_pixels;
  wire [48:0]   cfg_out;
  wire [6:0]    cfg_smooth;
  wire [32:0]   cfg_speckle;
  wire          grid_we;
  wire [31:0]   grid_wdata;
  wire [GAW-1:0] grid_waddr;  // {camera, bank, point}
  wire          frame_start;
  wire [5:0]    seq_err;
  wire          out_overflow;
  wire          core_enable, soft_reset;
  wire [OIW-1:0] obj_rd_idx;
  reg  [31:0]   obj_rd_data_q;

  wire [IN_LW-1:0] in_level;

  // The pipeline restarts on aresetn and on the CONTROL soft-reset pulse; registers keep
  // their values over a soft reset. The pipeline's reset is registered (fan-out), so it
  // is in reset at the edges one clock after those that sample aresetn low. The host
  // side -- the register file, the output formatter, the object packet sender and the
  // list's VALID bit -- takes the pipeline's outputs (frame start, error pulses, FIFO
  // level, list publish), so it is held in reset over the same edges and the one before:
  // host_rst_n is low at every edge that samples aresetn low and at the edge after it.
  // Both sides then leave reset at the same edge, whatever the pulse width (one clock
  // or more), and the first pipeline output the host side takes comes from a reset
  // pipeline (docs/streams.md, "Reset and soft reset"). aresetn itself is in host_rst_n,
  // so TVALID of both outputs is low from the first edge that samples aresetn low; the
  // edge after the reset is still a reset edge, so TVALID is low in the clock after the
  // reset too. An AXI master may start a transfer in the clock after the edge that first
  // samples aresetn high (AXI: valid rises only after an edge with ARESETn high), whose
  // handshake is at the first edge the register file is out of reset.
  // A soft reset does not reset the host side: the sink is not reset with it, so the
  // beat on the wire stays until taken and the frame in progress is completed by
  // sm_outfmt.
  reg rst_n_q;    // pipeline reset: aresetn or the soft-reset pulse at the previous edge
  reg aresetn_q;  // aresetn at the previous edge
  always @(posedge aclk) begin
    rst_n_q   <= aresetn && !soft_reset;
    aresetn_q <= aresetn;
  end
  wire rst_n      = rst_n_q;
  wire host_rst_n = aresetn && aresetn_q;

  sm_axil_regs #(
      .MAX_WIDTH(MAX_WIDTH), .MAX_HEIGHT(MAX_HEIGHT), .DISP(DISP), .MAX_OBJECTS(MAX_OBJECTS), .PU(PUE),
      .LEVEL_W(IN_LW), .MIN_HEIGHT(MIN_HEIGHT), .SPECKLE_ROWS(SPECKLE_ROWS)
  ) u_regs (
      .aclk(aclk), .aresetn(host_rst_n),
      .s_axil_awaddr(s_axil_awaddr), .s_axil_awvalid(s_axil_awvalid), .s_axil_awready(s_axil_awready),
      .s_axil_wdata(s_axil_wdata), .s_axil_wstrb(s_axil_wstrb), .s_axil_wvalid(s_axil_wvalid),
      .s_axil_wready(s_axil_wready), .s_axil_bresp(s_axil_bresp), .s_axil_bvalid(s_axil_bvalid),
      .s_axil_bready(s_axil_bready), .s_axil_araddr(s_axil_araddr), .s_axil_arvalid(s_axil_arvalid),
      .s_axil_arready(s_axil_arready), .s_axil_rdata(s_axil_rdata), .s_axil_rresp(s_axil_rresp),
      .s_axil_rvalid(s_axil_rvalid), .s_axil_rready(s_axil_rready),
      .frame_start(frame_start), .err_pulse({out_overflow, seq_err}), .in_level(in_level),
      .enable(core_enable), .soft_reset(soft_reset), .host_width(host_width), .host_height(host_height),
      .cfg_width(cfg_width), .cfg_height(cfg_height), .cfg_gain_l(cfg_gain_l), .cfg_gain_r(cfg_gain_r),
      .cfg_offset_l(cfg_offset_l), .cfg_offset_r(cfg_offset_r), .cfg_rect_enable(cfg_rect_enable),
      .cfg_grid_bank(cfg_grid_bank), .cfg_occ(cfg_occ), .cfg_occ_edge(cfg_occ_edge),
      .cfg_edge_t(cfg_edge_t), .cfg_sw_table(cfg_sw_table),
      .cfg_filter_enable(cfg_filter_enable), .cfg_obj_near(cfg_obj_near), .cfg_obj_tol(cfg_obj_tol),
      .cfg_obj_min_pixels(cfg_obj_min_pixels), .cfg_out(cfg_out), .cfg_smooth(cfg_smooth),
      .cfg_speckle(cfg_speckle),
      .obj_rd_idx(obj_rd_idx), .obj_rd_data(obj_rd_data_q),
      .grid_we(grid_we), .grid_waddr(grid_waddr), .grid_wdata(grid_wdata)
  );

  // ---------------------------------------------------------------- input sequencer
  wire       beat_valid;
  wire [`SM_SIDE_W-1:0] beat_side;
  wire [7:0] beat_left, beat_right;
  wire       out_room;
  // Pacing: with F > 1 clocks per pixel a beat is taken at most every F clocks; the
  // folded blocks compute a beat's F level groups on the clocks before its ce (their
  // inputs are the previous stages' registers, which change only on ce). The camera is
  // held by s_axis_tready only when the input FIFO is full (docs/streams.md, "Pacing").
  wire       pace_ok;
  wire       spk_ready;  // the speckle stage's labeller is not SLACK beats behind
  wire       ce = beat_valid && out_room && pace_ok && spk_ready;
  generate
    if (F > 1) begin : g_pace
      reg [FCW-1:0] pace_q;  // clocks until the next ce may come
      always @(posedge aclk) begin
        // the folded blocks start their first beat's groups at reset: its ce waits F - 1
        if (!rst_n) pace_q <= F[FCW-1:0] - 1'b1;
        else if (ce) pace_q <= F[FCW-1:0] - 1'b1;
        else if (pace_q != {FCW{1'b0}}) pace_q <= pace_q - 1'b1;
      end
      assign pace_ok = (pace_q == {FCW{1'b0}});
    end else begin : g_nopace
      assign pace_ok = 1'b1;
    end
  endgenerate

  sm_seq #(.MAX_WIDTH(MAX_WIDTH), .MAX_HEIGHT(MAX_HEIGHT), .FLUSH_ROWS(FLUSH_ROWS), .IN_DEPTH(IN_DEPTH)) u_seq (
      .clk(aclk), .rst_n(rst_n),
      .s_axis_tdata(s_axis_tdata), .s_axis_tuser(s_axis_tuser), .s_axis_tlast(s_axis_tlast),
      .s_axis_tvalid(s_axis_tvalid), .s_axis_tready(s_axis_tready),
      .enable(core_enable), .host_width(host_width), .host_height(host_height),
      .frame_start(frame_start), .ce(ce),
      .beat_valid(beat_valid), .beat_side(beat_side), .beat_left(beat_left), .beat_right(beat_right),
      .err_pulse(seq_err), .in_level(in_level)
  );
  // Shadow values change only at the sequencer's frame start, after the previous frame
  // at a different width has been flushed.
  wire [XW-1:0] width = cfg_width;

  // Per-frame parameters: every stage after the brightness control reads the shadow
  // values of its own frame from a four-frame history indexed by frame tag (a frame can
  // be more than one frame deep in the pipeline), each stage's field in its
  // sm_frame_sel, written with the frame's first beat (beat_side). The four tags must outlast the
  // pipeline: FLUSH_ROWS rows of 16 beats bound its latency, four frames last at least
  // 4 x MIN_HEIGHT rows.
  // Every parameter inside its range of rtl/defs.json (the ranges HwConfig::validate()
  // checks too), then the rules between parameters.
  `include "sm_defs_check.vh"
  generate
    `SM_BAD_PARAM(g_bad_pu, PUE < 1 || PUE > DISP || DISP % PUE != 0 || (PUE != DISP && PUE % 2 != 0),
                  ("sm_top: PU (%0d) must be 0, DISP (%0d) or an even divisor of DISP", PU, DISP))
    `SM_BAD_PARAM(g_bad_flush, BASE_FLUSH_ROWS >= 64,
                  ("sm_top: pipeline of %0d narrow rows outlasts the 4-frame parameter history", BASE_FLUSH_ROWS))
    `SM_BAD_PARAM(g_bad_min_height, MIN_HEIGHT > MAX_HEIGHT,
                  ("sm_top: MAX_HEIGHT (%0d) below the shortest frame the pipeline allows (%0d)", MAX_HEIGHT, MIN_HEIGHT))
  endgenerate
  localparam P_RECT = 0;               // rectification enable, grid bank
  localparam P_SWT  = P_RECT + 2;      // support-weight table
  localparam P_OCC  = P_SWT + 64;      // occlusion penalties: flat, then at an edge
  localparam P_EDGT = P_OCC + 16;      // edge threshold of the occlusion penalty
  localparam P_FILT = P_EDGT + 8;      // filter enables: F1..F3 medians, then F0 band
  localparam P_OBJ  = P_FILT + 4;      // object near, tol, min pixels, then the height
  localparam P_H    = P_OBJ + 32;
  localparam P_OUT  = P_H + YW;        // the output stage's registers (sm_outfields' s_cfg)
  localparam P_SMO  = P_OUT + 49;      // smoothing: enable, then the threshold
  localparam P_SPK  = P_SMO + 7;       // speckle stage: enable, size, diff, trust
  localparam PW     = P_SPK + 33;
  wire [PW-1:0] fr_par = {cfg_speckle, cfg_smooth, cfg_out, cfg_height, cfg_obj_min_pixels, cfg_obj_tol, cfg_obj_near, cfg_filter_enable,
                          cfg_edge_t, cfg_occ_edge, cfg_occ, cfg_sw_table, cfg_grid_bank, cfg_rect_enable};

  // ---------------------------------------------------------------- pre-processing
  wire [`SM_SIDE_W-1:0] br_side;
  wire [7:0] br_left, br_right;
  sm_brightness u_bright (
      .clk(aclk), .rst_n(rst_n), .ce(ce),
      .gain_l(cfg_gain_l), .gain_r(cfg_gain_r), .offset_l(cfg_offset_l), .offset_r(cfg_offset_r),
      .s_side(beat_side), .s_left(beat_left), .s_right(beat_right),
      .m_side(br_side), .m_left(br_left), .m_right(br_right)
  );

  wire [`SM_SIDE_W-1:0] rl_side, rr_side;
  wire [7:0] rl_pix, rr_pix;
  wire [GAW-2:0] grid_addr_cam = grid_waddr[GAW-2:0];  // {bank, gy, gx}
  wire [1:0] par_rect;  // {grid bank, enable}
  sm_frame_sel #(.PW(PW), .LSB(P_RECT), .W(2), .NEXT(1)) u_fsel_rect (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .ev_side(rl_side), .wr_side(beat_side), .wr_par(fr_par), .par(par_rect)
  );
  sm_rectify #(.MAX_WIDTH(MAX_WIDTH), .MAX_HEIGHT(MAX_HEIGHT), .RECT_RADIUS(RECT_RADIUS)) u_rect_l (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width), .enable(par_rect[0]),
      .grid_bank(par_rect[1]), .grid_we(grid_we && !grid_waddr[GAW-1]),
      .grid_waddr(grid_addr_cam), .grid_wdata(grid_wdata),
      .s_side(br_side), .s_pix(br_left), .m_side(rl_side), .m_pix(rl_pix)
  );
  sm_rectify #(.MAX_WIDTH(MAX_WIDTH), .MAX_HEIGHT(MAX_HEIGHT), .RECT_RADIUS(RECT_RADIUS)) u_rect_r (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width), .enable(par_rect[0]),
      .grid_bank(par_rect[1]), .grid_we(grid_we && grid_waddr[GAW-1]),
      .grid_waddr(grid_addr_cam), .grid_wdata(grid_wdata),
      .s_side(br_side), .s_pix(br_right), .m_side(rr_side), .m_pix(rr_pix)
  );
  wire unused_rr_side = ^rr_side;  // both rectifiers carry the same sideband

  // ---------------------------------------------------------------- main processing
  wire [`SM_SIDE_W-1:0] cs_side;
  wire [CB-1:0] cs_cl, cs_cr;
  wire [7:0]    cs_left, cs_right;
  sm_census #(.MAX_WIDTH(MAX_WIDTH), .CENSUS(CENSUS)) u_census (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width),
      .s_side(rl_side), .s_left(rl_pix), .s_right(rr_pix),
      .m_side(cs_side), .m_cl(cs_cl), .m_cr(cs_cr), .m_left(cs_left), .m_right(cs_right)
  );

  wire [`SM_SIDE_W-1:0] ct_side;
  wire [CW*DISP-1:0] ct_cost;  // C in bit-plane order: bit f of level d at [f*DISP + d]
  wire [7:0]         ct_left;
  sm_cost #(
      .MAX_WIDTH(MAX_WIDTH), .DISP(DISP), .CENSUS(CENSUS), .PU(PUE), .COST_SHIFT(COST_SHIFT),
      .AD_SHIFT(AD_SHIFT), .AD_MAX(AD_MAX)
  ) u_cost (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width),
      .s_side(cs_side), .s_cl(cs_cl), .s_cr(cs_cr), .s_left(cs_left), .s_right(cs_right),
      .m_side(ct_side), .m_cost(ct_cost), .m_left(ct_left)
  );

  wire [`SM_SIDE_W-1:0] ag_side;
  wire [DISP*CW-1:0] ag_cost;
  wire [63:0]        par_swt;
  sm_frame_sel #(.PW(PW), .LSB(P_SWT), .W(64), .NEXT(1)) u_fsel_agg (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .ev_side(ag_side), .wr_side(beat_side), .wr_par(fr_par), .par(par_swt)
  );
  sm_sw_aggregate #(
      .MAX_WIDTH(MAX_WIDTH), .DISP(DISP), .CENSUS(CENSUS), .SW(SW), .COST_SHIFT(COST_SHIFT), .PU(PUE)
  ) u_agg (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width), .sw_table(par_swt),
      .s_side(ct_side), .s_cost(ct_cost), .s_left(ct_left),
      .m_side(ag_side), .m_agg(ag_cost)
  );

  // Edge flags for the DP's occlusion penalty, from the left pixel that leaves the cost
  // stage with the beat, delayed by the aggregation's R rows and R + `SM_AGG_PIPE_BEATS beats.
  wire [7:0] par_edge_t;
  wire       dp_edge;
  sm_frame_sel #(.PW(PW), .LSB(P_EDGT), .W(8), .NEXT(1)) u_fsel_edge (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .ev_side(ct_side), .wr_side(beat_side), .wr_par(fr_par), .par(par_edge_t)
  );
  sm_edge_flag #(.MAX_WIDTH(MAX_WIDTH), .ROWS((SW - 1) / 2), .COLS((SW - 1) / 2 + `SM_AGG_PIPE_BEATS)) u_edge (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width), .edge_t(par_edge_t),
      .s_side(ct_side), .s_left(ct_left), .m_edge(dp_edge)
  );

  wire [`SM_SIDE_W-1:0] dp_side;
  wire [15:0] dp_disp;
  wire [15:0] par_occ;  // {at an edge, flat}
  wire        dp_matched;
  wire [7:0]  dp_gap;
  wire [DWD-1:0] dp_fill_bg;
  sm_frame_sel #(.PW(PW), .LSB(P_OCC), .W(16), .NEXT(1)) u_fsel_dp (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .ev_side(dp_side), .wr_side(beat_side), .wr_par(fr_par), .par(par_occ)
  );
  sm_dp #(.MAX_WIDTH(MAX_WIDTH), .DISP(DISP), .CW(CW), .PU(PUE)) u_dp (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width),
      .occ(par_occ[7:0]), .occ_edge(par_occ[15:8]), .s_edge(dp_edge),
      .s_side(ag_side), .s_cost(ag_cost), .m_side(dp_side), .m_disp(dp_disp),
      .m_matched(dp_matched), .m_gap(dp_gap), .m_fill_bg(dp_fill_bg)
  );

  // ---------------------------------------------------------------- post-processing
  // F0 band filter (FILTER_ENABLE bit 3), then the medians F1..F3 (bits 0..2)
  wire [`SM_SIDE_W-1:0] f0_side, f1_side, f2_side, f3_side;
  wire [15:0] f0_disp, f1_disp, f2_disp, f3_disp;
  wire [3:0]  par_filt;
  wire [4*`SM_SIDE_W-1:0] filt_ev = {f0_side, f3_side, f2_side, f1_side};
  genvar fi;
  generate
    for (fi = 0; fi < 4; fi = fi + 1) begin : g_fsel_post
      sm_frame_sel #(.PW(PW), .LSB(P_FILT + fi), .W(1), .NEXT(1)) u_fsel (
          .clk(aclk), .rst_n(rst_n), .ce(ce), .ev_side(filt_ev[`SM_SIDE_W*fi +: `SM_SIDE_W]),
          .wr_side(beat_side), .wr_par(fr_par), .par(par_filt[fi])
      );
    end
  endgenerate
  sm_post_band #(.MAX_WIDTH(MAX_WIDTH), .DISP(DISP), .K(BAND_K)) u_post0 (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width), .enable(par_filt[3]),
      .s_side(dp_side), .s_disp(dp_disp), .m_side(f0_side), .m_disp(f0_disp)
  );
  sm_post_median #(.MAX_WIDTH(MAX_WIDTH), .DISP(DISP), .RY(2), .RX(0)) u_post1 (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width), .enable(par_filt[0]),
      .s_side(f0_side), .s_disp(f0_disp), .m_side(f1_side), .m_disp(f1_disp)
  );
  sm_post_median #(.MAX_WIDTH(MAX_WIDTH), .DISP(DISP), .RY(1), .RX(1)) u_post2 (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width), .enable(par_filt[1]),
      .s_side(f1_side), .s_disp(f1_disp), .m_side(f2_side), .m_disp(f2_disp)
  );
  sm_post_median #(.MAX_WIDTH(MAX_WIDTH), .DISP(DISP), .RY(2), .RX(1)) u_post3 (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width), .enable(par_filt[2]),
      .s_side(f2_side), .s_disp(f2_disp), .m_side(f3_side), .m_disp(f3_disp)
  );

  // ---------------------------------------------------------------- output stage
  // Sub-pixel disparity, validity and confidence (docs/algorithm.md section 9). Its
  // registers are those of the frame whose first pixel the DP's read-out emits next: the
  // DP's input (ag_side) sees that frame's start two rows before.
  wire [48:0] par_out;
  sm_frame_sel #(.PW(PW), .LSB(P_OUT), .W(49), .NEXT(0)) u_fsel_out (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .ev_side(ag_side), .wr_side(beat_side), .wr_par(fr_par), .par(par_out)
  );
  wire [`SM_SIDE_W-1:0] out_side, obj_side;
  wire [31:0] out_word;
  wire        obj_valid;
  wire [DWD-1:0] obj_level;
  sm_outstage #(.MAX_WIDTH(MAX_WIDTH), .DISP(DISP), .CW(CW), .PU(PUE), .BAND_K(BAND_K)) u_outstage (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width), .s_side(ag_side), .s_cost(ag_cost),
      .dp_side(dp_side), .dp_disp(dp_disp), .dp_matched(dp_matched), .dp_gap(dp_gap), .dp_fill_bg(dp_fill_bg),
      .s_cfg(par_out), .post_side(f3_side), .post_disp(f3_disp),
      .m_side(out_side), .m_word(out_word)
  );

  // The speckle stage (docs/algorithm.md 9.8), where built: the words wait SPECKLE_ROWS
  // rows for their region's verdict. Its registers: those of the frame whose first word
  // it takes next, which the post filters' output (f3_side) sees a few beats before.
  // The object labeller and the smoothing take its words.
  wire [`SM_SIDE_W-1:0] sk_side;
  wire [31:0] sk_word;
  generate
    if (SPECKLE_ROWS > 0) begin : g_speckle
      wire [32:0] par_spk;  // {trust, diff, size, en}
      sm_frame_sel #(.PW(PW), .LSB(P_SPK), .W(33), .NEXT(0)) u_fsel_spk (
          .clk(aclk), .rst_n(rst_n), .ce(ce), .ev_side(f3_side), .wr_side(beat_side), .wr_par(fr_par), .par(par_spk)
      );
      sm_speckle #(.MAX_WIDTH(MAX_WIDTH), .ROWS(SPECKLE_ROWS), .LABELS(SPECKLE_LABELS), .SLACK(`SM_SPECKLE_SLACK)) u_speckle (
          .clk(aclk), .rst_n(rst_n), .ce(ce), .ready(spk_ready), .en(par_spk[0]), .size(par_spk[12:1]),
          .diff(par_spk[20:13]), .trust(par_spk[32:21]), .s_side(out_side), .s_word(out_word), .m_side(sk_side), .m_word(sk_word)
      );
    end else begin : g_no_speckle
      assign spk_ready = 1'b1;
      assign sk_side = out_side;
      assign sk_word = out_word;
    end
  endgenerate
  sm_obj_level #(.DISP(DISP)) u_obj_level (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .s_side(sk_side), .s_valid(sk_word[31]), .s_q4(sk_word[DQW-1:0]),
      .m_side(obj_side), .m_valid(obj_valid), .m_level(obj_level)
  );

  // Object list: the register file reads word (idx) of the list window -- header at 0,
  // object i at 4 + 4i .. 7 + 4i (rtl/regmap.json) -- two clocks after it sets idx.
  localparam IW = (MAX_OBJECTS > 1) ? $clog2(MAX_OBJECTS) : 1;
  wire        list_ready, too_many, table_full, pkt_lost;
  wire [7:0]  obj_count;
  wire [15:0] rd_x0, rd_y0, rd_x1, rd_y1;
  wire [31:0] rd_count, rd_sum;
  wire [7:0]  rd_mean, rd_max;
  wire [OIW-1:0] obj_word_idx = obj_rd_idx - 4;
  reg         list_valid_q;
  // Object thresholds and the frame height, for sm_objects and the output formatter: both
  // latch them at their start of frame, which follows post filter 3's input (f2_side) by
  // its delay of 2W + 3 beats, or the speckle stage's output (sk_side) by two beats.
  wire [32+YW-1:0] par_obj;  // {height, min pixels, tol, near}
  wire [`SM_SIDE_W-1:0] obj_ev_side = (SPECKLE_ROWS > 0) ? sk_side : f2_side;
  sm_frame_sel #(.PW(PW), .LSB(P_OBJ), .W(32 + YW), .NEXT(0)) u_fsel_obj (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .ev_side(obj_ev_side), .wr_side(beat_side), .wr_par(fr_par), .par(par_obj)
  );
  wire [YW-1:0] frame_height = par_obj[32 +: YW];
  sm_objects #(
      .MAX_WIDTH(MAX_WIDTH), .MAX_HEIGHT(MAX_HEIGHT), .DISP(DISP), .MAX_OBJECTS(MAX_OBJECTS),
      .LABEL_SLOTS(LABEL_SLOTS)
  ) u_objects (
      .clk(aclk), .rst_n(rst_n), .out_rst_n(host_rst_n), .ce(ce), .width(width), .height(frame_height),
      .near_thr(par_obj[7:0]), .tol(par_obj[15:8]), .min_pixels(par_obj[31:16]),
      .s_side(obj_side), .s_disp({obj_valid, {(15 - DWD) {1'b0}}, obj_level}),
      .list_ready(list_ready), .obj_count(obj_count), .too_many(too_many), .table_full(table_full),
      .pkt_lost(pkt_lost), .rd_index(obj_word_idx[IW+1:2]),
      .rd_x0(rd_x0), .rd_y0(rd_y0), .rd_x1(rd_x1), .rd_y1(rd_y1), .rd_count(rd_count), .rd_sum(rd_sum),
      .rd_mean(rd_mean), .rd_max(rd_max),
      .m_axis_obj_tdata(m_axis_obj_tdata), .m_axis_obj_tlast(m_axis_obj_tlast),
      .m_axis_obj_tvalid(m_axis_obj_tvalid), .m_axis_obj_tready(m_axis_obj_tready)
  );
  wire unused_obj = ^{rd_sum, pkt_lost, obj_word_idx};
  always @(posedge aclk) begin
    if (!host_rst_n) list_valid_q <= 1'b0;
    else if (list_ready) list_valid_q <= 1'b1;
    if (obj_rd_idx == {OIW{1'b0}})
      obj_rd_data_q <= {21'd0, table_full, too_many, list_valid_q, obj_count};
    else
      case (obj_word_idx[1:0])
        2'd0:    obj_rd_data_q <= {rd_x1, rd_x0};
        2'd1:    obj_rd_data_q <= {rd_y1, rd_y0};
        2'd2:    obj_rd_data_q <= rd_count;
        default: obj_rd_data_q <= {16'd0, rd_max, rd_mean};
      endcase
  end

  // ---------------------------------------------------------------- output
  // The words' window stage (docs/algorithm.md 9.7): their Q.4 values smoothed, the stream's
  // confidence from the window's support; the labeller above reads them as formed. Its
  // registers: those of the frame whose first centre it takes next.
  wire [`SM_SIDE_W-1:0] sm_side;
  wire [31:0] sm_word;
  wire [6:0]  par_smooth;
  sm_frame_sel #(.PW(PW), .LSB(P_SMO), .W(7), .NEXT(1)) u_fsel_smooth (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .ev_side(sm_side), .wr_side(beat_side), .wr_par(fr_par), .par(par_smooth)
  );
  sm_out_smooth #(.MAX_WIDTH(MAX_WIDTH), .DISP(DISP)) u_smooth (
      .clk(aclk), .rst_n(rst_n), .ce(ce), .width(width), .enable(par_smooth[0]), .thr(par_smooth[6:1]),
      .s_side(sk_side), .s_word(sk_word), .m_side(sm_side), .m_word(sm_word)
  );

  // the row support of the confidence (docs/algorithm.md 9.7)
  wire [`SM_SIDE_W-1:0] su_side;
  wire [31:0] su_word;
  sm_out_support #(.DISP(DISP)) u_support (
      .clk(aclk), .rst_n(rst_n), .ce(ce),
      .s_side(sm_side), .s_word(sm_word), .m_side(su_side), .m_word(su_word)
  );

  sm_outfmt #(.MAX_WIDTH(MAX_WIDTH), .MAX_HEIGHT(MAX_HEIGHT)) u_out (
      .clk(aclk), .rst_n(host_rst_n), .restart(!rst_n), .ce(ce), .width(width), .height(frame_height),
      .in_side(su_side), .in_word(su_word), .room(out_room), .err_overflow(out_overflow),
      .m_axis_tdata(m_axis_tdata), .m_axis_tuser(m_axis_tuser), .m_axis_tlast(m_axis_tlast),
      .m_axis_tvalid(m_axis_tvalid), .m_axis_tready(m_axis_tready)
  );

`ifndef SYNTHESIS
  // AXI4-Stream rules on both outputs (simulation only, live in every Verilated test):
  // TVALID low in the clock after an edge that sampled aresetn low and after the edge
  // that first samples it high again (the whole reset and the clock after it); once TVALID is high it stays high with the same payload until
  // TREADY, unless aresetn intervenes (a soft reset does not release a beat); TLAST and
  // TUSER only with TVALID.
  reg        chk_live_q;  // a reset has been seen (power-up state is arbitrary)
  reg        chk_rst_q;
  reg        chk_host_rst_q;
  reg        chk_wait_q, chk_owait_q;
  reg [33:0] chk_beat_q;
  reg [32:0] chk_obeat_q;
  wire [33:0] chk_beat  = {m_axis_tuser, m_axis_tlast, m_axis_tdata};
  wire [32:0] chk_obeat = {m_axis_obj_tlast, m_axis_obj_tdata};
  initial chk_live_q = 1'b0;
  always @(posedge aclk) begin
    if (chk_live_q) begin
      if (chk_rst_q && (m_axis_tvalid || m_axis_obj_tvalid))
        $error("sm_top: TVALID high in the clock after a reset edge");
      if (chk_wait_q && (!m_axis_tvalid || chk_beat != chk_beat_q))
        $error("sm_top: m_axis beat withdrawn or changed before tready");
      if (chk_owait_q && (!m_axis_obj_tvalid || chk_obeat != chk_obeat_q))
        $error("sm_top: m_axis_obj beat withdrawn or changed before tready");
      if (!m_axis_tvalid && (m_axis_tuser || m_axis_tlast)) $error("sm_top: m_axis tuser/tlast without tvalid");
      if (!m_axis_obj_tvalid && m_axis_obj_tlast) $error("sm_top: m_axis_obj tlast without tvalid");
    end
    // Reset release: after aresetn the host side and the pipeline leave reset at the same
    // edge, and at that edge the host side takes no pipeline event (frame start, error
    // pulse, input FIFO level, list publish): it would be one from before the reset.
    if (chk_live_q && chk_host_rst_q && host_rst_n) begin
      if (!rst_n) $error("sm_top: the register file and the outputs left reset before the pipeline");
      if (frame_start || seq_err != 6'd0 || out_overflow || list_ready || in_level != {IN_LW{1'b0}})
        $error("sm_top: a pipeline event from before the reset reached the register file or the outputs");
    end
    chk_host_rst_q <= !host_rst_n;
    // AXI: a master raises VALID only after an edge that samples ARESETn high. At the
    // first such edge the register file is still in reset (host_rst_n), so a transfer
    // handshaked there would be lost.
    if (chk_live_q && aresetn && !aresetn_q && (s_axil_awvalid || s_axil_wvalid || s_axil_arvalid))
      $error("sm_top: AXI4-Lite VALID at the edge that first samples aresetn high");
    if (!aresetn) chk_live_q <= 1'b1;
    // aresetn low at this edge resets the sink too: the beat is released; the edge after
    // it is a reset edge of the outputs too
    chk_rst_q   <= !host_rst_n;
    chk_wait_q  <= aresetn && m_axis_tvalid && !m_axis_tready;
    chk_owait_q <= aresetn && m_axis_obj_tvalid && !m_axis_obj_tready;
    chk_beat_q  <= chk_beat;
    chk_obeat_q <= chk_obeat;
  end
`endif
endmodule
`default_nettype wire
