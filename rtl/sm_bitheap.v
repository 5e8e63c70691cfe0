`default_nettype none
`include "sm_defs.vh"
// Bit-heap compressor for L independent lanes side by side: the heap of bits of
// weights 2^0 .. 2^(NC-1) (column c holds H0[c] bits of weight 2^c) is reduced to two
// rows whose sum is the heap's sum. Shared by the Hamming popcounts (sm_popcount) and
// the support-weight sums (sm_sw_aggregate). Sized for 6-input LUTs: Dadda-style
// stages cut every column into groups of up to six bits and replace each group by its
// count (one LUT6 per output bit; weights 1, 2, 4 go to this column and the next two),
// until no column holds more than two bits. A binary adder tree costs about the same
// LUTs on carry chains but is several adders deep; here every stage is one LUT level.
// The heap's shape is computed by constant functions from H0, so any heap works.
//
// Bit-plane order: every heap holds bit i of all L lanes together, at [i*L +: L], column
// by column (column 0's bits first). The bits of a column all have the same weight, so
// which of them share a counter is free; the groups of a column take its bits t, t + G,
// ..., t + 5*G. The logic of a lane is the same as with one instance per lane, but every
// stage becomes a few bitwise operations on long vectors, which Verilator evaluates
// word by word (bit by bit and lane by lane, the paper configuration's 128 levels would
// dominate the simulation time).
//
// With REG = 1 the two rows are registered here, where the bits that are always 0 are
// visible (a register outside would keep them). With ADD = 1 the two rows are also added
// here (after the register), for the same reason: which planes of row b can be set, and
// so which carries exist, follows from the heap's final shape, which only this module
// knows; a caller's adder over whole rows would hold wires that are 0 by construction.
module sm_bitheap #(
    parameter NC = 3,                      // columns: the sum is below 2^NC (1..32)
    parameter [32*NC-1:0] H0 = 96'd7,      // bits in column c at [c*32 +: 32]
    parameter L = 1,                       // lanes (1..4096)
    parameter REG = 0,                     // 1: the rows are registered (on ce)
    parameter ADD = 0                      // 1: `sum` is row_a + row_b
) (
    input  wire             clk,    // used only with REG = 1
    input  wire             ce,
    input  wire [HIN*L-1:0] bits,   // column c's bits from the sum of H0[0..c-1] on
    output wire [NC*L-1:0]  row_a,  // bit c of lane l at [c*L + l]
    output wire [NC*L-1:0]  row_b,  // row_a + row_b (modulo 2^NC) = the heap's sum
    // ADD = 1: that sum, bit c of lane l at [c*L + l]; ADD = 0: one bit, 0 (Verilog-2005
    // has no optional ports)
    output wire [SUMW-1:0]  sum
);
  localparam HB  = 32;      // bits per number in the packed shape tables
  localparam NCP = NC + 2;  // columns in the tables; the top two stay empty
  localparam MS  = 16;      // stages in the tables (1,023 bits in a column need 6)

  // Constant functions: they run while the design elaborates, never in simulation, so
  // their statements are no coverage points.
  /* verilator coverage_off */
  // Bits of the input heap (its own function: the port width must not wait for the
  // shape tables).
  function integer h0_total(input [NC*32-1:0] h0);
    integer c;
    begin
      h0_total = 0;
      for (c = 0; c < NC; c = c + 1) h0_total = h0_total + h0[c*32 +: 32];
    end
  endfunction
  localparam HIN = h0_total(H0);

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
  function [MS*NCP*HB-1:0] all_shapes(input [NC*HB-1:0] h0);
    integer k;
    reg [NCP*HB-1:0] h;
    reg [MS*NCP*HB-1:0] t;
    begin
      h = {{(2 * HB) {1'b0}}, h0};
      for (k = 0; k < MS; k = k + 1) begin
        t[k*NCP*HB +: NCP*HB] = h;
        h = shape_next(h);
      end
      all_shapes = t;
    end
  endfunction
  localparam [MS*NCP*HB-1:0] SHAPE = all_shapes(H0);

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

  // Stages until no column holds more than two bits (the last table entry if never).
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
  localparam [HB-1:0] LAST_MAX = max_height(SHAPE, NS);

  function [HB-1:0] max_height(input [MS*NCP*HB-1:0] sh, input integer st);
    integer c;
    begin
      max_height = 0;
      for (c = 0; c < NCP; c = c + 1)
        if (sh[(st*NCP + c)*HB +: HB] > max_height) max_height = sh[(st*NCP + c)*HB +: HB];
    end
  endfunction

  // Start of each stage's heap in one flat vector (in bits per lane): stage s at
  // [(HOFF(s) + bit)*L +: L].
  function integer hoff(input integer st);
    integer k;
    begin
      hoff = 0;
      for (k = 0; k < st; k = k + 1) hoff = hoff + OFFS[(k*NCP + NC)*HB +: HB];
    end
  endfunction

  // A carry into plane f of the final adder can be set: two of plane f-1's row a bit
  // (its column holds 1 or 2 bits), row b bit (it holds 2) and carry in can be.
  function carry_in(input integer f);
    integer k, hf;
    begin
      carry_in = 1'b0;
      for (k = 0; k < f; k = k + 1) begin
        hf       = SHAPE[(NS*NCP + k)*HB +: HB];
        carry_in = (hf >= 2) || (hf == 1 && carry_in);
      end
    end
  endfunction
  /* verilator coverage_on */
  localparam HTOT = hoff(NS + 1);
  localparam SUMW = (ADD != 0) ? NC * L : 1;

  generate
    `SM_BAD_PARAM(g_bad_nc, NC < 1 || NC > 32, ("sm_bitheap: NC (%0d) must be 1..32", NC))
    `SM_BAD_PARAM(g_bad_l, L < 1 || L > 4096, ("sm_bitheap: L (%0d) must be 1..4096", L))
    `SM_BAD_PARAM(g_bad_h0, HIN < 1, ("sm_bitheap: the heap H0 holds no bits"))
    `SM_BAD_PARAM(g_bad_depth, LAST_MAX > 2,
                  ("sm_bitheap: a column of H0 is too tall for %0d stages", MS))
  endgenerate

  // ---- compression stages ---------------------------------------------------------
  // Every stage's heap, column by column, bit-plane order. One flat vector rather than a
  // vector per generate block: only constant slices of it are used, so Verilator can
  // split it (split_var) into one variable per counter output instead of inserting
  // every output into, and extracting every input from, one long vector.
  // Stages 1..NS only: stage 0 is read straight from `bits` (a copy of the whole input
  // into `heap` made Verilator assemble it as one long concatenation every clock).
  // bits of stages 1..NS per lane (2 if there are none: split_var wants a vector)
  localparam HW   = (HTOT - HIN > 0) ? HTOT - HIN : 2;
  localparam HFIN = hoff(NS) - HIN;  // the last stage in `heap` (NS >= 1)
  wire [HW*L-1:0] heap  /*verilator split_var*/;
  genvar s, c, t, j;
  generate
    if (NS == 0) begin : g_no_heap
      assign heap = {HW * L{1'b0}};
      wire unused_heap = |heap;
    end
    for (s = 1; s <= NS; s = s + 1) begin : g_st
      localparam HS = hoff(s) - HIN;      // this stage's heap in `heap`
      localparam HP = hoff(s - 1) - HIN;  // the previous stage's (s >= 2)
      for (c = 0; c < NC; c = c + 1) begin : g_col
        if (SHAPE[((s-1)*NCP + c)*HB +: HB] > 0) begin : g_nz
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
          // Bit b of this column in the previous stage: `bits` for stage 0, else `heap`.
          // Every counter input is one such L-bit plane: an input spanning several
          // planes would make Verilator assemble it from the pieces every clock.
          if (RM <= 2) begin : g_pass
            for (t = 0; t < RM; t = t + 1) begin : g_p
              if (P == 0) begin : g_bits
                assign heap[(HS + Z0 + t)*L +: L] = bits[(IN0 + 6 * G + t)*L +: L];
              end else begin : g_heap
                assign heap[(HS + Z0 + t)*L +: L] = heap[(HP + IN0 + 6 * G + t)*L +: L];
              end
            end
          end
          // Counter t < G (a full group) takes the column's bits j*G + t, j = 0..5; the
          // partial group of RM = 3..5 bits, if any, is counter G with the bits 6*G + j
          // (the missing inputs are 0). Counter t's outputs go to bits O0 + t, O1 + t,
          // O2 + t.
          localparam NGC = G + ((RM >= 3) ? 1 : 0);
          for (t = 0; t < NGC; t = t + 1) begin : g_grp
            for (j = 0; j < 6; j = j + 1) begin : g_in
              localparam BI = (t < G) ? IN0 + j * G + t : IN0 + 6 * G + j;
              wire [L-1:0] v;
              if (t == G && j >= RM) begin : g_zero
                assign v = {L{1'b0}};
              end else if (P == 0) begin : g_bits
                assign v = bits[BI*L +: L];
              end else begin : g_heap
                assign v = heap[(HP + BI)*L +: L];
              end
            end
            // The 6:3 counter, plain logic (an arithmetic "+" would become carry
            // chains; in LUT6 each output is one LUT): three full adders that share
            // the XOR of their first two inputs between sum and carry, the fewest
            // bitwise operations for the simulator.
            wire [L-1:0] x1 = g_in[0].v ^ g_in[1].v;
            wire [L-1:0] s1 = x1 ^ g_in[2].v;
            wire [L-1:0] c1 = (g_in[0].v & g_in[1].v) | (g_in[2].v & x1);
            wire [L-1:0] x2 = g_in[3].v ^ g_in[4].v;
            wire [L-1:0] s2 = x2 ^ g_in[5].v;
            wire [L-1:0] c2 = (g_in[3].v & g_in[4].v) | (g_in[5].v & x2);
            wire [L-1:0] k  = s1 & s2;
            wire [L-1:0] xc = c1 ^ c2;
            wire [L-1:0] w1 = s1 ^ s2;                 // weight 1
            wire [L-1:0] w2 = xc ^ k;                  // weight 2
            wire [L-1:0] w4 = (c1 & c2) | (k & xc);    // weight 4: majority(c1, c2, k)
            assign heap[(HS + O0 + t)*L +: L] = w1;
            if (c + 1 < NC) begin : g_w2
              assign heap[(HS + O1 + t)*L +: L] = w2;
            end else begin : g_no_w2
              wire unused_w2 = |w2;  // weight 2^NC: always 0
            end
            if ((t < G || RM >= 4) && c + 2 < NC) begin : g_w4
              assign heap[(HS + O2 + t)*L +: L] = w4;
            end else begin : g_no_w4
              wire unused_w4 = |w4;  // 3 inputs never reach 4, or weight >= 2^NC
            end
          end
        end
      end
    end
  endgenerate

  // ---- the two rows, and their sum ----------------------------------------------
  // Only the planes the final shape can set are declared (HF bits of column f: row a's
  // plane, then row b's); the others are constant 0 at the ports.
  genvar f;
  generate
    for (f = 0; f < NC; f = f + 1) begin : g_fin
      localparam HF = SHAPE[(NS*NCP + f)*HB +: HB];
      localparam OF = OFFS[(NS*NCP + f)*HB +: HB];
      if (HF == 0) begin : g_none
        assign row_a[f*L +: L] = {L{1'b0}};
        assign row_b[f*L +: L] = {L{1'b0}};
      end else begin : g_set
        wire [HF*L-1:0] fin;
        if (NS == 0) begin : g_in
          assign fin = bits[OF*L +: HF*L];
        end else begin : g_heap
          assign fin = heap[(HFIN + OF)*L +: HF*L];
        end
        wire [HF*L-1:0] rows;
        if (REG != 0) begin : g_reg
          reg [HF*L-1:0] fin_q;
          always @(posedge clk) begin
            if (ce) fin_q <= fin;
          end
          assign rows = fin_q;
        end else begin : g_comb
          assign rows = fin;
        end
        assign row_a[f*L +: L] = rows[0 +: L];
        if (HF == 2) begin : g_two
          assign row_b[f*L +: L] = rows[L +: L];
        end else begin : g_one
          assign row_b[f*L +: L] = {L{1'b0}};
        end
      end
      // The adder: a ripple on whole bit planes (per lane the NC-bit addition modulo 2^NC),
      // one branch per combination of the terms that can be set, so no constant-zero
      // wire: plane f adds row a (HF >= 1), row b (HF = 2) and the carry in (CI); it
      // passes a carry on (CO) only if two of them can be set and plane f + 1 exists.
      if (ADD != 0) begin : g_add
        localparam CI = carry_in(f);
        localparam CO = (f + 1 < NC) && carry_in(f + 1);
        if (HF == 2) begin : g_x
          wire [L-1:0] x = g_set.rows[0 +: L] ^ g_set.rows[L +: L];
        end
        if (HF == 2 && CI) begin : g_abc
          assign sum[f*L +: L] = g_x.x ^ g_fin[f-1].g_add.g_co.co;
        end else if (HF == 2) begin : g_ab
          assign sum[f*L +: L] = g_x.x;
        end else if (HF == 1 && CI) begin : g_ac
          assign sum[f*L +: L] = g_set.rows[0 +: L] ^ g_fin[f-1].g_add.g_co.co;
        end else if (HF == 1) begin : g_a
          assign sum[f*L +: L] = g_set.rows[0 +: L];
        end else if (CI) begin : g_c
          assign sum[f*L +: L] = g_fin[f-1].g_add.g_co.co;
        end else begin : g_zero
          assign sum[f*L +: L] = {L{1'b0}};  // the heap's sum never reaches this plane
        end
        // carry out: HF = 2, or HF = 1 with a carry in (see carry_in)
        if (CO) begin : g_co
          wire [L-1:0] co;
          if (HF == 2 && CI) begin : g_abc
            assign co = (g_set.rows[0 +: L] & g_set.rows[L +: L]) |
                        (g_fin[f-1].g_add.g_co.co & g_x.x);
          end else if (HF == 2) begin : g_ab
            assign co = g_set.rows[0 +: L] & g_set.rows[L +: L];
          end else begin : g_ac
            assign co = g_set.rows[0 +: L] & g_fin[f-1].g_add.g_co.co;
          end
        end
      end
    end
    if (ADD == 0) begin : g_no_sum
      assign sum = 1'b0;
    end
    if (REG == 0) begin : g_no_clk
      wire unused_clk = clk ^ ce;  // combinational heap
    end
  endgenerate
endmodule
`default_nettype wire
