`default_nettype none
// Matching cost: Hamming distance of the left census vector with the right vectors
// of the DISP previous beats (docs/algorithm.md, section 4). The right vectors of the
// last DISP-1 beats sit in a delay line; since rows are exactly width beats, the
// beat d back in the same row is the right pixel x - d. A thermometer of the column
// (reset by sol) marks the levels with x - d < 0, which get CB.
//
// Latency 3 ce: popcount leaves, popcount result, output (with the x - d < 0 rule).
module sm_cost #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter DISP      = 128,  // disparity levels 0..DISP-1
    parameter CENSUS    = 15    // census window side (odd, 3..15)
) (
    input  wire               clk,
    input  wire               rst_n,
    input  wire               ce,
    input  wire [XW-1:0]      width,   // unused: the cost needs only the row starts
    input  wire [4:0]         s_side,
    input  wire [CB-1:0]      s_cl,    // left census vector
    input  wire [CB-1:0]      s_cr,    // right census vector
    input  wire [7:0]         s_left,  // left centre pixel, passed through
    output reg  [4:0]         m_side,
    output reg  [HW*DISP-1:0] m_cost,  // bit-plane order: bit f of level d at [f*DISP + d]
    output reg  [7:0]         m_left
);
  localparam XW = $clog2(MAX_WIDTH + 1);
  localparam CB = CENSUS * CENSUS - 1;
  localparam HW = $clog2(CB + 1);
  // cost of a level whose right pixel is left of the image; CB fits HW bits by definition
  /* verilator lint_off WIDTH */
  localparam [HW-1:0] CB_V = CB;
  /* verilator lint_on WIDTH */

  generate
    if (CENSUS < 3 || CENSUS > 15 || CENSUS % 2 == 0) begin : g_bad_census
      initial $error("sm_cost: CENSUS (%0d) must be odd, 3..15", CENSUS);
    end
    if (DISP < 2 || DISP > 256) begin : g_bad_disp
      initial $error("sm_cost: DISP (%0d) must be 2..256", DISP);
    end
  endgenerate
  wire unused_width = &width;

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
  genvar i;
  generate
    for (i = 0; i < CB; i = i + 1) begin : g_plane
      always @* begin
        cr_all[i*DISP +: DISP] = {crd_q[i*DISP +: DISP-1], s_cr[i]};
        cl_all[i*DISP +: DISP] = {DISP{s_cl[i]}};  // the left vector, every level
      end
      wire unused_crd_top = crd_q[i*DISP + DISP - 1];  // beat n - DISP
    end
  endgenerate
  always @(posedge clk) if (ce) crd_q <= cr_all;

  // ok[d] = (x >= d) for the entering beat: all ones shifted in since the row start.
  reg  [DISP-1:0] ok_q;
  wire [DISP-1:0] ok = s_side[2] ? {{(DISP - 1) {1'b0}}, 1'b1} : {ok_q[DISP-2:0], 1'b1};
  wire unused_ok_top = ok_q[DISP-1];  // shifted out

  // Popcount of every level (one compressor tree per level), latency 2.
  wire [HW*DISP-1:0] pc;  // bit-plane order: bit f of level d at [f*DISP + d]
  sm_popcount #(.N(CB), .L(DISP)) u_pc (.clk(clk), .ce(ce), .a(cl_all), .b(cr_all), .cnt(pc));

  // Control and pass-through data along the popcount's two stages.
  reg [DISP-1:0] ok_q2, ok_q3;
  reg [4:0]      side_q2, side_q3;
  reg [7:0]      left_q2, left_q3;
  always @(posedge clk) begin
    if (!rst_n) begin
      ok_q    <= {DISP{1'b0}};
      side_q2 <= 5'd0;
      side_q3 <= 5'd0;
      m_side  <= 5'd0;
    end else if (ce) begin
      ok_q    <= ok;
      side_q2 <= s_side;
      side_q3 <= side_q2;
      m_side  <= side_q3;
    end
  end

  // Output costs: CB where x - d < 0, applied plane by plane (bit f: the count's where
  // ok, CB's bit f elsewhere; the same 2:1 multiplexer per bit as a per-level select,
  // as DISP-bit operations in Verilator). They leave in bit-plane order, the order
  // sm_sw_aggregate sums them in: a transpose to level order and back would be wiring
  // in hardware but two thousand bit moves a clock in Verilator.
  wire [HW*DISP-1:0] cost_p;  // bit-plane order
  genvar f;
  generate
    for (f = 0; f < HW; f = f + 1) begin : g_cb
      if (CB_V[f]) begin : g_one
        assign cost_p[f*DISP +: DISP] = pc[f*DISP +: DISP] | ~ok_q3;
      end else begin : g_zero
        assign cost_p[f*DISP +: DISP] = pc[f*DISP +: DISP] & ok_q3;
      end
    end
  endgenerate
  always @(posedge clk) begin
    if (ce) begin
      ok_q2   <= ok;
      ok_q3   <= ok_q2;
      left_q2 <= s_left;
      left_q3 <= left_q2;
      m_left  <= left_q3;
      m_cost  <= cost_p;
    end
  end
endmodule
`default_nettype wire
