`default_nettype none
`include "sm_defs.vh"
// The output stage's first half, at the DP's read-out (docs/algorithm.md 9.6; model
// out_fields): a pixel's evidence -- the DP's level d, matched, gap and background fill
// from the traceback, the WTA record (dw, c1, c2, cmax, the band A(dw-2 .. dw+2)) and
// the right-view WTA level lr of right pixel x - d -- becomes the fields that travel
// beside the disparity through the post filters to sm_outword:
//   off       the Q.4 offset from 16 d (9.1): SUBPIX 2 fits the band at d when
//             |d - dw| <= 1 and 0 < d < DISP-1; SUBPIX 1 gives 16 (dw - d) + the fit of
//             band[1..3] when |d - dw| <= 1 and 0 < dw < DISP-1; otherwise 0
//   fail      an enabled rule of 9.2 fails (occlusion, left-right, agreement, uniqueness,
//             texture; the left border needs the output level and is sm_outword's)
//   lr_ok, agree_ok, ratio, matched   the confidence's bits (9.3); where fail, ratio
//             carries the rules that fail instead, {lr, tex, agree, uniq, occ}, for the
//             invalid word (9.4): an invalid pixel has no confidence, so the slot is free
//             and the fields' row store keeps its width
//   fb        the background fill where it may replace the level (occ_en 0, fill_bg 1,
//             unmatched), else DISP-1 (never below a level)
//   border_en occ_en, for sm_outword's border rule
// A pixel left of its level (x < d) has no right pixel: lr reads as 255, as in the model.
// s_cfg = {tex_t, uniq_t, agree_t, lr_t, occ_t (8 bits each), tex_en, uniq_en, agree_en,
// lr_en, fill_bg, occ_en, subpix_fit, subpix[1:0]} (the registers of the beat's frame);
// it is registered with the beat, so a frame boundary inside the pipeline is harmless.
// Pipeline: stage A registers the differences, stage B their magnitudes, stage C the
// rule compares; stage A2 registers the fit's three costs, so the fit (sm_subpix_fit,
// 7 ce's) and the ratio (sm_conf_ratio, 6 ce's and one register) start after A2; the
// word is registered on the ce after the fit, so the fields of the beat taken at ce n are
// on m_fields after ce n + 9 (m_side too: LAT = 10 stages).
module sm_outfields #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter DISP      = 128,  // disparity levels
    parameter CW        = 6     // aggregated cost width
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [XW-1:0]         s_x,        // column of the beat
    input  wire [DW-1:0]         s_d,        // the DP's level (after its fill)
    input  wire                  s_matched,
    input  wire [7:0]            s_gap,
    input  wire [DW-1:0]         s_fill_bg,
    input  wire [DW-1:0]         s_dw,
    input  wire [CW-1:0]         s_c1,
    input  wire [CW-1:0]         s_c2,
    input  wire [CW-1:0]         s_cmax,
    input  wire [5*CW-1:0]       s_band,     // A(dw - 2 + j) at [j*CW +: CW]
    input  wire [DW-1:0]         s_lr,       // right-view WTA level of right pixel x - d
    input  wire [CFG_W-1:0]      s_cfg,
    output wire [`SM_SIDE_W-1:0] m_side,
    output reg  [FIELDS_W-1:0]   m_fields    // sm_outword's s_fields
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam DW = $clog2(DISP);
  localparam FIELDS_W = 2 * DW + 16;
  localparam CFG_W = 49;
  localparam FIT_LAT = 7;  // sm_subpix_fit
  localparam RATIO_LAT = 6;  // sm_conf_ratio
  localparam LAT = FIT_LAT + 3;  // register stages, input to m_fields (A, A2, fit, word)
  /* verilator lint_off WIDTH */  // constants in the level width
  localparam [DW-1:0] D_TOP = DISP - 1;
  /* verilator lint_on WIDTH */

  generate
    `SM_BAD_PARAM(g_bad_disp, DISP < `SM_DISP_MIN || DISP > `SM_DISP_MAX || DISP % 2 != 0,
                  ("sm_outfields: DISP (%0d) must be even, %0d..%0d", DISP, `SM_DISP_MIN, `SM_DISP_MAX))
    `SM_BAD_PARAM(g_bad_cw, CW < 1 || CW > 8, ("sm_outfields: CW (%0d) must be 1..8", CW))
  endgenerate

  // ---- stage A: differences; the configuration and the beat registered ----
  /* verilator lint_off WIDTH */  // zero-extensions to 9 signed bits
  wire [8:0] ddw = {1'b0, s_d} - {1'b0, s_dw};        // d - dw
  wire [8:0] dlr = {1'b0, s_lr} - {1'b0, s_d};        // lr - d
  wire [7:0] d255 = 8'd255 - s_d;                     // |255 - d|: x < d
  /* verilator lint_on WIDTH */
  reg  [8:0]       ddw_a, dlr_a;
  reg  [7:0]       d255_a;
  reg              left_a;  // x < d
  reg              occf_a;  // unmatched and gap > occ_t
  reg  [CW-1:0]    uniqm_a, texm_a;  // c2 - c1, cmax - c1
  reg  [CFG_W-1:0] cfg_a;
  reg  [DW-1:0]    d_a, dw_a, fb_a;
  reg              match_a;
  reg  [5*CW-1:0]  band_a;
  reg  [CW-1:0]    c1_a, c2_a;
  /* verilator lint_off WIDTH */  // the level zero-extended to the column's width
  wire left = s_x < s_d;
  /* verilator lint_on WIDTH */
  always @(posedge clk) begin
    if (ce) begin
      ddw_a   <= ddw;
      dlr_a   <= dlr;
      d255_a  <= d255;
      left_a  <= left;
      occf_a  <= !s_matched && (s_gap > s_cfg[16:9]);
      uniqm_a <= s_c2 - s_c1;
      texm_a  <= s_cmax - s_c1;
      cfg_a   <= s_cfg;
      d_a     <= s_d;
      dw_a    <= s_dw;
      fb_a    <= (!s_cfg[3] && s_cfg[4] && !s_matched) ? s_fill_bg : D_TOP;
      match_a <= s_matched;
      band_a  <= s_band;
      c1_a    <= s_c1;
      c2_a    <= s_c2;
    end
  end

  // ---- the fit's inputs at stage A: the band around d (SUBPIX 2) or dw (SUBPIX 1) ----
  wire          near_a = (ddw_a == 9'd0) || (ddw_a == 9'd1) || (ddw_a == 9'h1ff);  // |d - dw| <= 1
  wire          src1 = (cfg_a[1:0] == 2'd1);
  wire          fit_ok = near_a && (src1 ? (dw_a != {DW{1'b0}} && dw_a != D_TOP) :
                                           (cfg_a[1:0] == 2'd2 && d_a != {DW{1'b0}} && d_a != D_TOP));
  // SUBPIX 2: the three band entries centred on j = d - dw + 2
  wire [1:0]    jm = src1 ? 2'd1 : (ddw_a == 9'h1ff) ? 2'd0 : (ddw_a == 9'd0) ? 2'd1 : 2'd2;  // j - 1
  wire [5*CW-1:0] b = band_a;
  wire [3*CW-1:0] trio = (jm == 2'd0) ? b[0 +: 3*CW] : (jm == 2'd1) ? b[CW +: 3*CW] : b[2*CW +: 3*CW];
  wire [3*CW-1:0] tri_in = fit_ok ? trio : {(3 * CW) {1'b0}};  // flat: no fit, f = 0
  // SUBPIX 1: the offset of dw from d, -16 / 0 / +16
  wire [5:0]    base_a = (!fit_ok || !src1) ? 6'd0 : (ddw_a == 9'd1) ? 6'b110000 : (ddw_a == 9'h1ff) ? 6'd16 : 6'd0;

  // registered (stage A2) so that the selects above and the fit's first stage are
  // separate paths
  reg [3*CW-1:0] tri_q;
  reg            fit_s_q;
  reg [CW-1:0]   c1_q, c2_q;
  always @(posedge clk) begin
    if (ce) begin
      tri_q   <= tri_in;
      fit_s_q <= cfg_a[2];
      c1_q    <= c1_a;
      c2_q    <= c2_a;
    end
  end
  wire [`SM_SIDE_W-1:0] fit_side, ratio_side;
  wire [4:0] frac, ratio;
  sm_subpix_fit #(.CW(CW)) u_fit (
      .clk(clk), .rst_n(rst_n), .ce(ce), .s_side({`SM_SIDE_W{1'b0}}),
      .s_cm(tri_q[0 +: CW]), .s_c0(tri_q[CW +: CW]), .s_cp(tri_q[2*CW +: CW]), .s_fit(fit_s_q),
      .m_side(fit_side), .m_frac(frac)
  );
  sm_conf_ratio #(.CW(CW)) u_ratio (
      .clk(clk), .rst_n(rst_n), .ce(ce), .s_side({`SM_SIDE_W{1'b0}}),
      .s_c1(c1_q), .s_c2(c2_q), .m_side(ratio_side), .m_ratio(ratio)
  );
  wire unused_sides = ^{fit_side, ratio_side};

  // ---- stage B: magnitudes ----
  wire [8:0] addw = ddw_a[8] ? -ddw_a : ddw_a;
  wire [8:0] adlr = dlr_a[8] ? -dlr_a : dlr_a;
  wire unused_mag = ^{addw[8], adlr[8]};  // |d - dw|, |lr - d| <= 255
  reg  [7:0] addw_b, adlr_b;
  reg  [CW-1:0] uniqm_b, texm_b;
  reg        occf_b;
  reg  [CFG_W-1:0] cfg_b;
  always @(posedge clk) begin
    if (ce) begin
      addw_b  <= addw[7:0];
      adlr_b  <= left_a ? d255_a : adlr[7:0];
      uniqm_b <= uniqm_a;
      texm_b  <= texm_a;
      occf_b  <= occf_a;
      cfg_b   <= cfg_a;
    end
  end

  wire unused_cfg_b = ^{cfg_b[16:9], cfg_b[4], cfg_b[2:0]};  // used at stage A

  // ---- stage C: the rules ----
  /* verilator lint_off WIDTH */  // costs zero-extended to the thresholds' 8 bits
  wire [4:0] fails_c = {cfg_b[5] && adlr_b > cfg_b[24:17], cfg_b[8] && texm_b < cfg_b[48:41],
                        cfg_b[6] && addw_b > cfg_b[32:25], cfg_b[7] && uniqm_b < cfg_b[40:33],
                        cfg_b[3] && occf_b};  // {lr, tex, agree, uniq, occ}
  /* verilator lint_on WIDTH */
  reg [4:0] fails_cq;
  reg fail_cq, lrok_cq, agok_cq;
  always @(posedge clk) begin
    if (ce) begin
      fails_cq <= fails_c;
      fail_cq <= |fails_c;
      lrok_cq <= adlr_b <= 8'd1;
      agok_cq <= addw_b <= 8'd1;
    end
  end

  // ---- the beat's other fields, delayed to the fit ----
  // stage A values needed at the end: d, fb, matched, border enable, the SUBPIX 1 base
  localparam KA = 2 * DW + 8;  // {base, border_en, matched, fb, d}
  localparam KC = 8;           // {fails, agree_ok, lr_ok, fail}
  // stage A's values meet the fit FIT_LAT + 1 ce's after A, stage C's FIT_LAT - 1 after C
  localparam NA = FIT_LAT + 1;
  localparam NC = FIT_LAT - 1;
  reg [KA*NA-1:0] ka_q;
  reg [KC*NC-1:0] kc_q;
  reg [4:0]       ratio_q;
  wire [KA-1:0] ka_in = {base_a, cfg_a[3], match_a, fb_a, d_a};
  wire [KC-1:0] kc_in = {fails_cq, agok_cq, lrok_cq, fail_cq};
  integer i;
  always @(posedge clk) begin
    if (ce) begin
      ka_q[0 +: KA] <= ka_in;
      for (i = 1; i < NA; i = i + 1) ka_q[i*KA +: KA] <= ka_q[(i-1)*KA +: KA];
      kc_q[0 +: KC] <= kc_in;
      for (i = 1; i < NC; i = i + 1) kc_q[i*KC +: KC] <= kc_q[(i-1)*KC +: KC];
      ratio_q <= ratio;
    end
  end
  wire [KA-1:0] ka = ka_q[(NA-1)*KA +: KA];
  wire [KC-1:0] kc = kc_q[(NC-1)*KC +: KC];
  wire [DW-1:0] d_k = ka[DW-1:0];
  wire [DW-1:0] fb_k = ka[DW +: DW];
  wire          match_k = ka[2*DW];
  wire          bord_k = ka[2*DW+1];
  wire [5:0]    base_k = ka[2*DW+2 +: 6];
  wire [5:0]    off = base_k + {frac[4], frac};
  always @(posedge clk) begin
    // {fb, ratio or the failed rules, agree_ok, matched, lr_ok, border_en, fail, off, d}
    if (ce) m_fields <= {fb_k, kc[0] ? kc[7:3] : ratio_q, kc[2], match_k, kc[1], bord_k, kc[0], off, d_k};
  end

  sm_side_delay #(.DEPTH(LAT)) u_side (.clk(clk), .rst_n(rst_n), .ce(ce), .d(s_side), .q(m_side));
  wire unused_lat = ^RATIO_LAT;
endmodule
`default_nettype wire
