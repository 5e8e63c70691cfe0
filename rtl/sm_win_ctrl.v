`default_nettype none
`include "sm_defs.vh"
// Window controller shared by every windowed stage (docs/algorithm.md, "Streaming
// protocol"). For the beat entering now it names the centre pixel of the stage's
// window -- the beat that entered D_ROWS rows and D_COLS columns earlier -- and says
// which window rows and columns lie inside the centre's frame. Stages apply their own
// border rule with these masks, so frame edges, virtual flush rows and the next
// frame's first rows are all handled in one place.
//
// All outputs are combinational functions of the entering beat and the state; the
// state advances on ce. The stage registers what it needs.
module sm_win_ctrl #(
    parameter MAX_WIDTH = 320,  // widest active line
    parameter D_ROWS    = 7,    // rows between the entering beat and the centre
    parameter D_COLS    = 7,    // columns between the entering beat and the centre
    parameter R_UP      = 7,    // window rows above the centre
    parameter R_DN      = 7,    // window rows below the centre (<= D_ROWS)
    parameter R_L       = 7,    // window columns left of the centre
    parameter R_R       = 7     // window columns right of the centre
) (
    input  wire                    clk,
    input  wire                    rst_n,
    input  wire                    ce,
    input  wire [XW-1:0]           width,     // active width, must exceed D_COLS
    input  wire [`SM_SIDE_W-1:0] s_side,    // sideband of the entering beat
    output wire [XW-1:0]           s_x,       // column of the entering beat
    output wire [`SM_SIDE_W-1:0] c_side,    // sideband of the centre beat
    output wire [XW-1:0]           c_x,       // column of the centre beat
    output wire [R_UP+R_DN:0]      row_ok,    // bit R_UP+j: centre row + j is in the frame
    output wire [R_L+R_R:0]        col_ok     // bit R_L+i: centre column + i is in 0..W-1
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam NT = D_ROWS + R_UP + 2;  // row tags kept: live row back to the oldest window row

  generate
    `SM_BAD_PARAM(g_bad_rdn, R_DN > D_ROWS,
                  ("sm_win_ctrl: R_DN (%0d) must not exceed D_ROWS (%0d)", R_DN, D_ROWS))
    `SM_BAD_PARAM(g_bad_dcols, D_COLS >= MAX_WIDTH,
                  ("sm_win_ctrl: D_COLS (%0d) must be below MAX_WIDTH", D_COLS))
  endgenerate

  // Row tag: {ftag[1:0], first row of frame, real}.
  reg  [3:0]    tag_q [0:NT-1];
  reg  [XW-1:0] col_q;

  wire          in_sol = s_side[`SM_SIDE_SOL];
  wire [3:0]    in_tag = {s_side[`SM_SIDE_TAG], s_side[`SM_SIDE_SOF], s_side[`SM_SIDE_REAL]};
  wire [XW-1:0] col = in_sol ? {XW{1'b0}} : col_q + 1'b1;
  assign s_x = col;

  // Tags of the rows as seen with the entering beat: index 0 is the live row.
  wire [3:0] row_tag [0:NT-1];
  genvar k;
  generate
    for (k = 0; k < NT; k = k + 1) begin : g_rows
      if (k == 0) begin : g_live
        assign row_tag[k] = in_sol ? in_tag : tag_q[0];
      end else begin : g_old
        assign row_tag[k] = in_sol ? tag_q[k-1] : tag_q[k];
      end
    end
  endgenerate

  // The centre is D_COLS beats back in the current row, or at the end of the row
  // before when the current row has not reached D_COLS yet.
  // Parameters overridden by a parent arrive as 32-bit integers; the truncation to the
  // column width is intended (D_COLS < MAX_WIDTH is checked above).
  /* verilator lint_off WIDTH */
  localparam [XW-1:0] DC = D_COLS;
  /* verilator lint_on WIDTH */
  wire          borrow;
  generate
    if (D_COLS == 0) begin : g_no_borrow
      assign borrow = 1'b0;
      assign c_x    = col;
      wire unused_width = &width;  // no wrap into the previous row without D_COLS
    end else begin : g_borrow
      assign borrow = (col < DC);
      assign c_x    = borrow ? col + width - DC : col - DC;
    end
  endgenerate
  wire [3:0]    ctag = borrow ? row_tag[D_ROWS+1] : row_tag[D_ROWS];

  // Rows entered since reset, saturating once the centre's row (and the one before it,
  // for a borrow) is always one of them. The beats before a stream's first SOL (a
  // stage's pipeline fill) are no row: a centre there or in the rows the window still
  // lags by gets no SOL. Otherwise every fill would leave a stub row behind, as long as
  // the fill happened to be, and stages further down would drop a stub shorter than
  // their own D_COLS but keep a longer one: row counts kept from reset on two streams
  // (sm_line_store) then disagree as soon as a stage's latency changes. So every
  // stream's rows are the sequencer's rows, exactly W beats each.
  localparam NR = D_ROWS + 2;  // the count a borrowing centre needs
  localparam RW = `SM_COUNT_W(NR);
  /* verilator lint_off WIDTH */  // small constants in the count's width
  localparam [RW-1:0] NRV = NR;
  localparam [RW-1:0] DR1 = D_ROWS + 1;
  /* verilator lint_on WIDTH */
  reg  [RW-1:0] rows_q;
  wire [RW-1:0] rows = (in_sol && rows_q != NRV) ? rows_q + 1'b1 : rows_q;
  wire          c_row = borrow ? (rows == NRV) : (rows >= DR1);  // the centre's row was entered
  wire          c_sol = c_row && (c_x == {XW{1'b0}});

  // Sideband order as in the spec: {ftag, sol, sof, real}.
  assign c_side = {ctag[3:2], c_sol, ctag[1] && c_sol, ctag[0]};

  genvar j;
  generate
    for (j = 0; j <= R_UP + R_DN; j = j + 1) begin : g_row_ok
      // window row offset o = j - R_UP; its tag index is the centre's minus o
      wire [3:0] t = borrow ? row_tag[D_ROWS + 1 - (j - R_UP)] : row_tag[D_ROWS - (j - R_UP)];
      // t[1] (first row) matters only for the centre's sof
      wire       unused_first = t[1];
      assign row_ok[j] = ctag[0] && t[0] && (t[3:2] == ctag[3:2]);
    end
    for (j = 0; j <= R_L + R_R; j = j + 1) begin : g_col_ok
      // column c_x + (j - R_L) must lie in 0..width-1
      if (j < R_L) begin : g_left
        /* verilator lint_off WIDTH */  // intended truncation of the 32-bit offset
        localparam [XW-1:0] OFF = R_L - j;
        /* verilator lint_on WIDTH */
        assign col_ok[j] = (c_x >= OFF);
      end else begin : g_right
        /* verilator lint_off WIDTH */  // intended truncation of the 32-bit offset
        localparam [XW:0] OFF = j - R_L;
        /* verilator lint_on WIDTH */
        assign col_ok[j] = ({1'b0, c_x} + OFF < {1'b0, width});
      end
    end
  endgenerate

  // The tags move only on a row start (row_tag is tag_q itself on other beats); an
  // update on every ce would be the same flip-flops, but Verilator would copy all NT
  // tags every clock (the rectifiers keep over 40).
  integer n;
  always @(posedge clk) begin
    if (!rst_n) begin
      col_q  <= {XW{1'b0}};
      rows_q <= {RW{1'b0}};
      for (n = 0; n < NT; n = n + 1) tag_q[n] <= 4'd0;
    end else if (ce) begin
      col_q  <= col;
      rows_q <= rows;
      if (in_sol) begin
        tag_q[0] <= in_tag;
        for (n = 1; n < NT; n = n + 1) tag_q[n] <= tag_q[n-1];
      end
    end
  end
endmodule
`default_nettype wire
