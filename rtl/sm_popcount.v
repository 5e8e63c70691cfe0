`default_nettype none
// Pipelined population count of a ^ b (docs/algorithm.md, section 4: the Hamming
// distance of two census vectors), for L independent lanes side by side (sm_cost: one
// lane per disparity level). A plain $countones, or a binary adder tree, costs 2-3 LUTs
// per bit in Yosys; this is a compressor tree sized for 6-input LUTs, one per lane:
//  - leaves fold the XOR into the first counter: three bit pairs (six inputs) give a
//    2-bit count, one LUT6 per output bit;
//  - then Dadda-style stages on the bit heap: every column is cut into groups of up
//    to six bits and each group is replaced by its count (one LUT6 per output bit,
//    weights 1, 2, 4 go to this column and the next two), until no column holds more
//    than two bits;
//  - a final two-row adder, a ripple of full adders on whole bit planes.
// The counts come out in bit-plane order too (sm_plane2lane puts them in lane order).
// The heap's shape is computed by constant functions from N, so any N works.
//
// Bit-plane order: the inputs and every heap hold bit i of all L lanes together, at
// [i*L +: L] (for L = 1 that is the plain order). The bits of a heap column all have
// the same weight, so which of them share a counter is free; the groups of a column
// take its bits t, t + G, ..., t + 5*G, and the leaves the input bits q, q + NG,
// q + 2*NG. The logic of a lane is the same as with one instance per lane and
// consecutive bits per counter, but every stage becomes a few bitwise operations on
// long vectors, which Verilator evaluates word by word (bit by bit and lane by lane,
// the paper configuration's 128 levels made sm_cost ~2/3 of the simulation time).
//
// Latency 2 ce: the two rows left after compression are registered, then their sum.
module sm_popcount #(
    parameter N = 224,  // bits to count (1..1023)
    parameter L = 1     // lanes (1..1024)
) (
    input  wire            clk,
    input  wire            ce,
    input  wire [N*L-1:0]  a,    // bit i of lane l at [i*L + l]
    input  wire [N*L-1:0]  b,
    output wire [OW*L-1:0] cnt   // bit f of lane l at [f*L + l]: popcount(a ^ b), 2 ce later
);
  localparam OW  = $clog2(N + 1);
  localparam NG  = (N + 2) / 3;  // leaf groups of three pairs
  localparam HB  = 32;           // bits per number in the packed shape tables
  localparam NC  = OW;           // heap columns: a bit of weight 2^OW is always 0
  localparam NCP = NC + 2;       // columns in the tables; the top two stay empty
  localparam MS  = 16;           // stages in the tables (N = 1023 needs 6)

  generate
    if (N < 1 || N > 1023) begin : g_bad_n
      initial $error("sm_popcount: N (%0d) must be 1..1023", N);
    end
    if (L < 1 || L > 1024) begin : g_bad_l
      initial $error("sm_popcount: L (%0d) must be 1..1024", L);
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

  // Start of each stage's heap in one flat vector (in bits per lane): stage s at
  // [(HOFF(s) + bit)*L +: L].
  function integer hoff(input integer st);
    integer k;
    begin
      hoff = 0;
      for (k = 0; k < st; k = k + 1) hoff = hoff + OFFS[(k*NCP + NC)*HB +: HB];
    end
  endfunction
  localparam HTOT = hoff(NS + 1);

  // ---- leaves: 2-bit counts of three XOR'ed pairs ----------------------------------
  // Group q takes input bits q, q + NG and q + 2*NG (bits past N count as 0). The
  // leaves are not registered: at 6-input LUTs, leaves and compression stages are 1 + NS
  // levels (5 for N = 225), and the two rows left after them are 2*OW bits a lane
  // against 2*NG leaf bits (the paper configuration's 128 lanes: 2,048 flip-flops
  // instead of 19,200).
  // x_q: input bits q*NG .. q*NG + NG - 1 of a ^ b, zero past N. Formed group by group
  // rather than as one padded a ^ b that is then sliced: Verilator copies every
  // intermediate long vector, and the leaves are the widest stage.
  genvar q;
  generate
    for (q = 0; q < 3; q = q + 1) begin : g_x
      localparam NR = (N - q * NG >= NG) ? NG : (N - q * NG > 0) ? N - q * NG : 0;
      wire [NG*L-1:0] xk;
      if (NR == NG) begin : g_full
        assign xk = a[q*NG*L +: NG*L] ^ b[q*NG*L +: NG*L];
      end else if (NR > 0) begin : g_part
        assign xk = {{((NG - NR) * L) {1'b0}}, a[q*NG*L +: NR*L] ^ b[q*NG*L +: NR*L]};
      end else begin : g_none
        assign xk = {NG * L{1'b0}};
      end
    end
  endgenerate
  wire [NG*L-1:0] x0 = g_x[0].xk;
  wire [NG*L-1:0] x1 = g_x[1].xk;
  wire [NG*L-1:0] x2 = g_x[2].xk;
  wire [NG*L-1:0] leaf0 = x0 ^ x1 ^ x2;  // weight 1 of every group
  wire [NG*L-1:0] leaf1 = (x0 & x1) | (x0 & x2) | (x1 & x2);  // weight 2

  // ---- compression stages ---------------------------------------------------------
  // A 6:3 counter is plain logic (an arithmetic "+" would become carry chains):
  //   s1, c1 = sum and carry of inputs 0..2; s2, c2 = of inputs 3..5; k = s1 & s2;
  //   weight 1 = s1 ^ s2, weight 2 = c1 ^ c2 ^ k, weight 4 = majority(c1, c2, k).
  //
  // Every stage's heap, column by column, bit-plane order. One flat vector rather than a
  // vector per generate block: only constant slices of it are used, so Verilator can
  // split it (split_var) into one variable per counter output instead of inserting
  // every output into, and extracting every input from, one long vector.
  wire [HTOT*L-1:0] heap  /*verilator split_var*/;
  genvar s, c, t;
  generate
    for (s = 0; s <= NS; s = s + 1) begin : g_st
      localparam HS = hoff(s);      // this stage's heap in `heap`
      localparam HP = hoff(s - 1);  // the previous stage's (s >= 1)
      if (s == 0) begin : g_leaf
        if (NC > 1) begin : g_two
          assign heap[HS*L +: NG*L]      = leaf0;
          assign heap[(HS+NG)*L +: NG*L] = leaf1;
        end else begin : g_one
          assign heap[HS*L +: NG*L] = leaf0;  // N = 1: bit 1 is always 0
          wire unused_leaf1 = |leaf1;
        end
      end else begin : g_cmp
        for (c = 0; c < NC; c = c + 1) begin : g_col
          localparam P  = s - 1;  // the stage this one compresses
          localparam HC = SHAPE[(P*NCP + c)*HB +: HB];
          localparam H1 = SHAPE[(P*NCP + c + 1)*HB +: HB];
          localparam H2 = SHAPE[(P*NCP + c + 2)*HB +: HB];
          localparam G  = HC / 6;
          localparam RM = HC % 6;
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
              assign heap[(HS + Z0 + t)*L +: L] = heap[(HP + IN0 + 6 * G + t)*L +: L];
            end
          end
          // The G full groups: input j of group t is bit IN0 + j*G + t; the outputs of
          // group t go to bits O0 + t, O1 + t, O2 + t.
          if (G > 0) begin : g_full
            localparam GL = G * L;
            wire [GL-1:0] i0 = heap[(HP + IN0        )*L +: GL];
            wire [GL-1:0] i1 = heap[(HP + IN0 +     G)*L +: GL];
            wire [GL-1:0] i2 = heap[(HP + IN0 + 2 * G)*L +: GL];
            wire [GL-1:0] i3 = heap[(HP + IN0 + 3 * G)*L +: GL];
            wire [GL-1:0] i4 = heap[(HP + IN0 + 4 * G)*L +: GL];
            wire [GL-1:0] i5 = heap[(HP + IN0 + 5 * G)*L +: GL];
            wire [GL-1:0] s1 = i0 ^ i1 ^ i2;
            wire [GL-1:0] c1 = (i0 & i1) | (i0 & i2) | (i1 & i2);
            wire [GL-1:0] s2 = i3 ^ i4 ^ i5;
            wire [GL-1:0] c2 = (i3 & i4) | (i3 & i5) | (i4 & i5);
            wire [GL-1:0] k  = s1 & s2;
            assign heap[(HS + O0)*L +: GL] = s1 ^ s2;
            if (c + 1 < NC) begin : g_w2
              assign heap[(HS + O1)*L +: GL] = c1 ^ c2 ^ k;
            end else begin : g_no_w2
              wire unused_w2 = |(c1 ^ c2 ^ k);  // weight 2^NC: always 0
            end
            if (c + 2 < NC) begin : g_w4
              assign heap[(HS + O2)*L +: GL] = (c1 & c2) | (c1 & k) | (c2 & k);
            end else begin : g_no_w4
              wire unused_w4 = |((c1 & c2) | (c1 & k) | (c2 & k));  // weight >= 2^NC
            end
          end
          // The partial group of RM = 3..5 bits, if any (bits IN0 + 6*G onwards; the
          // missing inputs are 0); its outputs go to bits O0 + G, O1 + G, O2 + G.
          if (RM >= 3) begin : g_part
            wire [6*L-1:0] in6 = {{((6 - RM) * L) {1'b0}},
                                  heap[(HP + IN0 + 6 * G)*L +: RM*L]};
            wire [L-1:0] i0 = in6[0 +: L];
            wire [L-1:0] i1 = in6[L +: L];
            wire [L-1:0] i2 = in6[2*L +: L];
            wire [L-1:0] i3 = in6[3*L +: L];
            wire [L-1:0] i4 = in6[4*L +: L];
            wire [L-1:0] i5 = in6[5*L +: L];
            wire [L-1:0] s1 = i0 ^ i1 ^ i2;
            wire [L-1:0] c1 = (i0 & i1) | (i0 & i2) | (i1 & i2);
            wire [L-1:0] s2 = i3 ^ i4 ^ i5;
            wire [L-1:0] c2 = (i3 & i4) | (i3 & i5) | (i4 & i5);
            wire [L-1:0] k  = s1 & s2;
            assign heap[(HS + O0 + G)*L +: L] = s1 ^ s2;
            if (c + 1 < NC) begin : g_w2
              assign heap[(HS + O1 + G)*L +: L] = c1 ^ c2 ^ k;
            end else begin : g_no_w2
              wire unused_w2 = |(c1 ^ c2 ^ k);  // weight 2^NC: always 0
            end
            if (RM >= 4 && c + 2 < NC) begin : g_w4
              assign heap[(HS + O2 + G)*L +: L] = (c1 & c2) | (c1 & k) | (c2 & k);
            end else begin : g_no_w4
              // 3 inputs never reach 4, or weight >= 2^NC
              wire unused_w4 = |((c1 & c2) | (c1 & k) | (c2 & k));
            end
          end
        end
      end
    end
  endgenerate

  // ---- final two-row adder ------------------------------------------------------
  localparam HFIN = hoff(NS);  // the last stage's heap: the two rows
  wire [NC*L-1:0] row_a, row_b;  // bit-plane order
  genvar f;
  generate
    for (f = 0; f < NC; f = f + 1) begin : g_fin
      localparam HF = SHAPE[(NS*NCP + f)*HB +: HB];
      localparam OF = OFFS[(NS*NCP + f)*HB +: HB];
      if (HF >= 1) begin : g_a
        assign row_a[f*L +: L] = heap[(HFIN + OF)*L +: L];
      end else begin : g_a0
        assign row_a[f*L +: L] = {L{1'b0}};
      end
      if (HF >= 2) begin : g_b
        assign row_b[f*L +: L] = heap[(HFIN + OF + 1)*L +: L];
      end else begin : g_b0
        assign row_b[f*L +: L] = {L{1'b0}};
      end
    end
  endgenerate
  // The pipeline register: two rows of OW bits a lane.
  reg [NC*L-1:0] row_a_q, row_b_q;
  always @(posedge clk) begin
    if (ce) begin
      row_a_q <= row_a;
      row_b_q <= row_b;
    end
  end
  // The two rows are added in bit-plane order, a ripple of full adders on whole planes
  // (modulo 2^OW: the count fits): per lane the same OW-bit addition as a lane-order
  // "+", but Verilator evaluates it L lanes per word.
  wire [NC*L-1:0] sum_p;  // bit-plane order
  generate
    for (f = 0; f < NC; f = f + 1) begin : g_add
      wire [L-1:0] pa = row_a_q[f*L +: L];
      wire [L-1:0] pb = row_b_q[f*L +: L];
      wire [L-1:0] pc;  // carry into plane f
      if (f == 0) begin : g_c0
        assign pc = {L{1'b0}};
      end else begin : g_cn
        assign pc = g_add[f-1].co;
      end
      wire [L-1:0] co = (pa & pb) | (pa & pc) | (pb & pc);
      assign sum_p[f*L +: L] = pa ^ pb ^ pc;
    end
  endgenerate
  wire unused_co = |g_add[NC-1].co;  // carry out of the top plane: the count fits OW bits

  reg [OW*L-1:0] cnt_q;
  always @(posedge clk) begin
    if (ce) cnt_q <= sum_p;
  end
  assign cnt = cnt_q;
endmodule
`default_nettype wire
