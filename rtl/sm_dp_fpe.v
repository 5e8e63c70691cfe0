`default_nettype none
`include "sm_defs.vh"
// The arithmetic of one trellis level (docs/algorithm.md, section 6), without state and
// cost skew: sm_dp_pe wraps it with its register and skew (one PE per level), and the
// folded array (sm_dp with F = DISP/PU > 1) uses it as a lane whose state and skew live
// in sm_dp's per-lane memories, because the lane serves a different level on each of
// the F sub-steps of a DP clock (its odd lanes as the occlusion node alone, NODE = 1).
// Per sub-step it advances U(., d) of its level d by the sites 2t+1 and 2t+2, in the
// order the parity of d dictates (PU is even, so the parity is the lane's):
//   odd d : site 2t+1 is an occlusion node (min3 over U(2t, d-1..d+1)), 2t+2 matched;
//   even d: site 2t+1 is matched, 2t+2 an occlusion node (min3 over U(2t+1, d-1..d+1)).
// Whether level d-1 / d+1 exists depends on the group at the array's two ends, so it is
// an input here (a parameter in sm_dp_pe). Purely combinational.
module sm_dp_fpe #(
    parameter CW    = 6,   // aggregated cost width
    parameter ACC_W = 19,  // accumulator width (algorithm.md: BIG = 2^(ACC_W-1))
    parameter ODD   = 0,   // 1: the lane's levels are odd
    // 1 (odd levels only): the occlusion node alone, for the folded array's odd lanes,
    // which compute it a clock ahead of their sub-step and add the cost behind a
    // register: u_next is then the node's value U(2t+1, d), and a is not used
    parameter NODE  = 0
) (
    input  wire [ACC_W-1:0] u,       // U(2t, d), read from the lane's state memory
    input  wire [CW-1:0]    a,       // skewed cost A(t + ceil(d/2), d)
    input  wire [7:0]       occ,     // penalty of this sub-step's occlusion node
    input  wire             has_lo,  // level d-1 exists (d >= 1)
    input  wire             has_hi,  // level d+1 exists (d <= DISP-2)
    input  wire [ACC_W-1:0] nb_lo,   // nb of level d-1
    input  wire [ACC_W-1:0] nb_hi,   // nb of level d+1
    output wire [ACC_W-1:0] nb,      // what levels d-1 and d+1 need this sub-step
    output wire [ACC_W-1:0] u_next,  // U(2t+2, d)
    output wire [1:0]       dec      // choice of this sub-step's occlusion node
);
  generate
    `SM_BAD_PARAM(g_bad_w, ACC_W <= 8 || CW < 1 || CW >= ACC_W,
                  ("sm_dp_fpe: need 8 < ACC_W (%0d) and 1 <= CW (%0d) < ACC_W", ACC_W, CW))
    `SM_BAD_PARAM(g_bad_node, NODE != 0 && (NODE != 1 || ODD == 0),
                  ("sm_dp_fpe: NODE (%0d) must be 0, or 1 with ODD", NODE))
  endgenerate

  wire [ACC_W-1:0] self_in;  // choice 0 of the occlusion node
  wire [ACC_W-1:0] c1 = nb_lo + {{(ACC_W - 8) {1'b0}}, occ};
  wire [ACC_W-1:0] c2 = nb_hi + {{(ACC_W - 8) {1'b0}}, occ};
  // min3 with the spec's tie order: 0, then 1, then 2 (later ones must be strictly
  // less). The three comparisons run in parallel and one 3:1 multiplexer picks the
  // result, instead of compare-select-compare-select: two compare/select levels per
  // site would put ten LUTs between registers across the two sites of a clock. Nothing
  // wraps (algorithm.md: every sum stays below 2*BIG), so c2 < c1 is nb_hi < nb_lo and
  // needs no adder in front.
  wire             lt10 = c1 < self_in;
  wire             lt20 = c2 < self_in;
  wire             lt21 = nb_hi < nb_lo;
  wire             take1 = has_lo && lt10;
  wire             take2 = has_hi && (take1 ? lt21 : lt20);
  wire [ACC_W-1:0] occ_u = take2 ? c2 : take1 ? c1 : self_in;
  assign dec = take2 ? 2'd2 : take1 ? 2'd1 : 2'd0;

  generate
    if (ODD != 0 && NODE != 0) begin : g_node
      assign self_in = u;      // site 2t+1: occlusion
      assign u_next  = occ_u;  // U(2t+1, d): the lane adds a behind its register
      assign nb      = occ_u;
      wire unused_a = ^a;
    end else if (ODD != 0) begin : g_odd
      assign self_in = u;                                   // site 2t+1: occlusion
      assign u_next  = occ_u + {{(ACC_W - CW) {1'b0}}, a};  // site 2t+2: matched
      assign nb      = occ_u;                               // U(2t+1, d)
    end else begin : g_even
      assign self_in = u + {{(ACC_W - CW) {1'b0}}, a};      // site 2t+1: matched
      assign u_next  = occ_u;                               // site 2t+2: occlusion
      assign nb      = u;                                   // U(2t, d)
    end
  endgenerate
endmodule
`default_nettype wire
