`default_nettype none
`include "sm_defs.vh"
// Winner-take-all record of one pixel (docs/algorithm.md section 9.0; model wta_row and
// wta_band, model/evidence.hpp) from its aggregated costs A(k) = s_cost[k*CW +: CW]:
//   dw   the lowest k of least A(k)             c1 = A(dw)        cmax = greatest A(k)
//   c2   least A(k) over |k - dw| >= 2 (at DISP >= 4 every dw has such a level, so the
//        model's "c1 when there is none" never applies)
//   band[j] = A(dw - 2 + j), j = 0..4, 0 outside 0..DISP-1
//
// One min tree computes all of it, so no second tree waits for dw and no 128:1 band
// select follows it. A tree node covers a range [lo, hi] of levels and holds
//   m, i  least cost of the range and its lowest level (ties go to the left child)
//   fl/la i == lo / i == hi
//   e     least cost over the range's k with |k - i| >= 2 (all ones when none)
//   xf/xl least cost of the range without its first / last level (all ones when none)
//   M     greatest cost;  band  A(i - 2 .. i + 2) (a leaf's own five neighbours)
// Merging the adjacent ranges L (left) and R: R wins when R.m < L.m. The levels of the
// other child that sit next to the winner are L.hi and R.lo only, so
//   L wins: e = min(L.e, L.la ? R.xf : R.m)     R wins: e = min(R.e, R.fl ? L.xl : L.m)
//   xf = min(L.xf, R.m), xl = min(L.m, R.xl), M = max(L.M, R.M)
// and the root's (i, m, e, M, band) is (dw, c1, c2, cmax, band). A merge is about 3 LUT
// levels (Yosys xc7, CW 6), so a register stage holds two tree levels: the even levels
// and the root are registered (NS = ceil(clog2(leaves) / 2) stages). The band:
// - PU = DISP: no tree node holds it. The costs wait NS ce's beside the tree in a shift
//   register without reset (SRLs: a LUT per cost bit instead of a 5*CW-bit register in
//   each registered node, about 1,300 flip-flops at DISP 128), and a select tree on the
//   root's level takes the five costs from there, after the root's registers.
// - PU < DISP: the accumulator merges the groups' bands, so the registered nodes hold
//   theirs, taken not through the merges' band selects (a 2:1 select per merge, each on
//   its own compare: 5*CW LUT3s per merge) but from the winner's descendant at the
//   registered level below (or from the leaves): a 4:1 select (2:1 at an odd root) on
//   two bits of the winner's level, a LUT6 per bit.
//
// Latency: the record of the beat that ce b samples is on m_* from ce b + LATENCY - 1
// on (m_side is s_side through sm_side_delay of DEPTH LATENCY).
// PU = DISP: the tree has DISP leaves (odd counts pass their last node through), its
// stages are registered on ce, the root registers are the outputs.
//   LATENCY = NS = ceil(clog2(DISP) / 2)  (DISP 128: 4; DISP 16, 10, 12: 2; DISP 4: 1)
// PU < DISP (an even divisor, F = DISP/PU clocks per beat; the input-stability rule
// of docs/algorithm.md "Folded datapath"): the same tree over PU leaves, its stages
// registered on every clock, takes level group g = levels [g*PU, g*PU + PU) of the held
// beat on the (g+1)-th clock after a ce (reset counts as a ce), through a window
// register of the group's PU + 4 costs (its leaves' bands reach two levels into the
// neighbours); an accumulator merges the groups' roots in level order with the same
// merge (the accumulated range is always left of the group). Group g is merged D - 1
// clocks after it is issued (D = NS + 2: window, NS tree stages, accumulator), so the
// beat that ce b samples (issued on the F clocks after ce b-1, the last on ce b at the
// latest) is complete in the accumulator D - 1 clocks after ce b at the latest, and the
// D-th clock after ce b brings the next beat's group 0: that edge copies it into slot
// (b mod N) of an N-slot ring. The ce N = floor(D / F) + 1 beats later (at least
// N*F > D clocks on) moves the slot into the output registers; the slot's next write
// comes D clocks after that ce.
//   LATENCY = N + 1 = floor(D / F) + 2  (DISP 128 at PU 16, 8: 2; DISP 16 at PU 8: 4,
//   PU 4: 2, PU 2: 2; DISP 10 PU 2: 2; DISP 12 PU 6: 4; DISP 4 PU 2: 3)
// As in sm_dp, the first beat's groups start at reset, so its ce must come at least F
// clocks after rst_n rises.
module sm_wta #(
    parameter DISP = 128,  // disparity levels 0..DISP-1 (even, 4..254)
    parameter CW   = 6,    // aggregated cost width
    // Levels compared per clock: DISP (one beat per clock) or an even divisor of DISP
    // (F = DISP/PU clocks per beat, ce at most every F clocks, input held between ces).
    parameter PU   = DISP
) (
    input  wire                  clk,
    input  wire                  rst_n,
    input  wire                  ce,
    input  wire [`SM_SIDE_W-1:0] s_side,
    input  wire [DISP*CW-1:0]    s_cost,  // A(k) at [k*CW +: CW]
    output wire [`SM_SIDE_W-1:0] m_side,
    output wire [DW-1:0]         m_dw,    // lowest level of least cost
    output wire [CW-1:0]         m_c1,    // A(dw)
    output wire [CW-1:0]         m_c2,    // least A(k) over |k - dw| >= 2
    output wire [CW-1:0]         m_cmax,  // greatest A(k)
    output wire [5*CW-1:0]       m_band   // A(dw - 2 + j) at [j*CW +: CW], 0 outside
);
  localparam DW = $clog2(DISP);
  localparam F = (PU > 0) ? DISP / PU : 1;  // clocks per beat
  localparam N0 = (F > 1) ? PU : DISP;      // leaves of the tree
  localparam NL = $clog2(N0);               // tree levels
  localparam NS = (NL + 1) / 2;             // register stages of the tree
  localparam D = NS + 2;                    // folded: clocks from issue to accumulator
  localparam NR = (F > 1) ? D / F + 1 : 1;  // folded: ring slots
  // ce's from s_cost sampled to m_*, counting the sampling ce (sm_side_delay's DEPTH)
  localparam LATENCY = (F > 1) ? NR + 1 : NS;

  generate
    `SM_BAD_PARAM(g_bad_disp, DISP < `SM_DISP_MIN || DISP > `SM_DISP_MAX || DISP % 2 != 0,
                  ("sm_wta: DISP (%0d) must be even, %0d..%0d", DISP, `SM_DISP_MIN, `SM_DISP_MAX))
    `SM_BAD_PARAM(g_bad_cw, CW < 1 || CW > 8, ("sm_wta: CW (%0d) must be 1..8", CW))
    `SM_BAD_PARAM(g_bad_pu, PU < 2 || PU > DISP || DISP % PU != 0 || PU % 2 != 0,
                  ("sm_wta: PU (%0d) must be an even divisor of DISP (%0d)", PU, DISP))
    `SM_BAD_PARAM(g_bad_lat, LATENCY > 64, ("sm_wta: LATENCY (%0d) above sm_side_delay's 64", LATENCY))
  endgenerate

  // ---- tree node layout ----------------------------------------------------------
  localparam O_M = 0;              // least cost
  localparam O_I = O_M + CW;       // its lowest level (leaf: local level in the tree)
  localparam O_FL = O_I + DW;      // i is the range's first level
  localparam O_LA = O_FL + 1;      // i is the range's last level
  localparam O_E = O_LA + 1;       // least cost at distance >= 2 from i
  localparam O_XF = O_E + CW;      // least cost without the first level
  localparam O_XL = O_XF + CW;     // least cost without the last level
  localparam O_MX = O_XL + CW;     // greatest cost
  localparam O_B = O_MX + CW;      // band A(i - 2 .. i + 2)
  localparam NW = O_B + 5 * CW;
  localparam [CW-1:0] ALL1 = {CW{1'b1}};

  function [CW-1:0] min2;
    input [CW-1:0] a, b;
    min2 = (b < a) ? b : a;
  endfunction

  // The node of the adjacent ranges l (left) and r (right).
  function [NW-1:0] merge;
    input [NW-1:0] l, r;
    reg rw;  // r wins: strictly less (ties keep the lower level)
    reg [CW-1:0] el, er;
    begin
      rw = r[O_M +: CW] < l[O_M +: CW];
      el = min2(l[O_E +: CW], l[O_LA] ? r[O_XF +: CW] : r[O_M +: CW]);
      er = min2(r[O_E +: CW], r[O_FL] ? l[O_XL +: CW] : l[O_M +: CW]);
      merge[O_M +: CW] = rw ? r[O_M +: CW] : l[O_M +: CW];
      merge[O_I +: DW] = rw ? r[O_I +: DW] : l[O_I +: DW];
      merge[O_FL] = ~rw & l[O_FL];
      merge[O_LA] = rw & r[O_LA];
      merge[O_E +: CW] = rw ? er : el;
      merge[O_XF +: CW] = min2(l[O_XF +: CW], r[O_M +: CW]);
      merge[O_XL +: CW] = min2(l[O_M +: CW], r[O_XL +: CW]);
      merge[O_MX +: CW] = (r[O_MX +: CW] > l[O_MX +: CW]) ? r[O_MX +: CW] : l[O_MX +: CW];
      // (used by the folded accumulator; a registered tree node selects its own band)
      merge[O_B +: 5*CW] = rw ? r[O_B +: 5*CW] : l[O_B +: 5*CW];
    end
  endfunction

  // A(i - 2 .. i + 2) from pad = {0, 0, A(0..DISP-1), 0, 0}: a binary select tree on i,
  // low bit first (pairs of candidates folded in place; Yosys makes an indexed
  // part-select of pad a barrel shifter over every bit of it).
  localparam NV = 1 << DW;
  function [5*CW-1:0] band_at;
    input [(DISP+4)*CW-1:0] pad;
    input [DW-1:0] i;
    reg [NV*5*CW-1:0] v;  // candidate n at [n*5*CW +: 5*CW]
    integer n, b;
    begin
      v = {(NV * 5 * CW) {1'b0}};
      for (n = 0; n < DISP; n = n + 1) v[n*5*CW +: 5*CW] = pad[n*CW +: 5*CW];
      for (b = 0; b < DW; b = b + 1)
        for (n = 0; n < (NV >> (b + 1)); n = n + 1)
          v[n*5*CW +: 5*CW] = i[b] ? v[(2*n+1)*5*CW +: 5*CW] : v[(2*n)*5*CW +: 5*CW];
      band_at = v[0 +: 5*CW];
    end
  endfunction

  // Nodes of tree level l (level 0: the leaves) and the first node of level l in the
  // flat vector of levels 1..NL.
  function integer lvl_n;
    input integer l;
    lvl_n = (N0 + (1 << l) - 1) >> l;
  endfunction
  function integer lvl_base;
    input integer l;
    integer k;
    begin
      lvl_base = 0;
      for (k = 1; k < l; k = k + 1) lvl_base = lvl_base + lvl_n(k);
    end
  endfunction
  localparam TOT = lvl_base(NL + 1);

  // ---- leaves: the costs of the N0 levels in view, with two neighbours on each side --
  // win[j*CW +: CW] = A(base + j - 2), j = 0..N0+3 (base = 0, or g*PU when folded).
  wire [(N0+4)*CW-1:0] win;
  wire [N0*NW-1:0] leaf;
  genvar j, l, t;
  generate
    for (j = 0; j < N0; j = j + 1) begin : g_leaf
      /* verilator lint_off WIDTH */  // the level number, truncated to DW bits
      localparam [DW-1:0] IDX = j;
      /* verilator lint_on WIDTH */
      assign leaf[j*NW +: NW] = {win[j*CW +: 5*CW], win[(j+2)*CW +: CW], ALL1, ALL1, ALL1, 2'b11, IDX, win[(j+2)*CW +: CW]};
    end
  endgenerate

  // ---- the tree: level l node n from level l-1 nodes 2n, 2n+1 -------------------------
  // Registered: the even levels and the root (two merges, about 6 LUT levels, per stage).
  // A registered node takes its band not through the merges' band selects (two 2:1
  // selects per level, each on its own compare) but from its winner's descendant at the
  // registered level below (or the leaves): one 4:1 (2:1 at an odd root) select on the
  // winner's level bits, a LUT6 per bit. The unregistered level's band is then unused.
  wire          tree_en = (F > 1) ? 1'b1 : ce;  // folded: every clock
  // Every node of levels 1..NL as the level above reads it, in two vectors so that no
  // signal is both read and driven by the combinational part of the tree: tr the
  // registered nodes (a flip-flop each), tc the others (the other vector's segment 0).
  wire [TOT*NW-1:0] tr, tc;
  generate
    for (l = 1; l <= NL; l = l + 1) begin : g_lvl
      for (j = 0; j < lvl_n(l); j = j + 1) begin : g_node
        localparam OUT = (lvl_base(l) + j) * NW;
        wire [NW-1:0] a, b, mg;
        if (l == 1) begin : g_from_leaf
          assign a = leaf[(2*j)*NW +: NW];
          if (2 * j + 1 < N0) begin : g_b
            assign b = leaf[(2*j+1)*NW +: NW];
          end else begin : g_nob
            assign b = a;
          end
        end else begin : g_from_lvl
          // level l-1 is registered when even (the root is the top level)
          wire [TOT*NW-1:0] src = ((l - 1) % 2 == 0) ? tr : tc;
          assign a = src[(lvl_base(l - 1) + 2 * j) * NW +: NW];
          if (2 * j + 1 < lvl_n(l - 1)) begin : g_b
            assign b = src[(lvl_base(l - 1) + 2 * j + 1) * NW +: NW];
          end else begin : g_nob
            assign b = a;
          end
        end
        if (2 * j + 1 < lvl_n(l - 1)) begin : g_merge
          assign mg = merge(a, b);
        end else begin : g_pass  // odd count: the last node passes through
          assign mg = a;
          wire unused_b = ^b;
        end
        if (l % 2 == 0 || l == NL) begin : g_reg
          localparam LP = (l % 2 == 0) ? l - 2 : l - 1;  // registered level below (0: leaves)
          localparam NT = 1 << (l - LP);                 // descendants there: 4 or 2
          wire [NT*5*CW-1:0] cand;                       // their bands
          for (t = 0; t < NT; t = t + 1) begin : g_cand
            if (j * NT + t >= lvl_n(LP)) begin : g_none  // past an odd count: never wins
              assign cand[t*5*CW +: 5*CW] = {(5 * CW) {1'b0}};
            end else if (LP == 0) begin : g_leaf
              assign cand[t*5*CW +: 5*CW] = win[(j*NT+t)*CW +: 5*CW];
            end else begin : g_node
              assign cand[t*5*CW +: 5*CW] = tr[(lvl_base(LP) + j * NT + t) * NW + O_B +: 5 * CW];
            end
          end
          wire [5*CW-1:0] bs;
          if (NT == 2) begin : g_sel2
            assign bs = mg[O_I+LP] ? cand[5*CW +: 5*CW] : cand[0 +: 5*CW];
          end else begin : g_sel4
            wire [1:0] w = mg[O_I+LP +: 2];
            assign bs = w[1] ? (w[0] ? cand[15*CW +: 5*CW] : cand[10*CW +: 5*CW])
                             : (w[0] ? cand[5*CW +: 5*CW] : cand[0 +: 5*CW]);
          end
          wire unused_mb = ^mg[O_B +: 5*CW];
          reg [O_B-1:0] q;
          always @(posedge clk) begin
            if (tree_en) q <= mg[O_B-1:0];
          end
          if (F > 1) begin : g_band  // folded: the accumulator merges the groups' bands
            reg [5*CW-1:0] b_q;
            always @(posedge clk) begin
              b_q <= bs;
            end
            assign tr[OUT +: NW] = {b_q, q};
          end else begin : g_noband  // one beat per clock: the band is taken at the root
            wire unused_bs = ^bs;
            assign tr[OUT +: NW] = {{(5 * CW) {1'b0}}, q};
          end
          assign tc[OUT +: NW] = {NW{1'b0}};
          wire unused_tc = ^tc[OUT +: NW];
        end else begin : g_comb
          assign tc[OUT +: NW] = mg;
          assign tr[OUT +: NW] = {NW{1'b0}};
          wire unused_tr = ^tr[OUT +: NW];
        end
      end
    end
  endgenerate
  wire [NW-1:0] root = tr[(TOT-1)*NW +: NW];

  // Record: {band, cmax, c2, c1, dw}
  localparam RW = 8 * CW + DW;
  wire [RW-1:0] rec;  // the output registers' value
  assign {m_band, m_cmax, m_c2, m_c1, m_dw} = rec;

  generate
    if (F == 1) begin : g_par
      // ---- one beat per clock: the leaves read s_cost, the root is the output --------
      assign win = {{2*CW{1'b0}}, s_cost, {2*CW{1'b0}}};
      // The band is not carried through the tree (a 5*CW register in each of its
      // registered nodes): the costs wait NS ce's beside the tree, a shift register
      // without reset (SRLs, LUTs instead of flip-flops), and the root's level selects
      // its five neighbours there, after the output registers.
      reg [NS*DISP*CW-1:0] cd_q;  // stage s at [s*DISP*CW +: DISP*CW], s = 0 the newest
      if (NS > 1) begin : g_cd_shift
        always @(posedge clk) begin
          if (ce) cd_q <= {cd_q[0 +: (NS-1)*DISP*CW], s_cost};
        end
      end else begin : g_cd_one
        always @(posedge clk) begin
          if (ce) cd_q <= s_cost;
        end
      end
      wire [(DISP+4)*CW-1:0] pad = {{2*CW{1'b0}}, cd_q[(NS-1)*DISP*CW +: DISP*CW], {2*CW{1'b0}}};
      wire [5*CW-1:0] band = band_at(pad, root[O_I +: DW]);
      assign rec = {band, root[O_MX +: CW], root[O_E +: CW], root[O_M +: CW], root[O_I +: DW]};
      wire unused_root = ^{root[O_FL], root[O_LA], root[O_XF +: CW], root[O_XL +: CW], root[O_B +: 5*CW], rst_n};
    end else begin : g_fold
      // ---- folded: group g of the held beat on the g-th clock after a ce ---------------
      localparam GW = $clog2(F);
      localparam AW = (NR > 1) ? $clog2(NR) : 1;
      /* verilator lint_off WIDTH */  // constants truncated to the counter widths
      localparam [DW-1:0] PU_C = PU;
      localparam [AW-1:0] A_LAST = NR - 1;
      /* verilator lint_on WIDTH */

      // Sub-step counter: run_q = group g_q is issued on this clock edge; gb_q = g_q*PU
      // is counted beside it.
      wire [GW-1:0] g_q;
      wire          run_q, fs_start, fs_step;
      sm_fold_step #(.F(F)) u_step (
          .clk(clk), .rst_n(rst_n), .ce(ce), .m_start(fs_start), .m_step(fs_step), .m_run(run_q), .m_g(g_q)
      );
      reg [DW-1:0] gb_q;
      always @(posedge clk) begin
        if (fs_start) gb_q <= {DW{1'b0}};
        else if (fs_step) gb_q <= gb_q + PU_C;
      end

      // Window register: the group's PU costs and two levels either side (zeros past
      // the ends), one F:1 selection from the held beat.
      // (An AND-OR over the groups: Yosys made the indexed part-select pad[g*PU*CW +: ..]
      // a barrel shifter over every bit of pad.)
      wire [(DISP+4)*CW-1:0] pad = {{2*CW{1'b0}}, s_cost, {2*CW{1'b0}}};
      reg  [(N0+4)*CW-1:0] win_nx;
      reg  [(N0+4)*CW-1:0] win_q;
      integer gi;
      always @* begin
        win_nx = {((N0 + 4) * CW) {1'b0}};
        for (gi = 0; gi < F; gi = gi + 1)
          win_nx = win_nx | ({((N0 + 4) * CW) {g_q == gi[GW-1:0]}} & pad[gi*(PU*CW) +: (PU+4)*CW]);
      end
      always @(posedge clk) begin
        win_q <= win_nx;
      end
      assign win = win_q;

      // Beside the window and every tree level: issued (control, reset), first group,
      // the group's first level. Stage s = 0 (window) .. NS (root).
      reg [NS:0]          tv_q;
      reg [NS:0]          tf_q;
      reg [(NS+1)*DW-1:0] tb_q;
      always @(posedge clk) begin
        if (!rst_n) tv_q <= {(NS + 1) {1'b0}};
        else tv_q <= {tv_q[NS-1:0], run_q};
        tf_q <= {tf_q[NS-1:0], g_q == {GW{1'b0}}};
        tb_q <= {tb_q[NS*DW-1:0], gb_q};
      end

      // Accumulator: the groups so far, the root's local level made global.
      wire [NW-1:0] grp = {root[NW-1:O_I+DW], root[O_I +: DW] + tb_q[NS*DW +: DW], root[O_M +: CW]};
      reg  [NW-1:0] acc_q;
      always @(posedge clk) begin
        if (tv_q[NS]) acc_q <= tf_q[NS] ? grp : merge(acc_q, grp);
      end
      wire unused_acc = ^{acc_q[O_FL], acc_q[O_LA], acc_q[O_XF +: CW], acc_q[O_XL +: CW]};

      // The ce's slot travels D clocks beside the beat's last groups; on the D-th clock
      // after the ce the accumulator holds that beat complete and is copied to the slot.
      reg [AW-1:0]   wc_q;  // slot of the beat the next ce samples = slot the ce reads
      reg [D-1:0]    cv_q;
      reg [D*AW-1:0] ca_q;
      always @(posedge clk) begin
        if (!rst_n) begin
          wc_q <= {AW{1'b0}};
          cv_q <= {D{1'b0}};
          ca_q <= {(D * AW) {1'b0}};
        end else begin
          if (ce) wc_q <= (wc_q == A_LAST) ? {AW{1'b0}} : wc_q + 1'b1;
          cv_q <= {cv_q[D-2:0], ce};
          ca_q <= {ca_q[(D-1)*AW-1:0], wc_q};
        end
      end
      reg [NR*RW-1:0] ring_q;
      reg [RW-1:0]    out_q;
      always @(posedge clk) begin
        if (cv_q[D-1])
          ring_q[ca_q[(D-1)*AW +: AW]*RW +: RW] <=
              {acc_q[O_B +: 5*CW], acc_q[O_MX +: CW], acc_q[O_E +: CW], acc_q[O_M +: CW], acc_q[O_I +: DW]};
        if (ce) out_q <= ring_q[wc_q*RW +: RW];
      end
      assign rec = out_q;
    end
  endgenerate

  sm_side_delay #(
      .DEPTH(LATENCY)
  ) u_side (
      .clk  (clk),
      .rst_n(rst_n),
      .ce   (ce),
      .d    (s_side),
      .q    (m_side)
  );
endmodule
`default_nettype wire
