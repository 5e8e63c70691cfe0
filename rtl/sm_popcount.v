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
  localparam OW = $clog2(N + 1);
  localparam NG = (N + 2) / 3;  // leaf groups of three pairs
  localparam NP = 3 * NG;       // padded input width
  localparam HB = 32;           // bits per column height in the packed shape vectors
  localparam NC = 24;           // heap columns tracked (carries above OW are always 0)

  generate
    if (N < 1 || N > 1023) begin : g_bad_n
      initial $error("sm_popcount: N (%0d) must be 1..1023", N);
    end
  endgenerate

  // ---- heap shape: packed column heights, HB bits per column ---------------------
  function [NC*HB-1:0] shape_next(input [NC*HB-1:0] h);
    integer c, hc, g, r, nch, nch2;
    reg [NC*HB-1:0] n;
    begin
      n = {NC * HB{1'b0}};
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

  function [NC*HB-1:0] shape_at(input integer s);
    integer k;
    reg [NC*HB-1:0] h;
    begin
      h = {NC * HB{1'b0}};
      h[0 +: HB]  = NG;  // leaf bit 0 of every group
      h[HB +: HB] = NG;  // leaf bit 1
      for (k = 0; k < s; k = k + 1) h = shape_next(h);
      shape_at = h;
    end
  endfunction

  function integer max_height(input [NC*HB-1:0] h);
    integer c, m;
    begin
      m = 0;
      for (c = 0; c < NC; c = c + 1) if (h[c*HB +: HB] > m) m = h[c*HB +: HB];
      max_height = m;
    end
  endfunction

  function integer num_stages(input integer dummy);
    integer k, s;
    reg [NC*HB-1:0] h;
    begin
      h = shape_at(0);
      s = dummy;
      for (k = 0; k < 32; k = k + 1)
        if (max_height(h) > 2) begin
          h = shape_next(h);
          s = s + 1;
        end
      num_stages = s;
    end
  endfunction

  function integer height(input integer s, input integer c);
    reg [NC*HB-1:0] h;
    begin
      h = shape_at(s);
      height = (c >= 0 && c < NC) ? h[c*HB +: HB] : 0;
    end
  endfunction

  // flat index of the first bit of column c at stage s
  function integer offset(input integer s, input integer c);
    integer k, o;
    begin
      o = 0;
      for (k = 0; k < c; k = k + 1) o = o + height(s, k);
      offset = o;
    end
  endfunction

  function [2:0] count6(input [5:0] v);
    count6 = {2'b0, v[0]} + {2'b0, v[1]} + {2'b0, v[2]} + {2'b0, v[3]} + {2'b0, v[4]}
           + {2'b0, v[5]};
  endfunction

  localparam NS = num_stages(0);

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
      localparam TOT = offset(s, NC);
      wire [TOT-1:0] v;  // the heap after s stages, column by column
      if (s == 0) begin : g_leaf
        assign v = {leaf1_q, leaf0_q};
      end else begin : g_cmp
        for (c = 0; c < NC; c = c + 1) begin : g_col
          localparam HC   = height(s - 1, c);
          localparam G    = HC / 6;
          localparam RM   = HC % 6;
          localparam NCH  = G + ((RM >= 3) ? 1 : 0);
          localparam IN0  = offset(s - 1, c);
          // where this column's outputs land in the next heap
          localparam PASS0 = (height(s - 1, c) % 6 <= 2) ? height(s - 1, c) % 6 : 0;
          localparam PASS1 = (height(s - 1, c + 1) % 6 <= 2) ? height(s - 1, c + 1) % 6 : 0;
          localparam PASS2 = (height(s - 1, c + 2) % 6 <= 2) ? height(s - 1, c + 2) % 6 : 0;
          localparam NCH1  = height(s - 1, c + 1) / 6 + ((height(s - 1, c + 1) % 6 >= 3) ? 1 : 0);
          localparam NCH2  = height(s - 1, c + 2) / 6 + ((height(s - 1, c + 2) % 6 >= 3) ? 1 : 0);
          localparam O0 = offset(s, c) + PASS0;                 // weight-1 outputs
          localparam O1 = offset(s, c + 1) + PASS1 + NCH1;      // weight-2 outputs
          localparam O2 = offset(s, c + 2) + PASS2 + NCH2 + NCH1;  // weight-4 outputs
          if (RM <= 2) begin : g_pass
            for (t = 0; t < RM; t = t + 1) begin : g_p
              assign v[offset(s, c) + t] = g_st[s-1].v[IN0 + 6 * G + t];
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
            end
            if (K >= 4 && c + 2 < NC) begin : g_w4
              assign v[O2 + t] = cnt3[2];
            end else begin : g_no_w4
              wire unused_w4 = cnt3[2];  // 3 inputs never reach 4
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
      localparam HF = height(NS, f);
      localparam OF = offset(NS, f);
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
  wire [NC-1:0] sum = row_a + row_b;
  wire unused_sum_top = |sum[NC-1:OW];  // the count fits OW bits

  reg [OW-1:0] cnt_q;
  always @(posedge clk) begin
    if (ce) cnt_q <= sum[OW-1:0];
  end
  assign cnt = cnt_q;
endmodule
`default_nettype wire
