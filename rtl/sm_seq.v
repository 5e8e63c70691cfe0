`default_nettype none
`include "sm_defs.vh"
// Input sequencer (docs/streams.md): turns the camera's AXI4-Stream video into the
// core's internal beats. Every frame becomes exactly H rows of exactly W beats whatever
// the camera sends; after a complete frame, at each row boundary where no camera pixel
// is waiting, up to FLUSH_ROWS virtual rows (real = 0) push the frame's tail out of the
// pipeline. Camera pixels go through an input FIFO so the camera is not stalled while
// a virtual row is being emitted.
//
// The output beat is a register: a new beat is loaded when the current one is taken
// (ce) or when there is none, so beat_valid never depends on ce. The top drives
// ce = beat_valid && room.
//
// Frame start: when a pixel with tuser reaches the FIFO head between frames, the
// sequencer latches host_width / host_height (the register file's host values), pulses
// frame_start in the same clock (the register file copies its shadow registers at that
// edge, so the shadow width is the new frame's width from its first beat on), and emits
// the pixel as the frame's sof beat. A width change first needs FLUSH_ROWS virtual rows
// of the old width after the previous frame: the sequencer inserts the missing ones
// while the new frame's pixels wait in the FIFO.
module sm_seq #(
    parameter MAX_WIDTH  = 320,  // widest active line
    parameter MAX_HEIGHT = 240,  // tallest active frame
    parameter FLUSH_ROWS = 16,   // virtual rows after a frame (pipeline depth in rows)
    // Input FIFO entries (a power of two). MAX_WIDTH + 32 rounded up holds a virtual
    // row's worth of camera pixels plus the FIFO's own latency and the beat register, so
    // a camera at the frame rate never sees tready low; with a folded datapath (F clocks
    // per beat) that holds while the camera's pixel clock is at most aclk / F: a virtual
    // row then lasts F*W clocks, in which at most W camera pixels arrive (docs/streams.md,
    // "Pacing").
    parameter IN_DEPTH   = 1 << $clog2(MAX_WIDTH + 32)
) (
    input  wire            clk,
    input  wire            rst_n,
    // camera: tdata = {right, left}, tuser = start of frame, tlast = end of line
    input  wire [15:0]     s_axis_tdata,
    input  wire            s_axis_tuser,
    input  wire            s_axis_tlast,
    input  wire            s_axis_tvalid,
    output wire            s_axis_tready,
    // run-time settings (host values, latched at each frame start)
    input  wire            enable,       // 0: whole input frames are dropped
    input  wire [XW-1:0]   host_width,    // 1..MAX_WIDTH (the register file clamps to 16..)
    input  wire [YW-1:0]   host_height,   // 1..MAX_HEIGHT
    output wire            frame_start,  // the register file updates its shadow copy
    // internal beats
    input  wire            ce,
    output reg             beat_valid,
    output reg  [`SM_SIDE_W-1:0] beat_side,
    output reg  [7:0]      beat_left,
    output reg  [7:0]      beat_right,
    // one-clock fault pulses, ERR_FLAGS bit order: short line, long line, missing sof,
    // extra sof, too few lines, too many lines
    output reg  [5:0]      err_pulse,
    output wire [LEVEL_W-1:0] in_level  // input FIFO entries (the camera's backlog)
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam YW = `SM_COUNT_W(MAX_HEIGHT);
  localparam FW = $clog2(FLUSH_ROWS + 1);
  localparam LEVEL_W  = $clog2(IN_DEPTH) + 1;
  localparam [FW-1:0] FR = FLUSH_ROWS[FW-1:0];
  localparam integer MAX_WIDTH1  = MAX_WIDTH - 1;
  localparam integer MAX_HEIGHT1 = MAX_HEIGHT - 1;

  localparam E_SHORT = 0, E_LONG = 1, E_MISSING = 2, E_EXTRA = 3, E_FEW = 4, E_MANY = 5;
  localparam [1:0] M_IDLE = 2'd0, M_FRAME = 2'd1, M_VROW = 2'd2;

  generate
    `SM_BAD_PARAM(g_bad_size, MAX_WIDTH < 16 || MAX_HEIGHT < 1,
                  ("sm_seq: MAX_WIDTH (%0d) must be >= 16, MAX_HEIGHT >= 1", MAX_WIDTH))
    `SM_BAD_PARAM(g_bad_depth, IN_DEPTH < MAX_WIDTH + 32 || (1 << $clog2(IN_DEPTH)) != IN_DEPTH,
                  ("sm_seq: IN_DEPTH (%0d) must be a power of two >= MAX_WIDTH + 32", IN_DEPTH))
    `SM_BAD_PARAM(g_bad_flush, FLUSH_ROWS < 1,
                  ("sm_seq: FLUSH_ROWS (%0d) must be >= 1", FLUSH_ROWS))
  endgenerate

  // ---- input FIFO: {tuser, tlast, tdata}
  wire        h_valid;
  wire [17:0] h_word;
  wire        fifo_full;
  wire        pop;
  sm_fifo #(
      .DATA_W(18),
      .DEPTH (IN_DEPTH)
  ) u_in_fifo (
      .clk       (clk),
      .rst_n     (rst_n),
      .wr_en     (s_axis_tvalid),
      .din       ({s_axis_tuser, s_axis_tlast, s_axis_tdata}),
      .full      (fifo_full),
      .rd_en     (pop),
      .dout      (h_word),
      .dout_valid(h_valid),
      .level     (in_level)
  );
  // Not ready while in reset: a pixel handed over then would be dropped by the FIFO's
  // reset, and a source that counts handshakes would count it. rst_n is a register in
  // sm_top, so ready still does not depend on any input combinationally.
  assign s_axis_tready = rst_n && !fifo_full;
  wire        h_user = h_word[17];
  wire        h_last = h_word[16];
  wire [15:0] h_data = h_word[15:0];

  // ---- state
  reg [1:0]    mode_q;
  reg [XW-1:0] x_q;
  reg [YW-1:0] y_q;
  reg [XW-1:0] w_q;          // width of the current / last frame (virtual rows use it)
  // w_q - 1 and the frame's height - 1, loaded at the frame start: the last-column /
  // last-row tests are then plain compares, not a subtract followed by a compare (at
  // 640 columns that chain was the sequencer's one path above 8 LUT levels)
  reg [XW-1:0] wm1_q;
  reg [YW-1:0] hm1_q;
  reg [1:0]    ftag_q;
  reg [FW-1:0] flushed_q;    // virtual rows since the last frame, saturating at FLUSH_ROWS
  reg          pad_row_q;    // short line: rest of the row is zeros
  reg          pad_frame_q;  // early sof: rest of the frame is zeros
  reg          drop_line_q;  // long line: discard up to tlast
  reg          dropping_q;   // discarding up to the next tuser (already reported)
  reg          after_frame_q;  // a frame has completed since reset (fault classification)

  wire adv = !beat_valid || ce;  // the beat register takes a new beat this clock

  // Discarding the rest of a long line runs at one entry per clock, beats or not.
  wire drop_pop = drop_line_q && h_valid && !h_user;
  wire drop_end = drop_line_q && h_valid && (h_user || h_last);

  wire flush_due = (flushed_q < FR);
  wire idle      = (mode_q == M_IDLE) && !drop_line_q;
  wire idle_sof  = idle && h_valid && h_user;
  wire idle_off  = idle_sof && !enable;                 // disabled: drop the frame silently
  wire idle_wflush = idle_sof && enable && (host_width != w_q) && flush_due;
  wire idle_start  = idle_sof && enable && !idle_wflush;
  wire idle_junk   = idle && h_valid && !h_user;        // no frame open: drop until tuser
  wire idle_vrow   = idle && ((!h_valid && flush_due) || idle_wflush);

  // The frame's pixel path; a frame start takes its first pixel in the same clock.
  wire          in_frame  = (mode_q == M_FRAME) && !drop_line_q;
  wire          pad       = in_frame && (pad_row_q || pad_frame_q);
  wire          fr_head   = in_frame && !pad && h_valid;
  wire          sof_break = fr_head && h_user;        // tuser inside an open frame
  wire          take_pix  = idle_start || (fr_head && !h_user);
  wire          real_beat = take_pix || pad || sof_break;
  wire [XW-1:0] ex   = idle_start ? {XW{1'b0}} : x_q;
  wire [YW-1:0] ey   = idle_start ? {YW{1'b0}} : y_q;
  wire [1:0]    etag = idle_start ? ftag_q + 2'd1 : ftag_q;
  // (ex == width - 1): a frame start has ex = 0, so then the test is width == 1
  wire          last_col = idle_start ? (host_width == {{(XW-1){1'b0}}, 1'b1}) : (x_q == wm1_q);
  wire          last_row = idle_start ? (host_height == {{(YW-1){1'b0}}, 1'b1}) : (y_q == hm1_q);

  wire          vbeat = idle_vrow || (mode_q == M_VROW);
  wire [XW-1:0] vx    = idle_vrow ? {XW{1'b0}} : x_q;
  wire          vlast = idle_vrow ? (w_q == {{(XW-1){1'b0}}, 1'b1}) : (x_q == wm1_q);

  assign pop = (take_pix && adv) || drop_pop || idle_off || idle_junk;
  assign frame_start = idle_start && adv;

  always @(posedge clk) begin
    if (adv) begin
      beat_left  <= take_pix ? h_data[7:0] : 8'd0;
      beat_right <= take_pix ? h_data[15:8] : 8'd0;
    end
  end

  always @(posedge clk) begin
    if (!rst_n) begin
      mode_q        <= M_IDLE;
      x_q           <= {XW{1'b0}};
      y_q           <= {YW{1'b0}};
      w_q           <= MAX_WIDTH[XW-1:0];
      wm1_q         <= MAX_WIDTH1[XW-1:0];
      hm1_q         <= MAX_HEIGHT1[YW-1:0];
      ftag_q        <= 2'd3;  // the first frame gets ftag 0
      flushed_q     <= FR;    // nothing to flush after reset
      pad_row_q     <= 1'b0;
      pad_frame_q   <= 1'b0;
      drop_line_q   <= 1'b0;
      dropping_q    <= 1'b0;
      after_frame_q <= 1'b0;
      beat_valid    <= 1'b0;
      beat_side     <= {`SM_SIDE_W{1'b0}};
      err_pulse     <= 6'd0;
    end else begin
      err_pulse <= 6'd0;
      if (drop_end) drop_line_q <= 1'b0;
      if (idle_off) dropping_q <= 1'b1;
      if (idle_junk) begin
        dropping_q <= 1'b1;
        // A camera that starts mid-frame vs. one sending extra lines: only the history
        // tells them apart (docs/streams.md).
        if (!dropping_q) err_pulse[after_frame_q ? E_MANY : E_MISSING] <= 1'b1;
      end
      if (adv) begin
        beat_valid <= real_beat || vbeat;
        if (real_beat) begin
          beat_side[`SM_SIDE_TAG]  <= etag;
          beat_side[`SM_SIDE_SOL]  <= (ex == {XW{1'b0}});
          beat_side[`SM_SIDE_SOF]  <= (ex == {XW{1'b0}}) && (ey == {YW{1'b0}});
          beat_side[`SM_SIDE_REAL] <= 1'b1;
          if (idle_start) begin
            mode_q     <= M_FRAME;
            w_q        <= host_width;
            wm1_q      <= host_width - 1'b1;
            hm1_q      <= host_height - 1'b1;
            ftag_q     <= ftag_q + 2'd1;
            dropping_q <= 1'b0;
          end
          if (sof_break) begin
            pad_frame_q <= 1'b1;
            err_pulse[(x_q == {XW{1'b0}}) ? E_FEW : E_EXTRA] <= 1'b1;
          end
          if (take_pix && h_last && !last_col) begin
            pad_row_q <= 1'b1;
            err_pulse[E_SHORT] <= 1'b1;
          end
          if (take_pix && !h_last && last_col) begin
            drop_line_q <= 1'b1;
            err_pulse[E_LONG] <= 1'b1;
          end
          if (last_col) begin
            x_q       <= {XW{1'b0}};
            pad_row_q <= 1'b0;
            if (last_row) begin
              y_q           <= {YW{1'b0}};
              mode_q        <= M_IDLE;
              pad_frame_q   <= 1'b0;
              after_frame_q <= 1'b1;
              flushed_q     <= {FW{1'b0}};
            end else begin
              y_q <= ey + 1'b1;
            end
          end else begin
            x_q <= ex + 1'b1;
          end
        end else if (vbeat) begin
          beat_side[`SM_SIDE_TAG]  <= ftag_q;
          beat_side[`SM_SIDE_SOL]  <= (vx == {XW{1'b0}});
          beat_side[`SM_SIDE_SOF]  <= 1'b0;
          beat_side[`SM_SIDE_REAL] <= 1'b0;
          if (vlast) begin
            x_q       <= {XW{1'b0}};
            mode_q    <= M_IDLE;
            flushed_q <= flushed_q + 1'b1;
          end else begin
            x_q    <= vx + 1'b1;
            mode_q <= M_VROW;
          end
        end
      end
    end
  end

`ifndef SYNTHESIS
  // Simulation-only invariants (Verilator --assert builds): the top's ce contract, the
  // beat register holding still until taken, and no pop of an empty FIFO head.
  reg         chk_hold_q;
  reg [20:0]  chk_beat_q;
  always @(posedge clk) begin
    chk_hold_q <= rst_n && beat_valid && !ce;
    chk_beat_q <= {beat_side, beat_left, beat_right};
    if (rst_n) begin
      if (ce && !beat_valid) $error("sm_seq: ce without a beat");
      if (pop && !h_valid) $error("sm_seq: pop of an empty input FIFO");
      if (chk_hold_q && (!beat_valid || chk_beat_q != {beat_side, beat_left, beat_right}))
        $error("sm_seq: beat changed before it was taken");
    end
  end
`endif
endmodule
`default_nettype wire
