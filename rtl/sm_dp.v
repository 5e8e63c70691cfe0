`default_nettype none
// Trellis dynamic programming stage (docs/algorithm.md, section 6): a systolic array
// of DISP processing elements (sm_dp_pe), one per level, linked only to neighbours.
// Line k runs its forward pass in exactly W ce's (two sites per clock), writing one
// 2*DISP-bit decision word per clock into a double-buffered block RAM; during the
// forward pass of line k+1, sm_dp_trace walks line k backwards and stacks its
// matches; during line k+2's forward pass line k leaves in raster order, filled.
// Lines follow each other with no gap, virtual rows included.
//
// Timing (x_in = column of the entering beat, S = DISP/2, P = 2):
//   PE d sees A(x, d) S - ceil(d/2) beats after it enters, so DP clock t of a line is
//   the ce on which column S + t enters (mod W, running into the next row); the ce at
//   x_in = S - 1 ends a line and loads U(0, .).
//   On forward clock t of line k+1, decision word W-1-t of line k (the other bank)
//   is read; the backward step uses it on the next ce, so the last backward step of
//   line k is at x_in = S, the read-out head is fetched at x_in = S + 1, and pixel x
//   of line k is registered on the ce at x_in = S + 2 + x (mod W), two rows later.
//   Latency: 2*W + S + P beats (sm_win_ctrl with D_ROWS = 2, D_COLS = S + P).
//   Minimum active width: S + P + 1 (width must exceed D_COLS).
module sm_dp #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter DISP      = 128,  // disparity levels 0..DISP-1 (even, 4..254)
    parameter CW        = 6,    // aggregated cost width
    // Cost skews of at least RING_MIN beats live in LUT-RAM ring buffers, shorter ones
    // in shift registers (sm_dp_pe). The default puts every chain longer than a 64-bit
    // word in a ring (paper configuration: skews of 11..64 beats).
    parameter RING_MIN  = 64 / CW + 1
) (
    input  wire               clk,
    input  wire               rst_n,
    input  wire               ce,
    input  wire [XW-1:0]      width,   // active width, S + 3 .. MAX_WIDTH
    input  wire [7:0]         occ,     // occlusion penalty, latched per frame
    input  wire [4:0]         s_side,
    input  wire [DISP*CW-1:0] s_cost,  // A(x, d) at [d*CW +: CW]
    output reg  [4:0]         m_side,
    output wire [15:0]        m_disp   // bit 15 valid (always), low DW bits disparity
);
  localparam XW = $clog2(MAX_WIDTH + 1);
  localparam AW = $clog2(MAX_WIDTH);
  localparam DW = $clog2(DISP);
  localparam S = DISP / 2;
  localparam P = 2;  // beats of the read-out beyond 2 lines + skew
  localparam ACC_W = $clog2(MAX_WIDTH * ((1 << CW) - 1) + 2 * MAX_WIDTH * 255 + 1) + 1;
  localparam KW = $clog2(S);  // ring pointers: the longest skew is S beats

  generate
    if (DISP < 4 || DISP > 254 || DISP % 2 != 0) begin : g_bad_disp
      initial $error("sm_dp: DISP (%0d) must be even, 4..254", DISP);
    end
    if (CW < 1 || CW > 8) begin : g_bad_cw
      initial $error("sm_dp: CW (%0d) must be 1..8", CW);
    end
    if (S + P + 1 > MAX_WIDTH) begin : g_bad_width
      initial $error("sm_dp: MAX_WIDTH (%0d) must be at least DISP/2 + 3", MAX_WIDTH);
    end
    if (RING_MIN < 2) begin : g_bad_ring
      initial $error("sm_dp: RING_MIN (%0d) must be at least 2", RING_MIN);
    end
  endgenerate

  // ---- beat position -----------------------------------------------------------
  wire [XW-1:0] x_in;
  wire [4:0]    c_side;
  wire [XW-1:0] c_x;
  wire [0:0]    row_ok;
  wire [0:0]    col_ok;
  sm_win_ctrl #(
      .MAX_WIDTH(MAX_WIDTH),
      .D_ROWS   (2),
      .D_COLS   (S + P),
      .R_UP     (0),
      .R_DN     (0),
      .R_L      (0),
      .R_R      (0)
  ) u_win (
      .clk   (clk),
      .rst_n (rst_n),
      .ce    (ce),
      .width (width),
      .s_side(s_side),
      .s_x   (x_in),
      .c_side(c_side),
      .c_x   (c_x),
      .row_ok(row_ok),
      .col_ok(col_ok)
  );

  /* verilator lint_off WIDTH */  // small constants truncated to the column width
  localparam [XW-1:0] S_M1 = S - 1;
  localparam [XW-1:0] S_0 = S;
  localparam [XW-1:0] S_P1 = S + 1;
  localparam [XW-1:0] S_P2 = S + 2;
  /* verilator lint_on WIDTH */
  // forward DP clock of this ce, and the pixel the read-out emits on it
  wire [XW-1:0] t_f = (x_in >= S_0) ? x_in - S_0 : x_in + width - S_0;
  wire [XW-1:0] t_rev = width - 1'b1 - t_f;
  // Pixel the read-out emits: (x_in - S - 2) mod W. Counted instead of computed from
  // x_in: the modulo (compare, subtract, add) in front of the read-out's equality
  // compare and stack-address select made the longest register-to-register path. Lines
  // are exactly W beats with sol on beat 0 (sm_seq), so the count equals the formula:
  // at sol x_in = 0 gives W - S - 2, and it steps by one, wrapping after W - 1.
  reg  [XW-1:0] xo_q;       // x_out of the previous ce
  reg           xo_last_q;  // xo_q == W - 1
  wire [XW-1:0] x_out = s_side[2] ? width - S_P2 : xo_last_q ? {XW{1'b0}} : xo_q + 1'b1;
  always @(posedge clk) begin
    if (ce) begin
      xo_q      <= x_out;
      xo_last_q <= (x_out == width - 1'b1);
    end
  end
  wire          line_end = (x_in == S_M1);  // forward clock W-1
  wire          step_last = (x_in == S_0);  // backward step of site pair 0
  wire          rd_start = (x_in == S_P1);
  // c_x/masks are not needed; t_rev's top bit is 0 (t < MAX_WIDTH)
  wire unused_win = &{c_x, row_ok, col_ok, t_rev};

  // ---- control: decision bank, per-frame occ -----------------------------------
  reg       fbank_q;     // decision bank the forward pass writes
  reg       rowfirst_q;  // the row entering is the first of a frame
  reg [7:0] occ_q;
  always @(posedge clk) begin
    if (!rst_n) begin
      fbank_q    <= 1'b0;
      rowfirst_q <= 1'b0;
      occ_q      <= 8'd0;
    end else if (ce) begin
      if (line_end) fbank_q <= ~fbank_q;
      if (s_side[2]) rowfirst_q <= s_side[1];
      // the next ce starts the forward pass of this row's line
      if (line_end && rowfirst_q) occ_q <= occ;
    end
  end

  // ---- skew rings: one write pointer, one read pointer per skew length k ----------
  // rp of length k is kept equal to wp - k (mod 2^KW) by counting alongside wp, so every
  // ring address comes straight from flip-flops (no subtractor in front of the RAM).
  // Both PEs of a length share its pointer. Every ring of depth 2^RW <= 2^KW uses the
  // pointers' low RW bits.
  reg  [KW-1:0]       wp_q;
  wire [(S+1)*KW-1:0] rps;  // read pointer of skew length k at [k*KW +: KW]
  always @(posedge clk) begin
    if (!rst_n) wp_q <= {KW{1'b0}};
    else if (ce) wp_q <= wp_q + 1'b1;
  end
  genvar k;
  generate
    for (k = 0; k <= S; k = k + 1) begin : g_rp
      if (k >= RING_MIN) begin : g_ring
        /* verilator lint_off WIDTH */  // -k modulo 2^KW
        localparam [KW-1:0] RP0 = (1 << KW) - k;
        /* verilator lint_on WIDTH */
        reg [KW-1:0] rp_q;
        always @(posedge clk) begin
          if (!rst_n) rp_q <= RP0;
          else if (ce) rp_q <= rp_q + 1'b1;
        end
        assign rps[k*KW +: KW] = rp_q;
      end else begin : g_shift
        assign rps[k*KW +: KW] = {KW{1'b0}};  // shift-register skew: unused
      end
    end
  endgenerate

  // ---- the array ---------------------------------------------------------------
  wire [(DISP+2)*ACC_W-1:0] nbx;  // nb of level d at (d+1)*ACC_W, zero pads at both ends
  wire [2*DISP-1:0]         dec;
  assign nbx[ACC_W-1:0] = {ACC_W{1'b0}};
  assign nbx[(DISP+1)*ACC_W +: ACC_W] = {ACC_W{1'b0}};
  genvar d;
  generate
    for (d = 0; d < DISP; d = d + 1) begin : g_pe
      sm_dp_pe #(
          .CW    (CW),
          .ACC_W (ACC_W),
          .ODD   (d % 2),
          .HAS_LO(d > 0 ? 1 : 0),
          .HAS_HI(d < DISP - 1 ? 1 : 0),
          .IS_D0 (d == 0 ? 1 : 0),
          .DELAY (S - (d + 1) / 2),
          .RING  (S - (d + 1) / 2 >= RING_MIN ? 1 : 0),
          .KW    (KW)
      ) u_pe (
          .clk  (clk),
          .ce   (ce),
          .init (line_end),
          .occ  (occ_q),
          .cost (s_cost[d*CW +: CW]),
          .wp   (wp_q),
          .ra   (rps[(S-(d+1)/2)*KW +: KW]),
          .nb_lo(nbx[d*ACC_W +: ACC_W]),
          .nb_hi(nbx[(d+2)*ACC_W +: ACC_W]),
          .nb   (nbx[(d+1)*ACC_W +: ACC_W]),
          .dec  (dec[2*d +: 2])
      );
    end
  endgenerate

  // ---- decisions: written by the forward pass, read back mirrored --------------
  wire [2*DISP-1:0] dec_rd;
  reg  [AW-1:0]     t_dec_q;  // t of dec_rd
  sm_dp_ram #(
      .DATA_W(2 * DISP),
      .ADDR_W(AW + 1)
  ) u_dec (
      .clk  (clk),
      .we   (ce),
      .waddr({fbank_q, t_f[AW-1:0]}),
      .wdata(dec),
      .re   (ce),
      .raddr({~fbank_q, t_rev[AW-1:0]}),
      .rdata(dec_rd)
  );
  always @(posedge clk) begin
    if (ce) t_dec_q <= t_rev[AW-1:0];
  end

  // ---- backward pass, fill, read-out --------------------------------------------
  wire [DW-1:0] disp_q;
  sm_dp_trace #(
      .MAX_WIDTH(MAX_WIDTH),
      .DISP     (DISP)
  ) u_trace (
      .clk      (clk),
      .rst_n    (rst_n),
      .ce       (ce),
      .dec_word (dec_rd),
      .t_dec    (t_dec_q),
      .step_last(step_last),
      .rd_start (rd_start),
      .x_out    (x_out),
      .disp_q   (disp_q)
  );
  assign m_disp = {1'b1, {(15 - DW) {1'b0}}, disp_q};

  always @(posedge clk) begin
    if (!rst_n) m_side <= 5'd0;
    else if (ce) m_side <= c_side;
  end
endmodule
`default_nettype wire
