`default_nettype none
`include "sm_defs.vh"
// Index of the lowest set bit of a vector (combinational): sm_objects' choice of the next
// free label. A loop over the bits is a priority chain N muxes deep; this is a tree of
// 8-bit priority encoders in three tiers (8, 64, 512 bits), each a function of at most
// 8 inputs per output bit, and a select of the chosen group's index per tier; only the
// groups N bits need are built.
module sm_lowest_set #(
    parameter N  = 64,  // bits (1..512)
    parameter IW = 6    // index width (clog2(N)..9, at least 1)
) (
    input  wire [N-1:0]  v,
    output wire          any,  // some bit is set
    output wire [IW-1:0] idx   // the lowest set bit (0 when none)
);
  generate
    `SM_BAD_PARAM(g_bad_n, N < 1 || N > 512 || IW < 1 || IW > 9 || (1 << IW) < N,
                  ("sm_lowest_set: need 1 <= N (%0d) <= 512 and 2^IW >= N, IW (%0d) <= 9", N, IW))
  endgenerate

  // {any, index} of the lowest set bit of 8
  function [3:0] low8;
    input [7:0] b;
    begin
      casez (b)
        8'b???????1: low8 = 4'b1000;
        8'b??????10: low8 = 4'b1001;
        8'b?????100: low8 = 4'b1010;
        8'b????1000: low8 = 4'b1011;
        8'b???10000: low8 = 4'b1100;
        8'b??100000: low8 = 4'b1101;
        8'b?1000000: low8 = 4'b1110;
        8'b10000000: low8 = 4'b1111;
        default:     low8 = 4'b0000;
      endcase
    end
  endfunction

  localparam G1 = (N + 7) / 8;   // tier 1: groups of 8 bits
  localparam G2 = (G1 + 7) / 8;  // tier 2: groups of 8 groups (at most 8)
  wire [8*G1-1:0] p;
  wire [8*G2-1:0] any1;          // the groups' "some bit set", padded with 0
  wire [3*G1-1:0] idx1;          // 3 bits each
  wire [7:0]      any2;          // tier 2's, padded with 0
  wire [47:0]     idx2;          // 6 bits each
  genvar g;
  generate
    if (8 * G1 > N) begin : g_pad_v
      assign p = {{(8 * G1 - N){1'b0}}, v};
    end else begin : g_v
      assign p = v;
    end
    if (8 * G2 > G1) begin : g_pad_1
      assign any1[8*G2-1:G1] = {(8 * G2 - G1){1'b0}};
    end
    for (g = 0; g < G1; g = g + 1) begin : g_t1
      assign {any1[g], idx1[3*g +: 3]} = low8(p[8*g +: 8]);
    end
    for (g = 0; g < 8; g = g + 1) begin : g_t2
      if (g < G2) begin : g_used
        wire [3:0] s = low8(any1[8*g +: 8]);
        // the chosen group's index (groups past G1 are never chosen: their any is 0)
        wire [23:0] grp;
        if (8 * g + 8 <= G1) begin : g_full
          assign grp = idx1[24*g +: 24];
        end else begin : g_part
          assign grp = {{(24 - 3 * (G1 - 8 * g)){1'b0}}, idx1[3*G1-1:24*g]};
        end
        assign any2[g] = s[3];
        assign idx2[6*g +: 6] = {s[2:0], grp[3*s[2:0] +: 3]};
      end else begin : g_none
        assign any2[g] = 1'b0;
        assign idx2[6*g +: 6] = 6'd0;
      end
    end
  endgenerate
  wire [3:0]  s3 = low8(any2);
  // the index of up to 512 bits; the bits above IW are 0 (set bits are below N <= 2^IW)
  /* verilator lint_off UNUSEDSIGNAL */
  wire [8:0]  full = {s3[2:0], idx2[6*s3[2:0] +: 6]};
  /* verilator lint_on UNUSEDSIGNAL */
  assign any = s3[3];
  assign idx = full[IW-1:0];
endmodule
`default_nettype wire
