`default_nettype none
`include "sm_defs.vh"
// AXI4-Lite register file (docs/registers.md, generated from rtl/regmap.json together
// with the included sm_regmap.vh). The host sees and writes one copy of the pipeline
// parameters; a shadow copy drives the pipeline and is refreshed from the host copy only
// at frame_start (the input sequencer's frame boundary), so a frame is never processed
// with a half-written parameter set. Writes are clamped to each register's range
// (ERR_FLAGS.CLAMPED records that it happened). The object list is read through the
// object block's read port; rectification grid writes are forwarded to the grid RAM.
//
// One write and one read can be in progress at a time; AW and W are accepted in any
// order (or together) and B / R wait for their ready. Reads take three clocks so the
// object block's registered read port can be used.
module sm_axil_regs #(
    parameter MAX_WIDTH   = 320,  // widest active line
    parameter MAX_HEIGHT  = 240,  // tallest active frame
    parameter DISP        = 128,  // disparity levels (reported in CAPS1)
    parameter MAX_OBJECTS = 8,    // objects in the list
    parameter PU          = DISP, // disparity levels per clock (reported in CAPS1)
    parameter LEVEL_W     = 10    // width of the input FIFO level
) (
    input  wire              aclk,
    input  wire              aresetn,
    // AXI4-Lite slave
    input  wire [ADDR_W-1:0] s_axil_awaddr,
    input  wire              s_axil_awvalid,
    output wire              s_axil_awready,
    input  wire [31:0]       s_axil_wdata,
    input  wire [3:0]        s_axil_wstrb,
    input  wire              s_axil_wvalid,
    output wire              s_axil_wready,
    output reg  [1:0]        s_axil_bresp,
    output reg               s_axil_bvalid,
    input  wire              s_axil_bready,
    input  wire [ADDR_W-1:0] s_axil_araddr,
    input  wire              s_axil_arvalid,
    output wire              s_axil_arready,
    output reg  [31:0]       s_axil_rdata,
    output reg  [1:0]        s_axil_rresp,
    output reg               s_axil_rvalid,
    input  wire              s_axil_rready,
    // from the stream edges
    input  wire              frame_start,   // copy host values into the shadow copy
    input  wire [6:0]        err_pulse,        // fault pulses, ERR_FLAGS bits 6:0
    input  wire [LEVEL_W-1:0] in_level,     // input FIFO entries (IN_FIFO.LEVEL_MAX)
    // control (not shadowed)
    output reg               enable,
    output reg               soft_reset,    // one-clock pulse
    output wire [XW-1:0]     host_width,    // host values for the sequencer's frame start
    output wire [YW-1:0]     host_height,
    // shadow copy of the pipeline parameters (what the pipeline uses)
    output reg  [XW-1:0]     cfg_width,
    output reg  [YW-1:0]     cfg_height,
    output reg  [9:0]        cfg_gain_l,
    output reg  [9:0]        cfg_gain_r,
    output reg  [8:0]        cfg_offset_l,
    output reg  [8:0]        cfg_offset_r,
    output reg               cfg_rect_enable,
    output reg               cfg_grid_bank,
    output reg  [7:0]        cfg_occ,
    output reg  [7:0]        cfg_occ_edge,
    output reg  [7:0]        cfg_edge_t,
    output reg  [63:0]       cfg_sw_table,    // code k at bits 2k+1:2k
    output reg  [3:0]        cfg_filter_enable,
    output reg  [7:0]        cfg_obj_near,
    output reg  [7:0]        cfg_obj_tol,
    output reg  [15:0]       cfg_obj_min_pixels,
    // object list read port: obj_rd_data is sampled two clocks after obj_rd_idx changes
    output reg  [OIW-1:0]    obj_rd_idx,
    input  wire [31:0]       obj_rd_data,
    // rectification grid writes
    output reg               grid_we,
    output reg  [GAW-1:0]    grid_waddr,    // {cam, bank, point}
    output reg  [31:0]       grid_wdata     // {sy, sx}, signed Q.5 each
);
  // Narrowest active line the pipeline supports (HwConfig::min_width, the WIDTH minimum
  // of the generated map): the DP needs DISP/2 + 3 columns (sm_dp.v), every window 16.
  localparam integer MIN_WIDTH = (DISP / 2 + 3 > 16) ? DISP / 2 + 3 : 16;
  /* verilator lint_off UNUSEDPARAM */  // the generated map holds every field's constants
  `include "sm_regmap.vh"
  /* verilator lint_on UNUSEDPARAM */

  localparam ADDR_W = SM_ADDR_BITS;
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam YW = `SM_COUNT_W(MAX_HEIGHT);
  // Port widths are written from parameters directly: Yosys 0.23 cannot evaluate
  // $clog2 of a parameter-derived localparam in a forward-referenced port width.
  // Grid point = {gy, gx} with a power-of-two row of points, the rectifier's grid
  // address (sm_rectify): no multiplier between the host and the grid memory.
  localparam GW_PTS = `SM_GRID_PTS(MAX_WIDTH);   // points per grid row
  localparam GH_PTS = `SM_GRID_PTS(MAX_HEIGHT);  // grid rows
  localparam GXB = `SM_GRID_AB(MAX_WIDTH);
  localparam GYB = `SM_GRID_AB(MAX_HEIGHT);
  localparam PB = GXB + GYB;
  localparam GRID_POINTS = (1 << PB);
  localparam GAW = `SM_GRID_AB(MAX_WIDTH) + `SM_GRID_AB(MAX_HEIGHT) + 2;
  localparam OBJ_IDX_END = SM_OBJ_FIRST_IDX + SM_OBJ_WORDS * MAX_OBJECTS;  // first unused
  localparam OIW = $clog2(SM_OBJ_FIRST_IDX + SM_OBJ_WORDS * MAX_OBJECTS);
  localparam OWW = $clog2(SM_OBJ_SIZE / 4);  // word index bits of the object window
  localparam GWW = SM_GRID_POINT_BITS + 2;   // word index bits of the grid window
  localparam [1:0] OKAY = 2'b00, SLVERR = 2'b10;
  localparam [GXB-1:0] GX_END = GW_PTS[GXB-1:0];
  localparam [GYB:0]   GY_END = GH_PTS[GYB:0];
  localparam [OWW:0] OBJ_FIRST = SM_OBJ_FIRST_IDX[OWW:0];
  localparam [OWW:0] OBJ_END   = OBJ_IDX_END[OWW:0];

  generate
    `SM_BAD_PARAM(g_bad_grid, PB > SM_GRID_POINT_BITS,
                  ("sm_axil_regs: %0d grid points exceed the grid window", GRID_POINTS))
    `SM_BAD_PARAM(g_bad_obj, 4 * OBJ_IDX_END > SM_OBJ_SIZE,
                  ("sm_axil_regs: MAX_OBJECTS (%0d) exceeds the object window", MAX_OBJECTS))
    `SM_BAD_PARAM(g_bad_obj_base, SM_OBJ_BASE % SM_OBJ_SIZE != 0,
                  ("sm_axil_regs: the object window must be aligned to its size"))
    `SM_BAD_PARAM(g_bad_level, LEVEL_W < 1 || LEVEL_W > SM_IN_FIFO_LEVEL_MAX_W,
                  ("sm_axil_regs: LEVEL_W (%0d) must be 1..%0d", LEVEL_W, SM_IN_FIFO_LEVEL_MAX_W))
    `SM_BAD_PARAM(g_bad_size, MAX_WIDTH < `SM_MAX_WIDTH_MIN || MAX_WIDTH > `SM_MAX_WIDTH_MAX || MAX_HEIGHT < `SM_MAX_HEIGHT_MIN || MAX_HEIGHT > `SM_MAX_HEIGHT_MAX,
                  ("sm_axil_regs: MAX_WIDTH / MAX_HEIGHT must be %0d..%0d / %0d..%0d", `SM_MAX_WIDTH_MIN, `SM_MAX_WIDTH_MAX, `SM_MAX_HEIGHT_MIN, `SM_MAX_HEIGHT_MAX))
  endgenerate

  // ---- host copy
  reg          grid_bank_q;
  reg [XW-1:0] width_q;
  reg [YW-1:0] height_q;
  reg [9:0]    gain_l_q, gain_r_q;
  reg [8:0]    offset_l_q, offset_r_q;
  reg          rect_enable_q;
  reg [7:0]    occ_q, occ_edge_q, edge_t_q;
  reg [63:0]   sw_table_q;
  reg [3:0]    filter_enable_q;
  reg [7:0]    obj_near_q, obj_tol_q;
  reg [15:0]   obj_min_pixels_q;
  // ---- status
  reg [15:0]   frame_count_q;
  reg [7:0]    err_flags_q;
  reg [111:0]  err_cnt_q;  // 7 x 16 bits, class n at 16n +: 16 (ERR_FLAGS bit order)
  reg [LEVEL_W-1:0] level_max_q;  // input FIFO high-water mark

  assign host_width  = width_q;
  assign host_height = height_q;

  // ---- address decoding (the byte-lane bits a[1:0] are ignored by design)
  /* verilator lint_off UNUSEDSIGNAL */
  function is_reg;  // word address of a register in the map
    input [ADDR_W-1:0] a;
    begin
      case ({a[ADDR_W-1:2], 2'b00})
        SM_ID_ADDR, SM_VERSION_ADDR, SM_CONTROL_ADDR, SM_STATUS_ADDR, SM_ERR_FLAGS_ADDR,
        SM_ERR_CNT_LINE_ADDR, SM_ERR_CNT_SOF_ADDR, SM_ERR_CNT_ROWS_ADDR, SM_ERR_CNT_OUT_ADDR,
        SM_CAPS0_ADDR, SM_CAPS1_ADDR, SM_IN_FIFO_ADDR, SM_WIDTH_ADDR, SM_HEIGHT_ADDR, SM_GAIN_L_ADDR,
        SM_GAIN_R_ADDR, SM_OFFSET_L_ADDR, SM_OFFSET_R_ADDR, SM_RECT_ENABLE_ADDR, SM_OCC_ADDR,
        SM_SW_TABLE0_ADDR, SM_SW_TABLE1_ADDR, SM_FILTER_ENABLE_ADDR, SM_OCC_EDGE_ADDR,
        SM_EDGE_T_ADDR, SM_OBJ_NEAR_ADDR,
        SM_OBJ_TOL_ADDR, SM_OBJ_MIN_PIXELS_ADDR: is_reg = 1'b1;
        default: is_reg = 1'b0;
      endcase
    end
  endfunction

  function is_writable;  // registers with rw / w1c / wp fields
    input [ADDR_W-1:0] a;
    begin
      case ({a[ADDR_W-1:2], 2'b00})
        SM_CONTROL_ADDR, SM_ERR_FLAGS_ADDR, SM_WIDTH_ADDR, SM_HEIGHT_ADDR, SM_GAIN_L_ADDR,
        SM_GAIN_R_ADDR, SM_OFFSET_L_ADDR, SM_OFFSET_R_ADDR, SM_RECT_ENABLE_ADDR, SM_OCC_ADDR,
        SM_SW_TABLE0_ADDR, SM_SW_TABLE1_ADDR, SM_FILTER_ENABLE_ADDR, SM_OCC_EDGE_ADDR,
        SM_EDGE_T_ADDR, SM_OBJ_NEAR_ADDR,
        SM_OBJ_TOL_ADDR, SM_OBJ_MIN_PIXELS_ADDR: is_writable = 1'b1;
        default: is_writable = 1'b0;
      endcase
    end
  endfunction

  // CONTROL's read/write fields (SOFT_RESET and CLEAR_ERRORS read as 0)
  reg [31:0] control_own;
  always @(*) begin
    control_own = 32'd0;
    control_own[SM_CONTROL_ENABLE_LSB]    = enable;
    control_own[SM_CONTROL_GRID_BANK_LSB] = grid_bank_q;
  end

  // Host-visible value of a register (0 for addresses outside the register block).
  function [31:0] host_value;
    input [ADDR_W-1:0] a;
    begin
      host_value = 32'd0;
      case ({a[ADDR_W-1:2], 2'b00})
        SM_ID_ADDR: host_value = SM_ID_VALUE_RESET;
        SM_VERSION_ADDR: begin
          host_value[SM_VERSION_MINOR_LSB +: SM_VERSION_MINOR_W] =
              SM_VERSION_MINOR_RESET[SM_VERSION_MINOR_W-1:0];
          host_value[SM_VERSION_MAJOR_LSB +: SM_VERSION_MAJOR_W] =
              SM_VERSION_MAJOR_RESET[SM_VERSION_MAJOR_W-1:0];
        end
        SM_CONTROL_ADDR: host_value = control_own;
        SM_STATUS_ADDR: begin
          host_value[SM_STATUS_FRAME_COUNT_LSB +: SM_STATUS_FRAME_COUNT_W] = frame_count_q;
          host_value[SM_STATUS_GRID_BANK_ACTIVE_LSB] = cfg_grid_bank;
        end
        SM_ERR_FLAGS_ADDR: host_value[7:0] = err_flags_q;
        SM_ERR_CNT_LINE_ADDR: host_value = {err_cnt_q[16 +: 16], err_cnt_q[0 +: 16]};
        SM_ERR_CNT_SOF_ADDR:  host_value = {err_cnt_q[48 +: 16], err_cnt_q[32 +: 16]};
        SM_ERR_CNT_ROWS_ADDR: host_value = {err_cnt_q[80 +: 16], err_cnt_q[64 +: 16]};
        SM_ERR_CNT_OUT_ADDR:  host_value = {16'd0, err_cnt_q[96 +: 16]};
        SM_CAPS0_ADDR: begin
          host_value[SM_CAPS0_MAX_WIDTH_LSB +: SM_CAPS0_MAX_WIDTH_W] =
              SM_CAPS0_MAX_WIDTH_RESET[SM_CAPS0_MAX_WIDTH_W-1:0];
          host_value[SM_CAPS0_MAX_HEIGHT_LSB +: SM_CAPS0_MAX_HEIGHT_W] =
              SM_CAPS0_MAX_HEIGHT_RESET[SM_CAPS0_MAX_HEIGHT_W-1:0];
        end
        SM_CAPS1_ADDR: begin
          host_value[SM_CAPS1_DISP_LSB +: SM_CAPS1_DISP_W] =
              SM_CAPS1_DISP_RESET[SM_CAPS1_DISP_W-1:0];
          host_value[SM_CAPS1_MAX_OBJECTS_LSB +: SM_CAPS1_MAX_OBJECTS_W] =
              SM_CAPS1_MAX_OBJECTS_RESET[SM_CAPS1_MAX_OBJECTS_W-1:0];
          host_value[SM_CAPS1_PU_LSB +: SM_CAPS1_PU_W] = SM_CAPS1_PU_RESET[SM_CAPS1_PU_W-1:0];
        end
        SM_IN_FIFO_ADDR: host_value[SM_IN_FIFO_LEVEL_MAX_LSB +: LEVEL_W] = level_max_q;
        SM_WIDTH_ADDR:  host_value = {{(32-XW){1'b0}}, width_q};
        SM_HEIGHT_ADDR: host_value = {{(32-YW){1'b0}}, height_q};
        SM_GAIN_L_ADDR: host_value = {22'd0, gain_l_q};
        SM_GAIN_R_ADDR: host_value = {22'd0, gain_r_q};
        SM_OFFSET_L_ADDR: host_value = {{23{offset_l_q[8]}}, offset_l_q};
        SM_OFFSET_R_ADDR: host_value = {{23{offset_r_q[8]}}, offset_r_q};
        SM_RECT_ENABLE_ADDR: host_value = {31'd0, rect_enable_q};
        SM_OCC_ADDR: host_value = {24'd0, occ_q};
        SM_OCC_EDGE_ADDR: host_value = {24'd0, occ_edge_q};
        SM_EDGE_T_ADDR: host_value = {24'd0, edge_t_q};
        SM_SW_TABLE0_ADDR: host_value = sw_table_q[31:0];
        SM_SW_TABLE1_ADDR: host_value = sw_table_q[63:32];
        SM_FILTER_ENABLE_ADDR: host_value = {28'd0, filter_enable_q};
        SM_OBJ_NEAR_ADDR: host_value = {24'd0, obj_near_q};
        SM_OBJ_TOL_ADDR: host_value = {24'd0, obj_tol_q};
        SM_OBJ_MIN_PIXELS_ADDR: host_value = {16'd0, obj_min_pixels_q};
        default: host_value = 32'd0;
      endcase
    end
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // {clamped, value}: saturate an unsigned / two's complement word to lo..hi.
  function [32:0] clamp_u;
    input [31:0] v;
    input [31:0] lo;
    input [31:0] hi;
    begin
      if (v < lo) clamp_u = {1'b1, lo};
      else if (v > hi) clamp_u = {1'b1, hi};
      else clamp_u = {1'b0, v};
    end
  endfunction
  function [32:0] clamp_s;
    input [31:0] v;
    input integer lo;
    input integer hi;
    begin
      if ($signed(v) < lo) clamp_s = {1'b1, lo[31:0]};
      else if ($signed(v) > hi) clamp_s = {1'b1, hi[31:0]};
      else clamp_s = {1'b0, v};
    end
  endfunction

  // ---- write channel: AW and W are held until both are there and B is free
  reg              aw_v_q, w_v_q;
  reg [ADDR_W-1:0] aw_a_q;
  reg [31:0]       w_d_q;
  reg [3:0]        w_s_q;
  assign s_axil_awready = !aw_v_q;
  assign s_axil_wready  = !w_v_q;
  wire do_write = aw_v_q && w_v_q && (!s_axil_bvalid || s_axil_bready);

  wire [31:0] strb_mask = {{8{w_s_q[3]}}, {8{w_s_q[2]}}, {8{w_s_q[1]}}, {8{w_s_q[0]}}};
  // A write merges the strobed bytes with the register's own value, not with the read-back
  // multiplexer's: each merge is used only at its own address, and the clamps behind it
  // stay off the multiplexer's path (one LUT level more at the vga point otherwise).
  function [31:0] wm;
    input [31:0] own;
    wm = (w_d_q & strb_mask) | (own & ~strb_mask);
  endfunction
  wire [31:0] w1  = w_d_q & strb_mask;                                       // w1c / wp fields
  wire [ADDR_W-1:0] wa = {aw_a_q[ADDR_W-1:2], 2'b00};

  wire              in_grid = (aw_a_q >= SM_GRID_BASE);
  wire [GWW-1:0]    g_word  = aw_a_q[GWW+1:2];
  wire [SM_GRID_POINT_BITS-1:0] g_point = g_word[SM_GRID_POINT_BITS-1:0];
  wire [GXB-1:0]    g_x     = g_point[GXB-1:0];
  wire [GYB-1:0]    g_y     = g_point[PB-1:GXB];
  wire              g_in    = (g_x < GX_END) && ({1'b0, g_y} < GY_END) &&
                              (g_point >> PB) == {SM_GRID_POINT_BITS{1'b0}};
  wire              grid_ok = in_grid && g_in && (w_s_q == 4'hf);
  wire              wr_ok   = grid_ok || (!in_grid && is_writable(aw_a_q));
  wire              wr_reg  = do_write && !in_grid && is_writable(aw_a_q);

  // Clamped values fit their fields, so only the low bits are used.
  /* verilator lint_off UNUSEDSIGNAL */
  wire [32:0] c_width  = clamp_u(wm({{(32-XW){1'b0}}, width_q}), SM_WIDTH_VALUE_MIN, SM_WIDTH_VALUE_MAX);
  wire [32:0] c_height = clamp_u(wm({{(32-YW){1'b0}}, height_q}), SM_HEIGHT_VALUE_MIN, SM_HEIGHT_VALUE_MAX);
  wire [32:0] c_gain_l = clamp_u(wm({22'd0, gain_l_q}), SM_GAIN_L_VALUE_MIN, SM_GAIN_L_VALUE_MAX);
  wire [32:0] c_gain_r = clamp_u(wm({22'd0, gain_r_q}), SM_GAIN_R_VALUE_MIN, SM_GAIN_R_VALUE_MAX);
  wire [32:0] c_off_l  = clamp_s(wm({{23{offset_l_q[8]}}, offset_l_q}), SM_OFFSET_L_VALUE_MIN, SM_OFFSET_L_VALUE_MAX);
  wire [32:0] c_off_r  = clamp_s(wm({{23{offset_r_q[8]}}, offset_r_q}), SM_OFFSET_R_VALUE_MIN, SM_OFFSET_R_VALUE_MAX);
  wire [32:0] c_occ    = clamp_u(wm({24'd0, occ_q}), SM_OCC_VALUE_MIN, SM_OCC_VALUE_MAX);
  wire [32:0] c_occ_e  = clamp_u(wm({24'd0, occ_edge_q}), SM_OCC_EDGE_VALUE_MIN, SM_OCC_EDGE_VALUE_MAX);
  wire [32:0] c_edge_t = clamp_u(wm({24'd0, edge_t_q}), SM_EDGE_T_VALUE_MIN, SM_EDGE_T_VALUE_MAX);
  wire [32:0] c_near   = clamp_u(wm({24'd0, obj_near_q}), SM_OBJ_NEAR_VALUE_MIN, SM_OBJ_NEAR_VALUE_MAX);
  wire [32:0] c_tol    = clamp_u(wm({24'd0, obj_tol_q}), SM_OBJ_TOL_VALUE_MIN, SM_OBJ_TOL_VALUE_MAX);
  wire [32:0] c_minpix = clamp_u(wm({16'd0, obj_min_pixels_q}), SM_OBJ_MIN_PIXELS_VALUE_MIN, SM_OBJ_MIN_PIXELS_VALUE_MAX);
  wire [31:0] c_control = wm(control_own);
  wire [31:0] c_rect_en = wm({31'd0, rect_enable_q});
  wire [31:0] c_filter  = wm({28'd0, filter_enable_q});
  /* verilator lint_on UNUSEDSIGNAL */
  reg         clamped;
  always @(*) begin
    case (wa)
      SM_WIDTH_ADDR:  clamped = c_width[32];
      SM_HEIGHT_ADDR: clamped = c_height[32];
      SM_GAIN_L_ADDR: clamped = c_gain_l[32];
      SM_GAIN_R_ADDR: clamped = c_gain_r[32];
      SM_OFFSET_L_ADDR: clamped = c_off_l[32];
      SM_OFFSET_R_ADDR: clamped = c_off_r[32];
      SM_OCC_ADDR: clamped = c_occ[32];
      SM_OCC_EDGE_ADDR: clamped = c_occ_e[32];
      SM_EDGE_T_ADDR: clamped = c_edge_t[32];
      SM_OBJ_NEAR_ADDR: clamped = c_near[32];
      SM_OBJ_TOL_ADDR: clamped = c_tol[32];
      SM_OBJ_MIN_PIXELS_ADDR: clamped = c_minpix[32];
      default: clamped = 1'b0;
    endcase
  end
  wire clear_errors = wr_reg && (wa == SM_CONTROL_ADDR) && w1[SM_CONTROL_CLEAR_ERRORS_LSB];

  always @(posedge aclk) begin
    if (!aresetn) begin
      aw_v_q        <= 1'b0;
      w_v_q         <= 1'b0;
      s_axil_bvalid <= 1'b0;
      s_axil_bresp  <= OKAY;
    end else begin
      if (s_axil_awvalid && !aw_v_q) aw_v_q <= 1'b1;
      if (s_axil_wvalid && !w_v_q) w_v_q <= 1'b1;
      if (do_write) begin
        aw_v_q        <= 1'b0;
        w_v_q         <= 1'b0;
        s_axil_bvalid <= 1'b1;
        s_axil_bresp  <= wr_ok ? OKAY : SLVERR;
      end else if (s_axil_bready) begin
        s_axil_bvalid <= 1'b0;
      end
    end
  end
  always @(posedge aclk) begin
    if (s_axil_awvalid && !aw_v_q) aw_a_q <= s_axil_awaddr;
    if (s_axil_wvalid && !w_v_q) begin
      w_d_q <= s_axil_wdata;
      w_s_q <= s_axil_wstrb;
    end
  end

  // ---- grid forwarding (data path: no reset)
  always @(posedge aclk) begin
    if (!aresetn) grid_we <= 1'b0;
    else grid_we <= do_write && grid_ok;
  end
  always @(posedge aclk) begin
    grid_waddr <= {g_word[SM_GRID_POINT_BITS+1:SM_GRID_POINT_BITS], g_point[PB-1:0]};
    grid_wdata <= w_d_q;
  end

  // ---- host copy, status and shadow copy
  integer n;
  always @(posedge aclk) begin
    if (!aresetn) begin
      enable           <= SM_CONTROL_ENABLE_RESET[0];
      soft_reset       <= 1'b0;
      grid_bank_q      <= SM_CONTROL_GRID_BANK_RESET[0];
      width_q          <= SM_WIDTH_VALUE_RESET[XW-1:0];
      height_q         <= SM_HEIGHT_VALUE_RESET[YW-1:0];
      gain_l_q         <= SM_GAIN_L_VALUE_RESET[9:0];
      gain_r_q         <= SM_GAIN_R_VALUE_RESET[9:0];
      offset_l_q       <= SM_OFFSET_L_VALUE_RESET[8:0];
      offset_r_q       <= SM_OFFSET_R_VALUE_RESET[8:0];
      rect_enable_q    <= SM_RECT_ENABLE_VALUE_RESET[0];
      occ_q            <= SM_OCC_VALUE_RESET[7:0];
      occ_edge_q       <= SM_OCC_EDGE_VALUE_RESET[7:0];
      edge_t_q         <= SM_EDGE_T_VALUE_RESET[7:0];
      sw_table_q       <= {SM_SW_TABLE1_CODES_RESET, SM_SW_TABLE0_CODES_RESET};
      filter_enable_q  <= SM_FILTER_ENABLE_VALUE_RESET[3:0];
      obj_near_q       <= SM_OBJ_NEAR_VALUE_RESET[7:0];
      obj_tol_q        <= SM_OBJ_TOL_VALUE_RESET[7:0];
      obj_min_pixels_q <= SM_OBJ_MIN_PIXELS_VALUE_RESET[15:0];
      frame_count_q    <= 16'd0;
      err_flags_q      <= 8'd0;
      err_cnt_q <= 112'd0;
      level_max_q      <= {LEVEL_W{1'b0}};
    end else begin
      if (clear_errors) level_max_q <= in_level;
      else if (in_level > level_max_q) level_max_q <= in_level;
      soft_reset <= 1'b0;
      if (frame_start) frame_count_q <= frame_count_q + 1'b1;
      // Error bookkeeping: a clear loses against an event of the same clock.
      if (clear_errors) begin
        err_flags_q <= 8'd0;
        err_cnt_q <= 112'd0;
      end else if (wr_reg && wa == SM_ERR_FLAGS_ADDR) begin
        err_flags_q <= err_flags_q & ~w1[7:0];
      end
      for (n = 0; n < 7; n = n + 1) begin
        if (err_pulse[n]) begin
          err_flags_q[n] <= 1'b1;
          if (clear_errors) err_cnt_q[16*n +: 16] <= 16'd1;
          else if (err_cnt_q[16*n +: 16] != 16'hffff)
            err_cnt_q[16*n +: 16] <= err_cnt_q[16*n +: 16] + 1'b1;
        end
      end
      if (wr_reg && clamped) err_flags_q[SM_ERR_FLAGS_CLAMPED_LSB] <= 1'b1;
      if (wr_reg) begin
        case (wa)
          SM_CONTROL_ADDR: begin
            enable      <= c_control[SM_CONTROL_ENABLE_LSB];
            grid_bank_q <= c_control[SM_CONTROL_GRID_BANK_LSB];
            soft_reset  <= w1[SM_CONTROL_SOFT_RESET_LSB];
          end
          SM_WIDTH_ADDR:  width_q <= c_width[XW-1:0];
          SM_HEIGHT_ADDR: height_q <= c_height[YW-1:0];
          SM_GAIN_L_ADDR: gain_l_q <= c_gain_l[9:0];
          SM_GAIN_R_ADDR: gain_r_q <= c_gain_r[9:0];
          SM_OFFSET_L_ADDR: offset_l_q <= c_off_l[8:0];
          SM_OFFSET_R_ADDR: offset_r_q <= c_off_r[8:0];
          SM_RECT_ENABLE_ADDR: rect_enable_q <= c_rect_en[0];
          SM_OCC_ADDR: occ_q <= c_occ[7:0];
          SM_OCC_EDGE_ADDR: occ_edge_q <= c_occ_e[7:0];
          SM_EDGE_T_ADDR: edge_t_q <= c_edge_t[7:0];
          SM_SW_TABLE0_ADDR: sw_table_q[31:0] <= wm(sw_table_q[31:0]);
          SM_SW_TABLE1_ADDR: sw_table_q[63:32] <= wm(sw_table_q[63:32]);
          SM_FILTER_ENABLE_ADDR: filter_enable_q <= c_filter[3:0];
          SM_OBJ_NEAR_ADDR: obj_near_q <= c_near[7:0];
          SM_OBJ_TOL_ADDR: obj_tol_q <= c_tol[7:0];
          SM_OBJ_MIN_PIXELS_ADDR: obj_min_pixels_q <= c_minpix[15:0];
          default: ;
        endcase
      end
    end
  end

  // The shadow copy takes the host copy as it was before this clock's write.
  always @(posedge aclk) begin
    if (!aresetn) begin
      cfg_width          <= SM_WIDTH_VALUE_RESET[XW-1:0];
      cfg_height         <= SM_HEIGHT_VALUE_RESET[YW-1:0];
      cfg_gain_l         <= SM_GAIN_L_VALUE_RESET[9:0];
      cfg_gain_r         <= SM_GAIN_R_VALUE_RESET[9:0];
      cfg_offset_l       <= SM_OFFSET_L_VALUE_RESET[8:0];
      cfg_offset_r       <= SM_OFFSET_R_VALUE_RESET[8:0];
      cfg_rect_enable    <= SM_RECT_ENABLE_VALUE_RESET[0];
      cfg_grid_bank      <= SM_CONTROL_GRID_BANK_RESET[0];
      cfg_occ            <= SM_OCC_VALUE_RESET[7:0];
      cfg_occ_edge       <= SM_OCC_EDGE_VALUE_RESET[7:0];
      cfg_edge_t         <= SM_EDGE_T_VALUE_RESET[7:0];
      cfg_sw_table       <= {SM_SW_TABLE1_CODES_RESET, SM_SW_TABLE0_CODES_RESET};
      cfg_filter_enable  <= SM_FILTER_ENABLE_VALUE_RESET[3:0];
      cfg_obj_near       <= SM_OBJ_NEAR_VALUE_RESET[7:0];
      cfg_obj_tol        <= SM_OBJ_TOL_VALUE_RESET[7:0];
      cfg_obj_min_pixels <= SM_OBJ_MIN_PIXELS_VALUE_RESET[15:0];
    end else if (frame_start) begin
      cfg_width          <= width_q;
      cfg_height         <= height_q;
      cfg_gain_l         <= gain_l_q;
      cfg_gain_r         <= gain_r_q;
      cfg_offset_l       <= offset_l_q;
      cfg_offset_r       <= offset_r_q;
      cfg_rect_enable    <= rect_enable_q;
      cfg_grid_bank      <= grid_bank_q;
      cfg_occ            <= occ_q;
      cfg_occ_edge       <= occ_edge_q;
      cfg_edge_t         <= edge_t_q;
      cfg_sw_table       <= sw_table_q;
      cfg_filter_enable  <= filter_enable_q;
      cfg_obj_near       <= obj_near_q;
      cfg_obj_tol        <= obj_tol_q;
      cfg_obj_min_pixels <= obj_min_pixels_q;
    end
  end

  // ---- read channel: accept, wait two clocks for the object port, answer
  reg [1:0]        rd_stage_q;  // 0 idle, 1..2 waiting
  reg [ADDR_W-1:0] ar_a_q;
  assign s_axil_arready = (rd_stage_q == 2'd0) && !s_axil_rvalid;

  wire              in_obj  = (ar_a_q >= SM_OBJ_BASE) && (ar_a_q < SM_OBJ_BASE + SM_OBJ_SIZE);
  // The window is aligned to its size: the word index is a slice of the address.
  wire [OWW-1:0]    rq_word = ar_a_q[OWW+1:2];
  wire              obj_ok  = in_obj && ((rq_word == {OWW{1'b0}}) ||
                              (({1'b0, rq_word} >= OBJ_FIRST) && ({1'b0, rq_word} < OBJ_END)));
  wire              reg_ok  = is_reg(ar_a_q);

  always @(posedge aclk) begin
    if (!aresetn) begin
      rd_stage_q    <= 2'd0;
      s_axil_rvalid <= 1'b0;
      s_axil_rresp  <= OKAY;
    end else begin
      if (s_axil_arvalid && s_axil_arready) rd_stage_q <= 2'd1;
      else if (rd_stage_q == 2'd1) rd_stage_q <= 2'd2;
      else if (rd_stage_q == 2'd2) begin
        rd_stage_q    <= 2'd0;
        s_axil_rvalid <= 1'b1;
        s_axil_rresp  <= (obj_ok || reg_ok) ? OKAY : SLVERR;
      end else if (s_axil_rready) begin
        s_axil_rvalid <= 1'b0;
      end
    end
  end
  always @(posedge aclk) begin
    if (s_axil_arvalid && s_axil_arready) begin
      ar_a_q     <= s_axil_araddr;
      obj_rd_idx <= s_axil_araddr[OIW+1:2];
    end
    if (rd_stage_q == 2'd2) s_axil_rdata <= obj_ok ? obj_rd_data : host_value(ar_a_q);
  end

`ifndef SYNTHESIS
  // Simulation-only AXI4-Lite rules (Verilator --assert builds): B and R stay valid with
  // the same response until the master takes them.
  reg        chk_b_q, chk_r_q;
  reg [1:0]  chk_bresp_q;
  reg [33:0] chk_r_word_q;
  always @(posedge aclk) begin
    chk_b_q      <= aresetn && s_axil_bvalid && !s_axil_bready;
    chk_r_q      <= aresetn && s_axil_rvalid && !s_axil_rready;
    chk_bresp_q  <= s_axil_bresp;
    chk_r_word_q <= {s_axil_rresp, s_axil_rdata};
    if (aresetn) begin
      if (chk_b_q && (!s_axil_bvalid || s_axil_bresp != chk_bresp_q))
        $error("sm_axil_regs: B response withdrawn or changed before bready");
      if (chk_r_q && (!s_axil_rvalid || {s_axil_rresp, s_axil_rdata} != chk_r_word_q))
        $error("sm_axil_regs: R response withdrawn or changed before rready");
    end
  end
`endif
endmodule
`default_nettype wire
