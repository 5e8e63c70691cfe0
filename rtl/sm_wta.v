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
//   M     greatest cost
// Merging the adjacent ranges L (left) and R: R wins when R.m < L.m. The levels of the
// other child that sit next to the winner are L.hi and R.lo only, so
//   L wins: e = min(L.e, L.la ? R.xf : R.m)     R wins: e = min(R.e, R.fl ? L.xl : L.m)
//   xf = min(L.xf, R.m), xl = min(L.m, R.xl), M = max(L.M, R.M)
// and the root's (i, m, e, M) is (dw, c1, c2, cmax). A node holds i relative to lo (l
// bits at tree level l: lo is fixed by the node's place) and a level-1 node has no e,
// so no node bit is constant by construction (a constant bit is free in the netlist but
// a toggle point that no stimulus can cover). A merge is about 3 LUT levels (Yosys xc7,
// CW 6), so a register stage holds two tree levels: the even levels and the root are
// registered (NS = ceil(clog2(leaves) / 2) stages). The band:
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
  // A node of tree level l >= 2 holds the fields below and, above them at [NB +: l], i as
  // the level within its range: the higher bits of the level are the node's place in the
  // tree, and a node keeps no bit that its subtree cannot set. A level-1 node (two
  // leaves) has no e (a range of two has no level two away): layout P_* below. A leaf is
  // its cost alone.
  localparam O_M = 0;              // least cost
  localparam O_FL = O_M + CW;      // i is the range's first level
  localparam O_LA = O_FL + 1;      // i is the range's last level
  localparam O_E = O_LA + 1;       // least cost at distance >= 2 from i
  localparam O_XF = O_E + CW;      // least cost without the first level
  localparam O_XL = O_XF + CW;     // least cost without the last level
  localparam O_MX = O_XL + CW;     // greatest cost
  localparam NB = O_MX + CW;       // the fields; i above them
  localparam P_XF = O_LA + 1;      // level-1 node: m, fl, la as above, then xf,
  localparam P_XL = P_XF + CW;     //   xl,
  localparam P_MX = P_XL + CW;     //   greatest cost,
  localparam P_I = P_MX + CW;      //   i (one bit)
  localparam NP = P_I + 1;
  localparam [CW-1:0] ALL1 = {CW{1'b1}};

  function [CW-1:0] min2;
    input [CW-1:0] a, b;
    min2 = (b < a) ? b : a;
  endfunction
  function [CW-1:0] max2;
    input [CW-1:0] a, b;
    max2 = (b > a) ? b : a;
  endfunction

  // The level-1 node of the leaves of costs lc (left) and rc: the general merge below of
  // two leaves (m = M = the cost, fl = la = 1, e = xf = xl = none).
  function [NP-1:0] pair;
    input [CW-1:0] lc, rc;
    reg rw;
    begin
      rw = rc < lc;
      pair = {rw, max2(lc, rc), lc, rc, rw, ~rw, rw ? rc : lc};
    end
  endfunction

  // A level-1 node's fields in the general layout (e: none).
  function [NB-1:0] unpair;
    input [NP-1:0] p;
    unpair = {p[P_MX +: CW], p[P_XL +: CW], p[P_XF +: CW], ALL1, p[O_LA], p[O_FL], p[O_M +: CW]};
  endfunction

  // The fields of the adjacent ranges l (left) and r merged, and above them (bit NB)
  // whether r wins: strictly less, ties keep the lower level.
  function [NB:0] merge;
    input [NB-1:0] l, r;
    reg rw;
    reg [CW-1:0] el, er;
    begin
      rw = r[O_M +: CW] < l[O_M +: CW];
      el = min2(l[O_E +: CW], l[O_LA] ? r[O_XF +: CW] : r[O_M +: CW]);
      er = min2(r[O_E +: CW], r[O_FL] ? l[O_XL +: CW] : l[O_M +: CW]);
      merge[NB] = rw;
      merge[O_M +: CW] = rw ? r[O_M +: CW] : l[O_M +: CW];
      merge[O_FL] = ~rw & l[O_FL];
      merge[O_LA] = rw & r[O_LA];
      merge[O_E +: CW] = rw ? er : el;
      merge[O_XF +: CW] = min2(l[O_XF +: CW], r[O_M +: CW]);
      merge[O_XL +: CW] = min2(l[O_M +: CW], r[O_XL +: CW]);
      merge[O_MX +: CW] = max2(l[O_MX +: CW], r[O_MX +: CW]);
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

  // Nodes of tree level l (level 0: the leaves); registered levels: the even ones and
  // the root (two merges, about 6 LUT levels, per stage).
  function integer lvl_n;
    input integer l;
    lvl_n = (N0 + (1 << l) - 1) >> l;
  endfunction
  function integer is_reg;
    input integer l;
    is_reg = (l % 2 == 0 || l == NL) ? 1 : 0;
  endfunction
  // A node's width at level l, and a registered node's segment of tr: the node and,
  // folded, its band above it.
  function integer nwl;
    input integer l;
    nwl = (l == 1) ? NP : NB + l;
  endfunction
  function integer segw;
    input integer l;
    segw = nwl(l) + ((F > 1) ? 5 * CW : 0);
  endfunction
  // The first bit of level l's nodes in tr (registered) and tc (the others).
  function integer off_r;
    input integer l;
    integer k;
    begin
      off_r = 0;
      for (k = 1; k < l; k = k + 1) if (is_reg(k) != 0) off_r = off_r + lvl_n(k) * segw(k);
    end
  endfunction
  function integer off_c;
    input integer l;
    integer k;
    begin
      off_c = 0;
      for (k = 1; k < l; k = k + 1) if (is_reg(k) == 0) off_c = off_c + lvl_n(k) * nwl(k);
    end
  endfunction
  localparam TRW = off_r(NL + 1);
  localparam TCW0 = off_c(NL + 1);           // 0 for a one-level tree (N0 = 2)
  localparam TCW = (TCW0 > 0) ? TCW0 : 1;
  localparam RNW = nwl(NL);                  // the root's width
  localparam RI = (NL == 1) ? P_I : NB;      // its i

  // ---- leaves: the costs of the N0 levels in view, folded with two neighbours on each
  // side for the leaves' bands: win[j*CW +: CW] = A(base + j - WP), j = 0..N0+2*WP-1
  // (base = 0, or g*PU when folded).
  localparam WP = (F > 1) ? 2 : 0;
  wire [(N0+2*WP)*CW-1:0] win;

  // ---- the tree: level l node n from level l-1 nodes 2n, 2n+1 -------------------------
  // A registered node takes its band (folded only: the accumulator merges the groups'
  // bands) not through band selects in the merges (two 2:1 selects per level, each on
  // its own compare) but from its winner's descendant at the registered level below (or
  // the leaves): one 4:1 (2:1 at an odd root) select on the winner's level bits, a LUT6
  // per bit.
  wire          tree_en = (F > 1) ? 1'b1 : ce;  // folded: every clock
  // The nodes as the level above reads them, in two vectors so that no signal is both
  // read and driven by the combinational part of the tree: tr the registered nodes (a
  // flip-flop each), tc the others.
  wire [TRW-1:0] tr;
  wire [TCW-1:0] tc;
  genvar j, l, t;
  generate
    if (TCW0 == 0) begin : g_no_tc
      assign tc = 1'b0;
      wire unused_tc = tc[0];
    end
    for (l = 1; l <= NL; l = l + 1) begin : g_lvl
      for (j = 0; j < lvl_n(l); j = j + 1) begin : g_node
        localparam W = nwl(l);
        wire [W-1:0] mg;
        if (l == 1) begin : g_pair  // N0 is even: every level-1 node has two leaves
          assign mg = pair(win[(2*j+WP)*CW +: CW], win[(2*j+WP+1)*CW +: CW]);
        end else begin : g_merge
          localparam CN = nwl(l - 1);  // a child's width and place
          localparam CA = (is_reg(l - 1) != 0) ? off_r(l - 1) + 2 * j * segw(l - 1)
                                               : off_c(l - 1) + 2 * j * CN;
          localparam CS = (is_reg(l - 1) != 0) ? segw(l - 1) : CN;
          wire [CN-1:0] a;
          if (is_reg(l - 1) != 0) begin : g_a_r
            assign a = tr[CA +: CN];
          end else begin : g_a_c
            assign a = tc[CA +: CN];
          end
          if (2 * j + 1 < lvl_n(l - 1)) begin : g_two
            wire [CN-1:0] b;
            if (is_reg(l - 1) != 0) begin : g_b_r
              assign b = tr[CA + CS +: CN];
            end else begin : g_b_c
              assign b = tc[CA + CS +: CN];
            end
            wire rw;  // b wins
            if (l == 2) begin : g_l2
              assign {rw, mg[NB-1:0]} = merge(unpair(a), unpair(b));
              assign mg[NB +: 2] = {rw, rw ? b[P_I] : a[P_I]};
            end else begin : g_ln
              assign {rw, mg[NB-1:0]} = merge(a[NB-1:0], b[NB-1:0]);
              assign mg[NB +: l] = {rw, rw ? b[NB +: l-1] : a[NB +: l-1]};
            end
          end else begin : g_pass  // odd count: the last node passes through
            if (l == 2) begin : g_l2
              assign mg = {1'b0, a[P_I], unpair(a)};
            end else begin : g_ln
              assign mg = {1'b0, a};
            end
          end
        end
        if (is_reg(l) != 0) begin : g_reg
          localparam OUT = off_r(l) + j * segw(l);
          reg [W-1:0] q;
          always @(posedge clk) begin
            if (tree_en) q <= mg;
          end
          if (F > 1) begin : g_band
            localparam LP = (l % 2 == 0) ? l - 2 : l - 1;  // registered level below (0: leaves)
            localparam NT = 1 << (l - LP);                 // descendants there: 4 or 2
            localparam IB = (l == 1) ? P_I : NB;           // mg's i
            wire [NT*5*CW-1:0] cand;                       // their bands
            for (t = 0; t < NT; t = t + 1) begin : g_cand
              if (j * NT + t >= lvl_n(LP)) begin : g_none  // past an odd count: never wins
                assign cand[t*5*CW +: 5*CW] = {(5 * CW) {1'b0}};
              end else if (LP == 0) begin : g_leaf
                assign cand[t*5*CW +: 5*CW] = win[(j*NT+t)*CW +: 5*CW];
              end else begin : g_node
                assign cand[t*5*CW +: 5*CW] = tr[off_r(LP) + (j * NT + t) * segw(LP) + nwl(LP) +: 5 * CW];
              end
            end
            wire [5*CW-1:0] bs;
            if (NT == 2) begin : g_sel2
              assign bs = mg[IB+LP] ? cand[5*CW +: 5*CW] : cand[0 +: 5*CW];
            end else begin : g_sel4
              wire [1:0] w = mg[IB+LP +: 2];
              assign bs = w[1] ? (w[0] ? cand[15*CW +: 5*CW] : cand[10*CW +: 5*CW])
                               : (w[0] ? cand[5*CW +: 5*CW] : cand[0 +: 5*CW]);
            end
            reg [5*CW-1:0] b_q;
            always @(posedge clk) begin
              b_q <= bs;
            end
            assign tr[OUT +: W+5*CW] = {b_q, q};
          end else begin : g_noband
            assign tr[OUT +: W] = q;
          end
        end else begin : g_comb
          assign tc[off_c(l) + j * W +: W] = mg;
        end
      end
    end
  endgenerate
  wire [RNW-1:0] root = tr[off_r(NL) +: RNW];

  // Record: {band, cmax, c2, c1, dw}
  localparam RW = 8 * CW + DW;
  wire [RW-1:0] rec;  // the output registers' value
  assign {m_band, m_cmax, m_c2, m_c1, m_dw} = rec;

  generate
    if (F == 1) begin : g_par
      // ---- one beat per clock: the leaves read s_cost, the root is the output --------
      assign win = s_cost;
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
      // (N0 = DISP >= 4: the root is a level >= 2 node and its i, NL = DW bits, is dw)
      wire [5*CW-1:0] band = band_at({{2*CW{1'b0}}, cd_q[(NS-1)*DISP*CW +: DISP*CW], {2*CW{1'b0}}}, root[NB +: DW]);
      assign rec = {band, root[O_MX +: CW], root[O_E +: CW], root[O_M +: CW], root[NB +: DW]};
      wire unused_root = ^{root[O_FL], root[O_LA], root[O_XF +: CW], root[O_XL +: CW], rst_n};
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
      wire [(DISP+4)*CW-1:0] pad = {{2*CW{1'b0}}, s_cost, {2*CW{1'b0}}};  // (every bit read)
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

      // Accumulator: the groups so far; the root's level within the group made global.
      wire [NB-1:0] grp_f;
      wire [NL-1:0] grp_li;
      if (NL == 1) begin : g_root1
        assign grp_f = unpair(root);
      end else begin : g_rootn
        assign grp_f = root[NB-1:0];
      end
      assign grp_li = root[RI +: NL];
      wire [DW-1:0] grp_i = {{(DW - NL) {1'b0}}, grp_li} + tb_q[NS*DW +: DW];
      wire [5*CW-1:0] grp_b = tr[off_r(NL) + RNW +: 5*CW];
      reg  [NB-1:0] acc_q;
      reg  [DW-1:0] acc_i_q;
      reg  [5*CW-1:0] acc_b_q;
      wire [NB:0] am = merge(acc_q, grp_f);  // am[NB]: the group wins
      always @(posedge clk) begin
        if (tv_q[NS]) begin
          acc_q <= tf_q[NS] ? grp_f : am[NB-1:0];
          if (tf_q[NS] || am[NB]) begin
            acc_i_q <= grp_i;
            acc_b_q <= grp_b;
          end
        end
      end

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
              {acc_b_q, acc_q[O_MX +: CW], acc_q[O_E +: CW], acc_q[O_M +: CW], acc_i_q};
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
