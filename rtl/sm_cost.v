`default_nettype none
`include "sm_defs.vh"
// Matching cost: Hamming distance of the left census vector with the right vectors
// of the DISP previous beats, plus the intensity term of the centre pixels (sm_ad_term),
// capped at CB (sm_cost_addsat; docs/algorithm.md, section 4), leaving at the
// aggregation's scale: C = that >> COST_SHIFT, CW = HW - COST_SHIFT planes, the only
// bits sm_sw_aggregate reads (the low planes would be registered here for nothing: 256
// flip-flops at the paper configuration, 768 at zynq's hold registers). The right vectors and
// pixels of the last beats sit in delay lines; since rows are exactly width beats, the
// beat d back in the same row is the right pixel x - d. A thermometer of the column
// (reset by sol) marks the levels with x - d < 0, which get CB.
//
// Latency 3 ce at every PU: popcount leaves, popcount result, output (with the x - d < 0
// rule) when PU = DISP; when folded, the beat's result is picked up on the second ce
// after the one that sampled it, like the parallel pipeline's.
//
// Folded (F = DISP / PU > 1 clocks per beat, PU popcount lanes): lane j at sub-step g
// computes level d = F*j + g + 1, except lane PU-1 at the last sub-step, which computes
// level 0 (d = DISP would be the unused beat n - DISP). The delay line is PU chained
// segments of F taps (sm_cost_srl, one SRL per census bit and lane): segment j holds
// the beats n-1-F*j .. n-F*j-F, read at tap g on sub-step g, and shifts on ce with the
// counter at F - 1, so it shifts in the oldest word of segment j - 1. Relies on sm_top's
// rules (docs/algorithm.md, "Folded datapath"): ce at most once every F clocks, and the
// inputs a ce samples stable from the clock after the previous ce. The F sub-steps of
// beat n run on the F clocks after the ce that presented it (a counter restarted by
// ce), before beat n's own ce; the popcount adds PL clocks (2, and at F >= 4 one more:
// its inputs registered, so the delay line's tap choice does not start the heap's path,
// placed and routed the block's slowest), its results are collected
// group by group (one register of PU lanes per sub-step), copied to a full-width hold
// register PL + 1 clocks after beat n's ce (when sub-step 0 of beat n + 1 overwrites the
// collect), shifted to a second hold register PL + 1 clocks after the next ce and
// presented from there on the ce after that. At F < PL + 2 that ce can come before the
// second copy; the output then takes the first hold register (the one multiplexer, small
// F only). The first copy always comes before the ce that presents it (2F > PL + 1).
module sm_cost #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter DISP      = 128,  // disparity levels 0..DISP-1
    parameter CENSUS    = 15,   // census window side (odd, 3..15)
    parameter PU        = DISP, // levels computed per clock (divides DISP; DISP: not folded)
    parameter COST_SHIFT = 2,   // the aggregation's shift of the cost: the intensity term is added at its scale
    parameter AD_SHIFT  = 2,    // intensity term: |left - right| >> AD_SHIFT ...
    parameter AD_MAX    = 7     // ... capped at AD_MAX (0: census only)
) (
    input  wire               clk,
    input  wire               rst_n,
    input  wire               ce,
    input  wire [XW-1:0]      width,   // unused: the cost needs only the row starts
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [CB-1:0]      s_cl,    // left census vector
    input  wire [CB-1:0]      s_cr,    // right census vector
    input  wire [7:0]         s_left,  // left centre pixel, passed through
    input  wire [7:0]         s_right, // right centre pixel
    output wire [`SM_SIDE_W-1:0] m_side,
    output reg  [CW*DISP-1:0] m_cost,  // C in bit-plane order: bit f of level d at [f*DISP + d]
    output reg  [7:0]         m_left
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam CB = CENSUS * CENSUS - 1;
  localparam HW = $clog2(CB + 1);
  localparam CW = $clog2((CB >> COST_SHIFT) + 1);  // C's width, HW - COST_SHIFT
  localparam F  = DISP / PU;                  // clocks per beat
  localparam GW = (F > 1) ? $clog2(F) : 1;    // sub-step counter
  localparam TW = (AD_MAX > 0) ? $clog2(AD_MAX + 1) : 1;  // intensity term

  generate
    `SM_BAD_PARAM(g_bad_census, CENSUS < `SM_CENSUS_MIN || CENSUS > `SM_CENSUS_MAX || CENSUS % 2 == 0,
                  ("sm_cost: CENSUS (%0d) must be odd, %0d..%0d", CENSUS, `SM_CENSUS_MIN, `SM_CENSUS_MAX))
    `SM_BAD_PARAM(g_bad_disp, DISP < 2 || DISP > 256, ("sm_cost: DISP (%0d) must be 2..256", DISP))
    `SM_BAD_PARAM(g_bad_pu, PU < 1 || PU > DISP || DISP % PU != 0,
                  ("sm_cost: PU (%0d) must divide DISP (%0d)", PU, DISP))
    `SM_BAD_PARAM(g_bad_ad, AD_MAX < 0 || AD_MAX > 15 || AD_SHIFT < 0 || AD_SHIFT > 7,
                  ("sm_cost: AD_MAX (%0d) must be 0..15 and AD_SHIFT (%0d) 0..7", AD_MAX, AD_SHIFT))
    `SM_BAD_PARAM(g_bad_shift, COST_SHIFT < 0 || COST_SHIFT > 7, ("sm_cost: COST_SHIFT (%0d) must be 0..7", COST_SHIFT))
  endgenerate
  wire unused_width = &width;

  // ok[d] = (x >= d) for the entering beat: all ones shifted in since the row start.
  reg  [DISP-1:0] ok_q;
  wire [DISP-1:0] ok = s_side[`SM_SIDE_SOL] ? {{(DISP - 1) {1'b0}}, 1'b1} : {ok_q[DISP-2:0], 1'b1};
  wire unused_ok_top = ok_q[DISP-1];  // shifted out (g_par reads it into okt_q)

  // Control and pass-through data along the three ce stages.
  sm_side_delay #(.DEPTH(3)) u_side (.clk(clk), .rst_n(rst_n), .ce(ce), .d(s_side), .q(m_side));
  reg [7:0] left_q2, left_q3;
  always @(posedge clk) begin
    if (!rst_n) begin
      ok_q    <= {DISP{1'b0}};
    end else if (ce) begin
      ok_q    <= ok;
    end
  end
  always @(posedge clk) begin
    if (ce) begin
      left_q2 <= s_left;
      left_q3 <= left_q2;
      m_left  <= left_q3;
    end
  end

  genvar i;
  generate
    if (F == 1) begin : g_par
      // Right vectors in bit-plane order (one plane per census bit, one bit per level):
      // cr_all[i*DISP + d] is bit i of the right vector of beat n - d, the one level d
      // compares with. Beat n itself is s_cr; the older ones come from a delay line of
      // the same order, crd_q[i*DISP + d] = bit i of beat n - 1 - d, shifted one level up
      // per ce (its top bit of every plane, beat n - DISP, is never read). Bit-plane order
      // lets the popcount below do all levels with the same long-vector operations. The
      // planes are assembled in always blocks: as CB continuous assignments, Verilator
      // 5.006 joins them into a chain of ever longer concatenations (quadratic in CB*DISP).
      reg [CB*DISP-1:0] crd_q;
      reg [CB*DISP-1:0] cr_all, cl_all;
      for (i = 0; i < CB; i = i + 1) begin : g_plane
        always @* begin
          cr_all[i*DISP +: DISP] = {crd_q[i*DISP +: DISP-1], s_cr[i]};
          cl_all[i*DISP +: DISP] = {DISP{s_cl[i]}};  // the left vector, every level
        end
        wire unused_crd_top = crd_q[i*DISP + DISP - 1];  // beat n - DISP
      end
      always @(posedge clk) if (ce) crd_q <= cr_all;

      // Popcount of every level (one compressor tree per level), latency 2.
      wire [HW*DISP-1:0] pc;  // bit-plane order: bit f of level d at [f*DISP + d]
      sm_popcount #(.N(CB), .L(DISP)) u_pc (.clk(clk), .ce(ce), .a(cl_all), .b(cr_all), .cnt(pc));

      // Right pixels in level order: after the ce of beat n, rpx_q[8*d +: 8] is the
      // pixel of beat n - d, level d's; with the left pixel of that ce (left_q2) they give
      // the intensity terms, registered on the next ce beside the popcount result.
      reg  [8*DISP-1:0]  rpx_q;
      reg  [TW*DISP-1:0] t_q;  // bit-plane order
      reg  [DISP-1:0]    okt_q;  // the thermometer of t_q's beat
      wire [TW*DISP-1:0] t_c;
      always @(posedge clk) if (ce) rpx_q <= {rpx_q[8*(DISP-1)-1:0], s_right};
      if (AD_MAX > 0) begin : g_ad
        sm_ad_term #(.L(DISP), .AD_SHIFT(AD_SHIFT), .AD_MAX(AD_MAX)) u_ad (.a(left_q2), .b(rpx_q), .t(t_c));
      end else begin : g_no_ad
        assign t_c = {TW*DISP{1'b0}};
        wire unused_rpx = ^rpx_q;
      end
      always @(posedge clk) begin
        if (ce) begin
          t_q   <= t_c;
          okt_q <= ok_q;
        end
      end

      // Output costs: the count plus the term, capped at CB, and CB where x - d < 0. They
      // stay in bit-plane order, the order sm_sw_aggregate sums them in: a transpose to
      // level order and back would be wiring in hardware but two thousand bit moves a
      // clock in Verilator. ok_q is the beat's thermometer while t_c is formed, so one
      // register beside t_q carries it on.
      wire [CW*DISP-1:0] cost_p;  // bit-plane order
      sm_cost_addsat #(.L(DISP), .HW(HW), .TW(TW), .COST_SHIFT(COST_SHIFT), .CB(CB)) u_sum (
          .h(pc), .t(t_q), .ok(okt_q), .cost(cost_p));
      always @(posedge clk) if (ce) m_cost <= cost_p;
    end else begin : g_fold
      /* verilator lint_off WIDTH */
      localparam [GW-1:0] G_LAST = F - 1;
      /* verilator lint_on WIDTH */

      // Sub-step counter: 0..F-1 on the F clocks after a ce, then held at F - 1 until the
      // next ce, so every ce (F or more clocks later) finds the segments at their last tap.
      // The reset counts as a ce: the first beat after it is computed on the F clocks
      // after the reset (a ce sooner gets a wrong first beat, which in sm_top is the
      // reset value of the stage before, a virtual beat).
      reg [GW-1:0] sub_q;
      always @(posedge clk) begin
        if (!rst_n || ce) sub_q <= {GW{1'b0}};
        else if (sub_q != G_LAST) sub_q <= sub_q + 1'b1;
      end
`ifndef SYNTHESIS
      reg seen_ce_q;  // a ce since the reset: the pacing rule applies
      always @(posedge clk) begin
        if (!rst_n) seen_ce_q <= 1'b0;
        else if (ce) seen_ce_q <= 1'b1;
        if (rst_n && ce && seen_ce_q && sub_q != G_LAST)
          $error("sm_cost: ce %0d clocks after the previous one, PU %0d needs %0d", sub_q + 1, PU, F);
      end
`endif
      // sub_q == F - 1, from a flip-flop: it selects level 0's input in front of the
      // popcount leaves, on the longest path.
      reg last;
      always @(posedge clk) begin
        if (!rst_n || ce) last <= 1'b0;
        else if (sub_q == G_LAST - 1'b1) last <= 1'b1;
      end

      // Popcount pipeline: PB_REG registers the lanes' vectors in front of it (PL clocks
      // from the sub-step to the count). At F = 2 the extra clock would bring the hold
      // copy onto the ce that presents it.
      localparam PB_REG = (F >= 4) ? 1 : 0;
      localparam PL = 2 + PB_REG;

      // The delay line in bit-plane order: seg_q[i*PU + j] = bit i of segment j's tap
      // sub_q, beat n - 1 - F*j - sub_q.
      wire [CB*PU-1:0] seg_q;
      reg  [CB*PU-1:0] pb;  // right vectors, bit-plane order (bit i of lane j at [i*PU + j])
      genvar j, g;
      for (i = 0; i < CB; i = i + 1) begin : g_plane
        sm_cost_srl #(.L(PU), .DEPTH(F)) u_srl (
            .clk(clk), .shift(ce), .addr(sub_q), .d(s_cr[i]), .q(seg_q[i*PU +: PU]));
        // Lane PU-1's last sub-step is level 0, beat n itself (its segment's last tap,
        // beat n - DISP, is never compared).
        always @* begin
          pb[i*PU +: PU] = seg_q[i*PU +: PU];
          if (last) pb[i*PU + PU - 1] = s_cr[i];
        end
      end

      // The right pixels in the same chained segments, one per pixel bit, gathered to
      // level order per lane and registered with the left pixel (which changes after the
      // beat's ce, possibly before its last sub-step's term); the terms are registered
      // PL - 1 times more, so they meet the popcount result PL clocks after its inputs.
      wire [8*PU-1:0]  pseg_q;  // bit-plane order
      reg  [8*PU-1:0]  px_p1;   // level order: lane j at [8*j +: 8]
      reg  [7:0]       left_p1;
      reg  [TW*PU-1:0] t_p2;    // bit-plane order
      wire [TW*PU-1:0] t_c;
      for (i = 0; i < 8; i = i + 1) begin : g_pix_plane
        sm_cost_srl #(.L(PU), .DEPTH(F)) u_srl (
            .clk(clk), .shift(ce), .addr(sub_q), .d(s_right[i]), .q(pseg_q[i*PU +: PU]));
        for (j = 0; j < PU; j = j + 1) begin : g_lane
          wire b = (last && j == PU - 1) ? s_right[i] : pseg_q[i*PU + j];
          always @(posedge clk) px_p1[8*j + i] <= b;
        end
      end
      always @(posedge clk) left_p1 <= s_left;
      if (AD_MAX > 0) begin : g_ad
        sm_ad_term #(.L(PU), .AD_SHIFT(AD_SHIFT), .AD_MAX(AD_MAX)) u_ad (.a(left_p1), .b(px_p1), .t(t_c));
      end else begin : g_no_ad
        assign t_c = {TW*PU{1'b0}};
        wire unused_px = ^{px_p1, left_p1};
      end
      always @(posedge clk) t_p2 <= t_c;
      wire [TW*PU-1:0] t_pl;  // the terms PL clocks after the sub-step
      if (PB_REG != 0) begin : g_t_reg
        reg [TW*PU-1:0] t_p3;
        always @(posedge clk) t_p3 <= t_p2;
        assign t_pl = t_p3;
      end else begin : g_t_direct
        assign t_pl = t_p2;
      end

      // x - d >= 0 of each lane's level at this sub-step (ok[0] = 1 covers level 0).
      wire [PU-1:0] ok_l;
      for (j = 0; j < PU; j = j + 1) begin : g_okl
        wire [F-1:0] oks;
        for (g = 0; g < F; g = g + 1) begin : g_sub
          assign oks[g] = ok[(j == PU - 1 && g == F - 1) ? 0 : F * j + g + 1];
        end
        assign ok_l[j] = oks[sub_q];
      end

      // PU popcounts every clock, latency 2 (PL with the input register); the sub-step
      // and ok bits follow them. The left vector is registered beside the right ones:
      // the input changes on the clock after a ce, while the last sub-step's vectors are
      // still in the register (one CB-bit register, copied to the lanes after it).
      wire [CB*PU-1:0] pa_pc, pb_pc;
      wire [CB-1:0]    cl_pc;  // the left vector the popcount compares
      if (PB_REG != 0) begin : g_pb_reg
        reg [CB*PU-1:0] pb_q;
        reg [CB-1:0]    cl_q;
        always @(posedge clk) begin
          pb_q <= pb;
          cl_q <= s_cl;
        end
        assign pb_pc = pb_q;
        assign cl_pc = cl_q;
      end else begin : g_pb_direct
        assign pb_pc = pb;
        assign cl_pc = s_cl;
      end
      for (i = 0; i < CB; i = i + 1) begin : g_pa  // the lanes' copies of the left vector
        assign pa_pc[i*PU +: PU] = {PU{cl_pc[i]}};
      end
      wire [HW*PU-1:0] pc;  // bit-plane order: bit f of lane j at [f*PU + j]
      sm_popcount #(.N(CB), .L(PU)) u_pc (.clk(clk), .ce(1'b1), .a(pa_pc), .b(pb_pc), .cnt(pc));
      reg [PU-1:0] ok_p [1:PL];
      reg [GW-1:0] sub_p [1:PL];
      always @(posedge clk) begin : a_pipe
        integer s;
        ok_p[1]  <= ok_l;
        sub_p[1] <= sub_q;
        for (s = 2; s <= PL; s = s + 1) begin
          ok_p[s]  <= ok_p[s-1];
          sub_p[s] <= sub_p[s-1];
        end
      end
      wire [CW*PU-1:0] cost_l;  // bit-plane order
      sm_cost_addsat #(.L(PU), .HW(HW), .TW(TW), .COST_SHIFT(COST_SHIFT), .CB(CB)) u_sum (
          .h(pc), .t(t_pl), .ok(ok_p[PL]), .cost(cost_l));

      // Collect: sub-step g's lanes at [g*CW*PU +: CW*PU]. Sub-steps repeated while the
      // counter waits at F - 1 rewrite the same values.
      localparam GB = CW * PU;
      reg [F*GB-1:0] col_q;
      always @(posedge clk) begin : a_col
        integer s;
        for (s = 0; s < F; s = s + 1)
          if (sub_p[PL] == s[GW-1:0]) col_q[s*GB +: GB] <= cost_l;
      end

      // ce PL + 1 clocks ago: sub-step 0 of the next beat reaches the collect now, so
      // the collect holds the whole previous beat for the last time.
      reg [PL:0] ce_p;
      always @(posedge clk) begin
        if (!rst_n) ce_p <= {(PL + 1){1'b0}};
        else ce_p <= {ce_p[PL-1:0], ce};
      end
      // The hold registers in the output's bit-plane order (fixed wiring from the collect:
      // level d = F*j + g + 1 of sub-step g, lane j; level 0 of sub-step F-1, lane PU-1).
      reg [CW*DISP-1:0] hold_q, hold2_q;
      always @(posedge clk) begin : a_hold
        integer d, b, s, l;
        if (ce_p[PL]) begin
          for (d = 0; d < DISP; d = d + 1) begin
            s = (d == 0) ? F - 1 : (d - 1) % F;
            l = (d == 0) ? PU - 1 : (d - 1) / F;
            for (b = 0; b < CW; b = b + 1) hold_q[b*DISP + d] <= col_q[s*GB + b*PU + l];
          end
          hold2_q <= hold_q;
        end
      end
      if (F < PL + 2) begin : g_early
        // A ce within PL + 1 clocks of the previous one comes before that one's hold copy.
        always @(posedge clk) if (ce) m_cost <= (|ce_p) ? hold_q : hold2_q;
      end else begin : g_late
        always @(posedge clk) if (ce) m_cost <= hold2_q;
      end
    end
  endgenerate
endmodule
`default_nettype wire
