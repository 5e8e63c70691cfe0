`default_nettype none
`include "sm_defs.vh"
// Pipelined unsigned restoring division with a saturating QW-bit quotient, the one
// divider of the output stage (docs/algorithm.md sections 9.1 and 9.3; sm_subpix_fit,
// sm_conf_ratio):
//   q = min(floor(n / d), 2^QW - 1)        (d = 0 gives 2^QW - 1)
// One quotient bit per ce stage, most significant first: stage s decides bit
// b = QW - 1 - s by comparing the remainder with d << b, i.e. its bits [NW-1:b] with d
// (one subtraction whose borrow is the compare, then a 2:1 select of the remainder:
// ~2-4 LUT levels at the widths used). The quotient saturates by itself: when
// n >= 2^QW d, every stage keeps a remainder of at least d << b, so every bit is 1.
// Latency: QW ce's (LATENCY) from n, d to q. Data only, no reset: the caller delays its
// sideband beside it. Everything changes only on ce.
module sm_udiv #(
    parameter NW = 11,  // dividend bits (QW..32)
    parameter DW = 8,   // divisor bits (1..32)
    parameter QW = 4    // quotient bits = pipeline stages (2..16)
) (
    input  wire          clk,
    input  wire          ce,
    input  wire [NW-1:0] n,  // dividend
    input  wire [DW-1:0] d,  // divisor
    output wire [QW-1:0] q   // min(floor(n / d), 2^QW - 1), LATENCY ce's later
);
  localparam LATENCY = QW;  // ce's from n, d to q: one stage per quotient bit

  generate
    `SM_BAD_PARAM(g_bad_qw, QW < 2 || QW > 16, ("sm_udiv: QW (%0d) must be 2..16", QW))
    `SM_BAD_PARAM(g_bad_nw, NW < QW || NW > 32, ("sm_udiv: NW (%0d) must be QW (%0d)..32", NW, QW))
    `SM_BAD_PARAM(g_bad_dw, DW < 1 || DW > 32, ("sm_udiv: DW (%0d) must be 1..32", DW))
  endgenerate

  // Stage s's registers (s = 0..QW-2 feed stage s+1): remainder at [s*NW +: NW], divisor
  // at [s*DW +: DW], quotient bits decided so far at [s*QW +: QW] (the others 0).
  reg [(QW-1)*NW-1:0] rem_r;
  reg [(QW-1)*DW-1:0] d_r;
  reg [(QW-1)*QW-1:0] q_r;
  reg [QW-1:0]        q_o;  // the last stage: the whole quotient
  assign q = q_o;

  genvar s;
  generate
    for (s = 0; s < LATENCY; s = s + 1) begin : g_st
      localparam B = QW - 1 - s;                // the quotient bit this stage decides
      localparam HW = NW - B;                   // remainder bits compared with d
      localparam CMW = (HW > DW ? HW : DW) + 1;  // compare width: one borrow bit on top
      wire [NW-1:0] r;   // remainder in
      wire [DW-1:0] dv;  // divisor in
      wire [QW-1:0] qp;  // quotient bits above b
      if (s == 0) begin : g_first
        assign r  = n;
        assign dv = d;
        assign qp = {QW{1'b0}};
      end else begin : g_next
        assign r  = rem_r[(s-1)*NW +: NW];
        assign dv = d_r[(s-1)*DW +: DW];
        assign qp = q_r[(s-1)*QW +: QW];
      end
      wire [CMW-1:0] a  = {{(CMW - HW) {1'b0}}, r[NW-1:B]};
      wire [CMW-1:0] dz = {{(CMW - DW) {1'b0}}, dv};
      if (s < QW - 1) begin : g_mid
        // a - d; its borrow (top bit) is a < d. When a >= d the difference is below a,
        // so its bits above HW are 0 and only [HW-1:0] go back into the remainder.
        /* verilator lint_off UNUSEDSIGNAL */
        wire [CMW-1:0] df = a - dz;
        /* verilator lint_on UNUSEDSIGNAL */
        wire ge = ~df[CMW-1];
        always @(posedge clk) begin
          if (ce) begin
            rem_r[s*NW +: NW] <= ge ? {df[HW-1:0], r[B-1:0]} : r;
            d_r[s*DW +: DW]   <= dv;
            q_r[s*QW +: QW]   <= qp | ({{(QW - 1) {1'b0}}, ge} << B);
          end
        end
      end else begin : g_last  // bit 0: only the compare, no remainder left to keep
        always @(posedge clk) begin
          if (ce) q_o <= qp | {{(QW - 1) {1'b0}}, a >= dz};
        end
      end
    end
  endgenerate
endmodule
`default_nettype wire
