`default_nettype none
`include "sm_defs.vh"
// AXI4-Lite register file (docs/registers.md, generated from rtl/regmap.json together
// with the included sm_regmap.vh). The host sees and writes one copy of the pipeline
// parameters; a shadow copy drives the pipeline and is refreshed from the host copy only
// at frame_start (the input sequencer's frame boundary), so a frame is never processed
// with a half-written parameter set. Writes are clamped to each register's range
// (ERR_FLAGS.CLAMPED records that it happened). The object list is read through the
// object block's read port; rectification grid writes are forwarded to the grid RAM.
// The rw fields (address, position, reset, range, shadow) and the constant ro fields come
// from the generated tables (SM_RW_*, SM_CONST_*, SM_REG_*): a plain rw register added to
// regmap.json needs no edit here; only the live ro fields and CONTROL's pulses are
// written out by hand.
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
    parameter LEVEL_W     = 10,   // width of the input FIFO level
    parameter MIN_HEIGHT  = 16,   // shortest active frame (sm_top: four frames outlast the pipeline)
    parameter SPECKLE_ROWS = 0    // the speckle stage's rows (reported in CAPS1; 0: none)
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
    output wire              enable,
    output reg               soft_reset,    // one-clock pulse
    output wire [XW-1:0]     host_width,    // host values for the sequencer's frame start
    output wire [YW-1:0]     host_height,
    // shadow copy of the pipeline parameters (what the pipeline uses), slices of the
    // packed shadow vector; toggle coverage counts the shadow registers themselves
    /* verilator coverage_off */
    output wire [XW-1:0]     cfg_width,
    output wire [YW-1:0]     cfg_height,
    output wire [9:0]        cfg_gain_l,
    output wire [9:0]        cfg_gain_r,
    output wire [8:0]        cfg_offset_l,
    output wire [8:0]        cfg_offset_r,
    output wire              cfg_rect_enable,
    output wire              cfg_grid_bank,
    output wire [7:0]        cfg_occ,
    output wire [7:0]        cfg_occ_edge,
    output wire [7:0]        cfg_edge_t,
    output wire [63:0]       cfg_sw_table,    // code k at bits 2k+1:2k
    output wire [3:0]        cfg_filter_enable,
    output wire [7:0]        cfg_obj_near,
    output wire [7:0]        cfg_obj_tol,
    output wire [15:0]       cfg_obj_min_pixels,
    // the output stage's registers SUBPIX .. TEX_T in sm_outfields' s_cfg layout: {TEX_T,
    // UNIQ_T, AGREE_T, LR_T, OCC_T, TEX_EN, UNIQ_EN, AGREE_EN, LR_EN, FILL_BG, OCC_EN,
    // SUBPIX_FIT, SUBPIX}
    output wire [48:0]       cfg_out,
    output wire [6:0]        cfg_smooth,      // {SMOOTH_T, SMOOTH_EN}
    output wire [32:0]       cfg_speckle,     // {SPECKLE_TRUST, SPECKLE_DIFF, SPECKLE_SIZE, SPECKLE_EN}
    /* verilator coverage_on */
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
  // The checked mode's reset (HwConfig::speckle_mode / pixel_rules): where the speckle stage
  // is built it replaces the per-pixel left-right and agreement rules (SPECKLE_EN 1, LR_EN
  // and AGREE_EN 0), chosen on the 14 scenes.
  localparam integer SPECKLE_MODE = (SPECKLE_ROWS > 0) ? 1 : 0;
  localparam integer PIXEL_RULES = 1 - SPECKLE_MODE;
  /* verilator lint_off UNUSEDPARAM */  // the generated map holds every field's constants
  // The older Verilator (5.006) calls the tables' 32-bit typed elements unsized when
  // their value comes from an unsized expression; the newer one does not.
  /* verilator lint_off WIDTHCONCAT */
  `include "sm_regmap.vh"
  /* verilator lint_on WIDTHCONCAT */
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

  // ---- status (live fields, hand-written: they carry behaviour)
  reg [15:0]   frame_count_q;
  reg [7:0]    err_flags_q;
  reg [111:0]  err_cnt_q;  // 7 x 16 bits, class n at 16n +: 16 (ERR_FLAGS bit order)
  reg [LEVEL_W-1:0] level_max_q;  // input FIFO high-water mark

  // ---- host and shadow copies of the rw fields: packed as the generated table says
  // (SM_RW_*), so a register added to regmap.json needs no edit here.
  // Both vectors only gather the fields' own registers (g_rw[].q, g_rw[].g_shadow.s):
  // toggle coverage counts those, not these aliases a second time.
  /* verilator coverage_off */
  wire [SM_RW_BITS-1:0]     host_q;
  wire [SM_SHADOW_BITS-1:0] shadow_q;
  /* verilator coverage_on */

  assign enable      = host_q[SM_CONTROL_ENABLE_OFF];
  assign host_width  = host_q[SM_WIDTH_VALUE_OFF +: SM_WIDTH_VALUE_SW];
  assign host_height = host_q[SM_HEIGHT_VALUE_OFF +: SM_HEIGHT_VALUE_SW];
  assign cfg_width          = shadow_q[SM_WIDTH_VALUE_SOFF +: SM_WIDTH_VALUE_SW];
  assign cfg_height         = shadow_q[SM_HEIGHT_VALUE_SOFF +: SM_HEIGHT_VALUE_SW];
  assign cfg_gain_l         = shadow_q[SM_GAIN_L_VALUE_SOFF +: SM_GAIN_L_VALUE_SW];
  assign cfg_gain_r         = shadow_q[SM_GAIN_R_VALUE_SOFF +: SM_GAIN_R_VALUE_SW];
  assign cfg_offset_l       = shadow_q[SM_OFFSET_L_VALUE_SOFF +: SM_OFFSET_L_VALUE_SW];
  assign cfg_offset_r       = shadow_q[SM_OFFSET_R_VALUE_SOFF +: SM_OFFSET_R_VALUE_SW];
  assign cfg_rect_enable    = shadow_q[SM_RECT_ENABLE_VALUE_SOFF];
  assign cfg_grid_bank      = shadow_q[SM_CONTROL_GRID_BANK_SOFF];
  assign cfg_occ            = shadow_q[SM_OCC_VALUE_SOFF +: SM_OCC_VALUE_SW];
  assign cfg_occ_edge       = shadow_q[SM_OCC_EDGE_VALUE_SOFF +: SM_OCC_EDGE_VALUE_SW];
  assign cfg_edge_t         = shadow_q[SM_EDGE_T_VALUE_SOFF +: SM_EDGE_T_VALUE_SW];
  assign cfg_sw_table       = {shadow_q[SM_SW_TABLE1_CODES_SOFF +: SM_SW_TABLE1_CODES_SW],
                               shadow_q[SM_SW_TABLE0_CODES_SOFF +: SM_SW_TABLE0_CODES_SW]};
  assign cfg_filter_enable  = shadow_q[SM_FILTER_ENABLE_VALUE_SOFF +: SM_FILTER_ENABLE_VALUE_SW];
  assign cfg_obj_near       = shadow_q[SM_OBJ_NEAR_VALUE_SOFF +: SM_OBJ_NEAR_VALUE_SW];
  assign cfg_obj_tol        = shadow_q[SM_OBJ_TOL_VALUE_SOFF +: SM_OBJ_TOL_VALUE_SW];
  assign cfg_obj_min_pixels = shadow_q[SM_OBJ_MIN_PIXELS_VALUE_SOFF +: SM_OBJ_MIN_PIXELS_VALUE_SW];
  assign cfg_out = {shadow_q[SM_TEX_T_VALUE_SOFF +: 8], shadow_q[SM_UNIQ_T_VALUE_SOFF +: 8],
                    shadow_q[SM_AGREE_T_VALUE_SOFF +: 8], shadow_q[SM_LR_T_VALUE_SOFF +: 8],
                    shadow_q[SM_OCC_T_VALUE_SOFF +: 8], shadow_q[SM_TEX_EN_VALUE_SOFF],
                    shadow_q[SM_UNIQ_EN_VALUE_SOFF], shadow_q[SM_AGREE_EN_VALUE_SOFF], shadow_q[SM_LR_EN_VALUE_SOFF],
                    shadow_q[SM_FILL_BG_VALUE_SOFF], shadow_q[SM_OCC_EN_VALUE_SOFF],
                    shadow_q[SM_SUBPIX_FIT_VALUE_SOFF], shadow_q[SM_SUBPIX_VALUE_SOFF +: 2]};
  assign cfg_smooth = {shadow_q[SM_SMOOTH_T_VALUE_SOFF +: 6], shadow_q[SM_SMOOTH_EN_VALUE_SOFF]};
  assign cfg_speckle = {shadow_q[SM_SPECKLE_TRUST_VALUE_SOFF +: 12], shadow_q[SM_SPECKLE_DIFF_VALUE_SOFF +: 8],
                        shadow_q[SM_SPECKLE_SIZE_VALUE_SOFF +: 12], shadow_q[SM_SPECKLE_EN_VALUE_SOFF]};

  // ---- address decoding (the byte-lane bits a[1:0] are ignored by design)
  /* verilator lint_off UNUSEDSIGNAL */
  function is_reg;  // word address of a register in the map
    input [ADDR_W-1:0] a;
    integer k;
    begin
      is_reg = 1'b0;
      for (k = 0; k < SM_REG_N; k = k + 1)
        if ({a[ADDR_W-1:2], 2'b00} == SM_REG_ADDR[k*ADDR_W +: ADDR_W]) is_reg = 1'b1;
    end
  endfunction

  function is_writable;  // registers with rw / w1c / wp fields
    input [ADDR_W-1:0] a;
    integer k;
    begin
      is_writable = 1'b0;
      for (k = 0; k < SM_REG_N; k = k + 1)
        if (SM_REG_WRITABLE[k] && {a[ADDR_W-1:2], 2'b00} == SM_REG_ADDR[k*ADDR_W +: ADDR_W])
          is_writable = 1'b1;
    end
  endfunction

  // Host-visible value of a register (0 for addresses outside the register block): the
  // rw and constant fields from the tables (signed fields sign-extended to bit 31), the
  // live fields by hand.
  function [31:0] host_value;
    input [ADDR_W-1:0] a;
    integer k, b, l, sw, off;
    begin
      host_value = 32'd0;
      for (k = 0; k < SM_RW_N; k = k + 1) begin
        l   = SM_RW_LSB[k*32 +: 32];
        sw  = SM_RW_SW[k*32 +: 32];
        off = SM_RW_OFF[k*32 +: 32];
        if ({a[ADDR_W-1:2], 2'b00} == SM_RW_ADDR[k*ADDR_W +: ADDR_W])
          for (b = 0; b < 32; b = b + 1)
            if (b >= l && b < l + sw) host_value[b] = host_q[off + b - l];
            else if (b >= l + sw && SM_RW_SIGNED[k]) host_value[b] = host_q[off + sw - 1];
      end
      for (k = 0; k < SM_CONST_N; k = k + 1)
        if ({a[ADDR_W-1:2], 2'b00} == SM_CONST_ADDR[k*ADDR_W +: ADDR_W])
          host_value = host_value | SM_CONST_VALUE[k*32 +: 32];
      case ({a[ADDR_W-1:2], 2'b00})
        SM_STATUS_ADDR: begin
          host_value[SM_STATUS_FRAME_COUNT_LSB +: SM_STATUS_FRAME_COUNT_W] = frame_count_q;
          host_value[SM_STATUS_GRID_BANK_ACTIVE_LSB] = cfg_grid_bank;
        end
        SM_ERR_FLAGS_ADDR: host_value[7:0] = err_flags_q;
        SM_ERR_CNT_LINE_ADDR: host_value = {err_cnt_q[16 +: 16], err_cnt_q[0 +: 16]};
        SM_ERR_CNT_SOF_ADDR:  host_value = {err_cnt_q[48 +: 16], err_cnt_q[32 +: 16]};
        SM_ERR_CNT_ROWS_ADDR: host_value = {err_cnt_q[80 +: 16], err_cnt_q[64 +: 16]};
        SM_ERR_CNT_OUT_ADDR:  host_value = {16'd0, err_cnt_q[96 +: 16]};
        SM_IN_FIFO_ADDR: host_value[SM_IN_FIFO_LEVEL_MAX_LSB +: LEVEL_W] = level_max_q;
        default: ;
      endcase
    end
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // ---- write channel: AW and W are held until both are there and B is free
  reg              aw_v_q, w_v_q;
  reg [ADDR_W-1:0] aw_a_q;
  reg [31:0]       w_d_q;
  reg [3:0]        w_s_q;
  assign s_axil_awready = !aw_v_q;
  assign s_axil_wready  = !w_v_q;
  wire do_write = aw_v_q && w_v_q && (!s_axil_bvalid || s_axil_bready);

  wire [31:0] strb_mask = {{8{w_s_q[3]}}, {8{w_s_q[2]}}, {8{w_s_q[1]}}, {8{w_s_q[0]}}};
  // A write merges the strobed bytes with the field's own value, not with the read-back
  // multiplexer's: each merge is used only at its own address, and the clamps behind it
  // stay off the multiplexer's path.
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

  // ---- the rw fields: byte merge with the field's own value, clamp, write, shadow copy.
  // A clamp works on the field-width value plus the bits above it (a wider written word
  // saturates), so no intermediate holds bits that are constant by construction.
  wire [SM_CLAMP_N-1:0] clamp_hit;  // the clamped field at wa saturated this write
  genvar gi;
  // A table bound may be the field's own limit (min 0, max 255 in 8 bits): the compare
  // is then constant, and synthesis drops it.
  /* verilator lint_off CMPCONST */
  /* verilator lint_off UNSIGNED */
  generate
    for (gi = 0; gi < SM_RW_N; gi = gi + 1) begin : g_rw
      localparam [ADDR_W-1:0] A = SM_RW_ADDR[gi*ADDR_W +: ADDR_W];
      localparam integer L   = SM_RW_LSB[gi*32 +: 32];
      localparam integer SW  = SM_RW_SW[gi*32 +: 32];
      localparam integer OFF = SM_RW_OFF[gi*32 +: 32];
      localparam [31:0]  RST = SM_RW_RESET[gi*32 +: 32];
      reg  [SW-1:0] q;
      wire [SW-1:0] nv;  // the field after this clock's write to its register
      assign host_q[OFF +: SW] = q;
      // Merged field bits (the strobed bytes of the word, the rest of the field's own value)
      wire [SW-1:0] mrg = (w_d_q[L +: SW] & strb_mask[L +: SW]) | (q & ~strb_mask[L +: SW]);
      if (SM_RW_CLAMP[gi] && !SM_RW_SIGNED[gi]) begin : g_clamp_u
        localparam [SW-1:0] MN = SM_RW_MIN[gi*32 +: SW];
        localparam [SW-1:0] MX = SM_RW_MAX[gi*32 +: SW];
        // Bits above the stored ones: the field's own value has none (0..max fits SW bits).
        wire big = |(w_d_q[31:SW] & strb_mask[31:SW]);
        assign nv = (big || mrg > MX) ? MX : (mrg < MN) ? MN : mrg;
        assign clamp_hit[SM_RW_CIDX[gi*32 +: 32]] =
            (wa == A) && (big || mrg > MX || mrg < MN);
      end else if (SM_RW_CLAMP[gi]) begin : g_clamp_s
        localparam [SW-1:0] MN = SM_RW_MIN[gi*32 +: SW];
        localparam [SW-1:0] MX = SM_RW_MAX[gi*32 +: SW];
        // Bits above the field: the field's own value is sign-extended.
        wire [31:SW] up = (w_d_q[31:SW] & strb_mask[31:SW]) |
                          ({(32 - SW){q[SW-1]}} & ~strb_mask[31:SW]);
        // The word fits the field when its bits 31..SW-1 are all equal.
        wire fits = (&{up, mrg[SW-1]}) || !(|{up, mrg[SW-1]});
        if (MN == {1'b1, {(SW - 1){1'b0}}} && MX == {1'b0, {(SW - 1){1'b1}}}) begin : g_full
          // min..max is the field's whole range: only a word that does not fit saturates
          // (no compares that could never be true, and no branch coverage points behind them).
          assign nv = !fits ? (up[31] ? MN : MX) : mrg;
          assign clamp_hit[SM_RW_CIDX[gi*32 +: 32]] = (wa == A) && !fits;
        end else begin : g_part
          assign nv = !fits ? (up[31] ? MN : MX) :
                      ($signed(mrg) < $signed(MN)) ? MN : ($signed(mrg) > $signed(MX)) ? MX : mrg;
          assign clamp_hit[SM_RW_CIDX[gi*32 +: 32]] = (wa == A) &&
              (!fits || $signed(mrg) < $signed(MN) || $signed(mrg) > $signed(MX));
        end
      end else begin : g_plain
        assign nv = mrg;
      end
      always @(posedge aclk) begin
        if (!aresetn) q <= RST[SW-1:0];
        else if (wr_reg && wa == A) q <= nv;
      end
      // The shadow copy takes the host copy as it was before this clock's write.
      if (SM_RW_SHADOW[gi]) begin : g_shadow
        localparam integer SOFF = SM_RW_SOFF[gi*32 +: 32];
        reg [SW-1:0] s;
        assign shadow_q[SOFF +: SW] = s;
        always @(posedge aclk) begin
          if (!aresetn) s <= RST[SW-1:0];
          else if (frame_start) s <= q;
        end
      end
    end
  endgenerate
  /* verilator lint_on UNSIGNED */
  /* verilator lint_on CMPCONST */
  wire clamped = |clamp_hit;
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

  // ---- CONTROL pulses and status
  integer n;
  always @(posedge aclk) begin
    if (!aresetn) begin
      soft_reset       <= 1'b0;
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
      if (wr_reg && wa == SM_CONTROL_ADDR) soft_reset <= w1[SM_CONTROL_SOFT_RESET_LSB];
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
