`default_nettype none
// Pipelined population count of a ^ b (docs/algorithm.md, section 4: the Hamming
// distance of two census vectors). A plain $countones, or a binary adder tree, costs
// 2-3 LUTs per bit in Yosys; this is a compressor tree sized for 6-input LUTs:
//  - leaves fold the XOR into the first counter: three bit pairs (six inputs) give a
//    2-bit count, one LUT6 per output bit;
//  - then Dadda-style stages on the bit heap: every column is cut into groups of up
//    to six bits and each group is replaced by its count (one LUT6 per output bit,
//    weights 1, 2, 4 go to this column and the next two), until no column holds more
//    than two bits;
//  - a final two-row carry-chain adder.
// The heap's shape is computed by constant functions from N, so any N works.
//
// Latency 2 ce: the leaves are registered, then the compressed and added result.
module sm_popcount #(
    parameter N = 224  // bits to count (1..1023)
) (
    input  wire          clk,
    input  wire          ce,
    input  wire [N-1:0]  a,
    input  wire [N-1:0]  b,
    output wire [OW-1:0] cnt  // popcount(a ^ b), 2 ce after a and b
);
  localparam OW  = $clog2(N + 1);
  localparam NG  = (N + 2) / 3;  // leaf groups of three pairs
  localparam NP  = 3 * NG;       // padded input width
  localparam HB  = 32;           // bits per number in the packed shape tables
  localparam NC  = OW;           // heap columns: a bit of weight 2^OW is always 0
  localparam NCP = NC + 2;       // columns in the tables; the top two stay empty
  localparam MS  = 16;           // stages in the tables (N = 1023 needs 6)

  generate
    if (N < 1 || N > 1023) begin : g_bad_n
      initial $error("sm_popcount: N (%0d) must be 1..1023", N);
    end
  endgenerate

  // ---- heap shape ----------------------------------------------------------------
  // Column heights after one more stage; outputs of weight 2^NC and up are dropped.
  function [NCP*HB-1:0] shape_next(input [NCP*HB-1:0] h);
    integer c, hc, g, r, nch, nch2;
    reg [NCP*HB-1:0] n;
    begin
      n = {NCP * HB{1'b0}};
      for (c = 0; c < NC; c = c + 1) begin
        hc   = h[c*HB +: HB];
        g    = hc / 6;
        r    = hc % 6;
        nch  = g + ((r >= 3) ? 1 : 0);  // groups, each with a weight-1 and weight-2 output
        nch2 = g + ((r >= 4) ? 1 : 0);  // groups with a weight-4 output (4+ inputs)
        if (r <= 2) n[c*HB +: HB] = n[c*HB +: HB] + r;
        n[c*HB +: HB] = n[c*HB +: HB] + nch;
        if (c + 1 < NC) n[(c+1)*HB +: HB] = n[(c+1)*HB +: HB] + nch;
        if (c + 2 < NC) n[(c+2)*HB +: HB] = n[(c+2)*HB +: HB] + nch2;
      end
      shape_next = n;
    end
  endfunction

  // Heights of every stage: stage s, column c at [(s*NCP + c)*HB +: HB].
  function [MS*NCP*HB-1:0] all_shapes(input integer dummy);
    integer k;
    reg [NCP*HB-1:0] h;
    reg [MS*NCP*HB-1:0] t;
    begin
      h = {NCP * HB{1'b0}};
      h[0 +: HB] = NG + dummy;  // leaf bit 0 of every group
      if (NC > 1) h[HB +: HB] = NG;  // leaf bit 1
      for (k = 0; k < MS; k = k + 1) begin
        t[k*NCP*HB +: NCP*HB] = h;
        h = shape_next(h);
      end
      all_shapes = t;
    end
  endfunction
  localparam [MS*NCP*HB-1:0] SHAPE = all_shapes(0);

  // Flat index of the first bit of each column, same layout.
  function [MS*NCP*HB-1:0] all_offsets(input [MS*NCP*HB-1:0] sh);
    integer k, c, o;
    reg [MS*NCP*HB-1:0] t;
    begin
      for (k = 0; k < MS; k = k + 1) begin
        o = 0;
        for (c = 0; c < NCP; c = c + 1) begin
          t[(k*NCP + c)*HB +: HB] = o;
          o = o + sh[(k*NCP + c)*HB +: HB];
        end
      end
      all_offsets = t;
    end
  endfunction
  localparam [MS*NCP*HB-1:0] OFFS = all_offsets(SHAPE);

  // Stages until no column holds more than two bits.
  function integer num_stages(input [MS*NCP*HB-1:0] sh);
    integer k, c, s;
    reg done;
    begin
      s = MS - 1;
      for (k = MS - 1; k >= 0; k = k - 1) begin
        done = 1'b1;
        for (c = 0; c < NCP; c = c + 1) if (sh[(k*NCP + c)*HB +: HB] > 2) done = 1'b0;
        if (done) s = k;
      end
      num_stages = s;
    end
  endfunction
  localparam NS = num_stages(SHAPE);

  // 6:3 counter as plain logic: an arithmetic "+" here would become carry chains.
  function [2:0] count6(input [5:0] v);
    reg s1, c1, s2, c2, k;
    begin
      s1 = v[0] ^ v[1] ^ v[2];
      c1 = (v[0] & v[1]) | (v[0] & v[2]) | (v[1] & v[2]);
      s2 = v[3] ^ v[4] ^ v[5];
      c2 = (v[3] & v[4]) | (v[3] & v[5]) | (v[4] & v[5]);
      k  = s1 & s2;
      count6 = {(c1 & c2) | (c1 & k) | (c2 & k), c1 ^ c2 ^ k, s1 ^ s2};
    end
  endfunction

  // ---- leaves: registered 2-bit counts of three XOR'ed pairs ----------------------
  // Padding bits are equal in a and b, so they XOR to 0.
  wire [NP-1:0] x = {{(NP - N) {1'b0}}, a ^ b};
  reg  [NG-1:0] leaf0_q;  // weight 1 of every group
  reg  [NG-1:0] leaf1_q;  // weight 2
  integer q;
  always @(posedge clk) begin
    if (ce) begin
      for (q = 0; q < NG; q = q + 1) begin
        leaf0_q[q] <= x[3*q] ^ x[3*q+1] ^ x[3*q+2];
        leaf1_q[q] <= (x[3*q] & x[3*q+1]) | (x[3*q] & x[3*q+2]) | (x[3*q+1] & x[3*q+2]);
      end
    end
  end

  // ---- compression stages ---------------------------------------------------------
  genvar s, c, t;
  generate
    for (s = 0; s <= NS; s = s + 1) begin : g_st
      localparam TOT = OFFS[(s*NCP + NC)*HB +: HB];
      wire [TOT-1:0] v;  // the heap after s stages, column by column
      if (s == 0) begin : g_leaf
        if (NC > 1) begin : g_two
          assign v = {leaf1_q, leaf0_q};
        end else begin : g_one
          assign v = leaf0_q;  // N = 1: bit 1 is always 0
          wire unused_leaf1 = |leaf1_q;
        end
      end else begin : g_cmp
        for (c = 0; c < NC; c = c + 1) begin : g_col
          localparam P  = s - 1;  // the stage this one compresses
          localparam HC = SHAPE[(P*NCP + c)*HB +: HB];
          localparam H1 = SHAPE[(P*NCP + c + 1)*HB +: HB];
          localparam H2 = SHAPE[(P*NCP + c + 2)*HB +: HB];
          localparam G  = HC / 6;
          localparam RM = HC % 6;
          localparam NCH  = G + ((RM >= 3) ? 1 : 0);
          localparam NCH1 = H1 / 6 + ((H1 % 6 >= 3) ? 1 : 0);
          localparam NCH2 = H2 / 6 + ((H2 % 6 >= 3) ? 1 : 0);
          localparam PS0  = (HC % 6 <= 2) ? HC % 6 : 0;  // bits passed through
          localparam PS1  = (H1 % 6 <= 2) ? H1 % 6 : 0;
          localparam PS2  = (H2 % 6 <= 2) ? H2 % 6 : 0;
          localparam IN0  = OFFS[(P*NCP + c)*HB +: HB];
          // where this column's outputs land in the next heap: in each column the
          // passed bits come first, then weight-1, -2, -4 outputs of columns c, c-1, c-2
          localparam Z0 = OFFS[(s*NCP + c)*HB +: HB];
          localparam O0 = Z0 + PS0;
          localparam O1 = OFFS[(s*NCP + c + 1)*HB +: HB] + PS1 + NCH1;
          localparam O2 = OFFS[(s*NCP + c + 2)*HB +: HB] + PS2 + NCH2 + NCH1;
          if (RM <= 2) begin : g_pass
            for (t = 0; t < RM; t = t + 1) begin : g_p
              assign v[Z0 + t] = g_st[s-1].v[IN0 + 6 * G + t];
            end
          end
          for (t = 0; t < NCH; t = t + 1) begin : g_grp
            localparam K = (t < G) ? 6 : RM;  // inputs of this group
            wire [5:0] in6;
            if (K == 6) begin : g_full
              assign in6 = g_st[s-1].v[IN0 + 6 * t +: 6];
            end else begin : g_part
              assign in6 = {{(6 - K) {1'b0}}, g_st[s-1].v[IN0 + 6 * t +: K]};
            end
            wire [2:0] cnt3 = count6(in6);
            assign v[O0 + t] = cnt3[0];
            if (c + 1 < NC) begin : g_w2
              assign v[O1 + t] = cnt3[1];
            end else begin : g_no_w2
              wire unused_w2 = cnt3[1];  // weight 2^NC: always 0
            end
            if (K >= 4 && c + 2 < NC) begin : g_w4
              assign v[O2 + t] = cnt3[2];
            end else begin : g_no_w4
              wire unused_w4 = cnt3[2];  // 3 inputs never reach 4, or weight >= 2^NC
            end
          end
        end
      end
    end
  endgenerate

  // ---- final two-row adder ----------------------------------------------------------
  wire [NC-1:0] row_a, row_b;
  genvar f;
  generate
    for (f = 0; f < NC; f = f + 1) begin : g_fin
      localparam HF = SHAPE[(NS*NCP + f)*HB +: HB];
      localparam OF = OFFS[(NS*NCP + f)*HB +: HB];
      if (HF >= 1) begin : g_a
        assign row_a[f] = g_st[NS].v[OF];
      end else begin : g_a0
        assign row_a[f] = 1'b0;
      end
      if (HF >= 2) begin : g_b
        assign row_b[f] = g_st[NS].v[OF + 1];
      end else begin : g_b0
        assign row_b[f] = 1'b0;
      end
    end
  endgenerate
  wire [NC-1:0] sum = row_a + row_b;  // modulo 2^OW: the count fits

  reg [OW-1:0] cnt_q;
  always @(posedge clk) begin
    if (ce) cnt_q <= sum;
  end
  assign cnt = cnt_q;
endmodule
`default_nettype wire
