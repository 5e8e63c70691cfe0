`default_nettype none
`include "sm_defs.vh"
// One level d of the trellis systolic array (docs/algorithm.md, section 6). Per DP
// clock t it advances U(., d) by the two sites 2t+1 and 2t+2: one matched add and one
// min3, in the order the parity of d dictates. It talks only to levels d-1 and d+1:
//   odd d : site 2t+1 is an occlusion node (min3 over U(2t, d-1..d+1), the even
//           neighbours' registered state), site 2t+2 is matched (+ cost);
//   even d: site 2t+1 is matched (+ cost), site 2t+2 is an occlusion node (min3 over
//           U(2t+1, d-1..d+1), the odd neighbours' mid-clock value).
// So a PE exports on nb what its neighbours need: U(2t+1) if odd, U(2t) if even.
// The cost input is skewed by DELAY beats: a short skew by a private shift register
// (no reset, SRL-friendly), a long one (RING = 1) by a ring buffer in LUT-RAM that
// sm_dp addresses (wp: the write pointer, ra: wp - DELAY, both counted in sm_dp and
// shared by every PE of the same DELAY).
module sm_dp_pe #(
    parameter CW     = 6,   // aggregated cost width
    parameter ACC_W  = 19,  // accumulator width (algorithm.md: BIG = 2^(ACC_W-1))
    parameter ODD    = 0,   // 1: level d is odd
    parameter HAS_LO = 1,   // 1: level d-1 exists (d >= 1)
    parameter HAS_HI = 1,   // 1: level d+1 exists (d <= DISP-2)
    parameter IS_D0  = 0,   // 1: d == 0, the line starts here with U = 0 (others BIG)
    parameter DELAY  = 0,   // cost skew in beats: S - ceil(d/2)
    parameter RING   = 0,   // 1: the skew is a LUT-RAM ring buffer (DELAY >= 2)
    parameter KW     = 1    // ring pointer width: 2^KW >= DELAY
) (
    input  wire             clk,
    input  wire             ce,
    input  wire             init,    // this clock ends a line: load U(0, d) instead
    input  wire [7:0]       occ,     // this clock's occlusion penalty (its level pair's)
    input  wire [CW-1:0]    cost,    // A(x, d) of the beat entering now (unskewed)
    input  wire [KW-1:0]    wp,      // ring write pointer (RING = 1)
    input  wire [KW-1:0]    ra,      // ring read pointer, wp - DELAY modulo 2^KW
    input  wire [ACC_W-1:0] nb_lo,   // nb of level d-1 (ignored when !HAS_LO)
    input  wire [ACC_W-1:0] nb_hi,   // nb of level d+1 (ignored when !HAS_HI)
    output wire [ACC_W-1:0] nb,      // what levels d-1 and d+1 need this clock
    output wire [1:0]       dec      // choice of this clock's occlusion node
);
  localparam [ACC_W-1:0] BIG = {1'b1, {(ACC_W - 1) {1'b0}}};
  localparam [ACC_W-1:0] U0  = (IS_D0 != 0) ? {ACC_W{1'b0}} : BIG;

  generate
    `SM_BAD_PARAM(g_bad_w, ACC_W <= 8 || CW < 1 || CW >= ACC_W,
                  ("sm_dp_pe: need 8 < ACC_W (%0d) and 1 <= CW (%0d) < ACC_W", ACC_W, CW))
    `SM_BAD_PARAM(g_bad_delay, DELAY < 0, ("sm_dp_pe: negative DELAY %0d", DELAY))
    `SM_BAD_PARAM(g_bad_ring, RING != 0 && (DELAY < 2 || (1 << KW) < DELAY),
                  ("sm_dp_pe: a ring needs 2 <= DELAY (%0d) <= 2^KW (KW %0d)", DELAY, KW))
  endgenerate

  // ---- cost skew ---------------------------------------------------------------
  wire [CW-1:0] a;
  generate
    if (RING != 0) begin : g_ring
      // DEPTH = 2^RW >= DELAY words; slot wp is written on every ce and slot
      // wp - DELAY, written DELAY ce's ago, is read. When DELAY = DEPTH the two are the
      // same slot, whose read still sees the old word during the ce that overwrites it.
      // Against a chain of DELAY stages: a RAM32M/RAM64M group instead of DELAY/32 SRLs
      // per bit, and in Verilator one write and one read per clock instead of shifting
      // DELAY*CW bits (the chains were a tenth of the paper configuration's simulation).
      localparam RW = (DELAY > 1) ? $clog2(DELAY) : 1;
      (* ram_style = "distributed" *)
      reg [CW-1:0] ring [0:(1<<RW)-1];
      always @(posedge clk) begin
        if (ce) ring[wp[RW-1:0]] <= cost;
      end
      assign a = ring[ra[RW-1:0]];
      if (RW < KW) begin : g_hi
        wire unused_hi = &{wp[KW-1:RW], ra[KW-1:RW]};  // shared pointers of deeper rings
      end
    end else if (DELAY == 0) begin : g_nodelay
      assign a = cost;
    end else if (DELAY == 1) begin : g_delay1
      reg [CW-1:0] sr_q;
      always @(posedge clk) begin
        if (ce) sr_q <= cost;
      end
      assign a = sr_q;
    end else begin : g_delay
      // One packed vector, stage k at [k*CW +: CW]: the same flip-flop chain (SRLs after
      // mapping) as an array of stages, but Verilator shifts it as a few machine words
      // per clock instead of copying every stage through a delayed-assignment temporary.
      reg [DELAY*CW-1:0] sr_q;
      always @(posedge clk) begin
        if (ce) sr_q <= {sr_q[(DELAY-1)*CW-1:0], cost};
      end
      assign a = sr_q[(DELAY-1)*CW +: CW];
    end
    if (RING == 0) begin : g_noring
      wire unused_ring = &{wp, ra};
    end
  endgenerate

  // ---- the two sites (sm_dp_fpe: the same arithmetic as the folded array's lanes) ----
  reg  [ACC_W-1:0] u_q;  // U(2t, d)
  wire [ACC_W-1:0] u_next;
  sm_dp_fpe #(.CW(CW), .ACC_W(ACC_W), .ODD(ODD)) u_fpe (
      .u(u_q), .a(a), .occ(occ), .has_lo(HAS_LO != 0), .has_hi(HAS_HI != 0), .nb_lo(nb_lo), .nb_hi(nb_hi),
      .nb(nb), .u_next(u_next), .dec(dec)
  );

  // Datapath register: no reset; the line start loads U(0, d) every line.
  always @(posedge clk) begin
    if (ce) u_q <= init ? U0 : u_next;
  end
endmodule
`default_nettype wire
