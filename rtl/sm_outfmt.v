`default_nettype none
`include "sm_defs.vh"
// Output formatter (docs/streams.md): at each ce it takes the last stage's beat, keeps
// the real ones and queues them as the AXI4-Stream video output (the 32-bit word of
// docs/algorithm.md 9.4, bit 31 = valid; tuser on the frame's first pixel, tlast at x == W-1). The FIFO
// absorbs sink back-pressure; `room` tells the top whether one more ce is safe, so the
// top drives ce = beat_valid && room and no beat is ever lost.
//
// Reset: rst_n is the output's own reset (aresetn: the sink is reset with it), so
// m_axis_tvalid is low from the first edge that samples it low. `restart` is the
// pipeline's reset without the output's (CONTROL.SOFT_RESET): the sink is not reset, so
// the frame it is receiving -- the one whose tuser beat it has taken or is offered -- is
// delivered whole: its queued pixels, then invalid pixels (tdata = 0) for the ones the
// abandoned pipeline will not deliver. Every other queued beat is dropped unseen, and
// the pipeline delivers again once the FIFO is empty (docs/streams.md, "Soft reset").
module sm_outfmt #(
    parameter MAX_WIDTH  = 320,  // widest active line
    parameter MAX_HEIGHT = 240,  // tallest active frame
    parameter FIFO_DEPTH = 256   // output FIFO RAM entries (power of two); holds +1
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          restart,       // the pipeline is in reset (level)
    input  wire          ce,
    input  wire [XW-1:0] width,         // active width (shadow), latched at each sof
    input  wire [YW-1:0] height,        // the height of the frame whose sof enters next
    input  wire [`SM_SIDE_W-1:0] in_side,       // last stage's beat
    input  wire [31:0]   in_word,       // the output word (docs/algorithm.md 9.4)
    output wire [31:0]   m_axis_tdata,
    output wire          m_axis_tuser,
    output wire          m_axis_tlast,
    output wire          m_axis_tvalid,
    input  wire          m_axis_tready,
    output reg           room,          // the FIFO can take the beat of one more ce
    output reg           err_overflow   // pulse: a real beat met a full FIFO and was lost
);
  localparam XW = `SM_COUNT_W(MAX_WIDTH);
  localparam YW = `SM_COUNT_W(MAX_HEIGHT);
  localparam LW = $clog2(FIFO_DEPTH) + 1;
  localparam [LW-1:0] CAP = FIFO_DEPTH[LW-1:0];  // level at which one more write still fits

  wire          in_real = in_side[`SM_SIDE_REAL];
  wire          in_sof  = in_side[`SM_SIDE_SOF];
  wire          in_sol  = in_side[`SM_SIDE_SOL];
  wire [1:0]    unused_ftag = in_side[`SM_SIDE_TAG];

  // Write side: position of the last queued pixel of the current frame.
  reg  [XW-1:0] x_q;
  reg  [YW-1:0] y_q;
  reg  [XW-1:0] w_q;
  reg  [YW-1:0] h_q;
  reg           xlast_q;  // the last queued pixel ended its row
  reg           open_q;   // a frame is partly queued
  reg           pad_q;    // completing the sink's frame with invalid pixels
  // Soft-reset flush: until the FIFO is empty, beats outside the sink's frame are dropped
  // and the pipeline is held (room low).
  reg           flush_q;
  reg           keep_q;   // the sink's frame is still being delivered
  reg           rd_open_q;  // the sink has taken a tuser beat and not yet its last pixel
  reg  [LW-1:0] eofs_q;   // frames whose last pixel is queued
  wire          full;
  wire [LW-1:0] level;
  wire [34:0]   head;  // {last pixel of the frame, tuser, tlast, tdata}
  wire          fifo_valid;
  wire          pad_wr = pad_q && !full;
  wire          wr_in = ce && in_real;
  wire          wr = wr_in || pad_wr;  // ce is low while padding (room)
  wire          drop = flush_q && !keep_q;
  assign        m_axis_tvalid = fifo_valid && !drop;
  wire          rd = m_axis_tvalid && m_axis_tready;
  wire          pop = rd || (drop && fifo_valid);

  wire          sof = wr_in && in_sof;
  wire          new_row = pad_q ? xlast_q : in_sol;
  wire [XW-1:0] x     = new_row ? {XW{1'b0}} : x_q + 1'b1;
  wire [YW-1:0] y     = sof ? {YW{1'b0}} : new_row ? y_q + 1'b1 : y_q;
  wire [XW-1:0] cur_w = sof ? width : w_q;
  wire [YW-1:0] cur_h = sof ? height : h_q;
  wire          tlast = (x == cur_w - 1'b1);
  wire          last_px = tlast && (y == cur_h - 1'b1);

  sm_fifo #(
      .DATA_W(35),
      .DEPTH (FIFO_DEPTH)
  ) u_out_fifo (
      .clk       (clk),
      .rst_n     (rst_n),
      .wr_en     (wr),
      .din       ({last_px, sof, tlast, pad_q ? 32'd0 : in_word}),
      .full      (full),
      .rd_en     (pop),
      .dout      (head),
      .dout_valid(fifo_valid),
      .level     (level)
  );
  // tuser / tlast only with tvalid (the FIFO head holds stale bits when empty)
  assign m_axis_tuser = m_axis_tvalid & head[33];
  assign m_axis_tlast = m_axis_tvalid & head[32];
  assign m_axis_tdata = head[31:0];
  wire          head_eof = head[34];

  // Level after this clock; room is registered, so it must already count this clock's
  // write and read to be exact for the next ce.
  wire          wr_ok = wr && !full;
  wire [LW-1:0] level_next = level + {{(LW-1){1'b0}}, wr_ok} - {{(LW-1){1'b0}}, pop};
  wire          popped_eof = pop && head_eof;
  wire [LW-1:0] eofs_next = eofs_q + {{(LW-1){1'b0}}, wr_ok && last_px} - {{(LW-1){1'b0}}, popped_eof};
  wire          rd_open_next = rd ? (!head_eof && (head[33] || rd_open_q)) : rd_open_q;
  // The sink's frame at a restart: it has taken the frame's tuser beat, or is offered it.
  wire          keep_next = restart ? (rd_open_next || (m_axis_tvalid && head[33] && !rd))
                                    : keep_q && !(rd && head_eof);
  wire          open_w = wr_ok ? !last_px : open_q;
  // Padding is needed when the sink's frame is the one being written: no last pixel of
  // any frame is queued (the sink's frame is the oldest in the FIFO).
  wire          pad_start = restart && keep_next && open_w && (eofs_q == {LW{1'b0}});
  wire          pad_next = pad_q ? open_w : pad_start;
  wire          open_next = (restart && !pad_q && !pad_start) ? 1'b0 : open_w;
  // The flush ends once the FIFO is empty with nothing left to pad or deliver (nothing
  // is written then: ce is low and the padding is done), judged on this clock's state.
  wire          flush_next = restart || (flush_q && !(level == {LW{1'b0}} && !pad_q && !keep_q));

  always @(posedge clk) begin
    if (!rst_n) begin
      x_q          <= {XW{1'b0}};
      y_q          <= {YW{1'b0}};
      w_q          <= MAX_WIDTH[XW-1:0];
      h_q          <= MAX_HEIGHT[YW-1:0];
      xlast_q      <= 1'b0;
      open_q       <= 1'b0;
      pad_q        <= 1'b0;
      flush_q      <= 1'b0;
      keep_q       <= 1'b0;
      rd_open_q    <= 1'b0;
      eofs_q       <= {LW{1'b0}};
      room         <= 1'b0;
      err_overflow <= 1'b0;
    end else begin
      // Low from the restart to the clock after the flush (kept off the flush's own
      // logic: the FIFO level's adder already leads here).
      room         <= !restart && !flush_q && (level_next <= CAP);
      err_overflow <= wr_in && full;
      if (wr_ok) begin
        x_q     <= x;
        y_q     <= y;
        xlast_q <= tlast;
        if (sof) begin
          w_q <= width;
          h_q <= height;
        end
      end
      open_q    <= open_next;
      pad_q     <= pad_next;
      flush_q   <= flush_next;
      keep_q    <= keep_next;
      rd_open_q <= rd_open_next;
      eofs_q    <= eofs_next;
    end
  end

`ifndef SYNTHESIS
  // Simulation-only AXI4-Stream rule (Verilator --assert builds): once tvalid is high it
  // stays high, with the same beat, until the sink takes it.
  reg        chk_wait_q;
  reg [33:0] chk_beat_q;
  always @(posedge clk) begin
    chk_wait_q <= rst_n && m_axis_tvalid && !m_axis_tready;
    chk_beat_q <= {m_axis_tuser, m_axis_tlast, m_axis_tdata};
    if (rst_n && chk_wait_q && (!m_axis_tvalid || chk_beat_q != {m_axis_tuser, m_axis_tlast, m_axis_tdata}))
      $error("sm_outfmt: m_axis beat withdrawn or changed before tready");
  end
`endif
endmodule
`default_nettype wire
