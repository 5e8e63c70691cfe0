`default_nettype none
// Output formatter (docs/streams.md): at each ce it takes the last stage's beat, keeps
// the real ones and queues them as the AXI4-Stream video output (tdata bit 15 = valid,
// low bits = disparity; tuser on the frame's first pixel, tlast at x == W-1). The FIFO
// absorbs sink back-pressure; `room` tells the top whether one more ce is safe, so the
// top drives ce = beat_valid && room and no beat is ever lost.
module sm_outfmt #(
    parameter MAX_WIDTH  = 320,  // widest active line
    parameter FIFO_DEPTH = 256   // output FIFO RAM entries (power of two); holds +1
) (
    input  wire          clk,
    input  wire          rst_n,
    input  wire          ce,
    input  wire [XW-1:0] width,         // active width (shadow), latched at each sof
    input  wire [4:0]    in_side,       // last stage's beat
    input  wire [15:0]   in_disp,
    output wire [15:0]   m_axis_tdata,
    output wire          m_axis_tuser,
    output wire          m_axis_tlast,
    output wire          m_axis_tvalid,
    input  wire          m_axis_tready,
    output reg           room,          // the FIFO can take the beat of one more ce
    output reg           err_overflow       // pulse: a real beat met a full FIFO and was lost
);
  localparam XW = $clog2(MAX_WIDTH + 1);
  localparam LW = $clog2(FIFO_DEPTH) + 1;
  localparam [LW-1:0] CAP = FIFO_DEPTH[LW-1:0];  // level at which one more write still fits

  wire          in_real = in_side[0];
  wire          in_sof  = in_side[1];
  wire          in_sol  = in_side[2];
  wire [1:0]    unused_ftag = in_side[4:3];

  reg  [XW-1:0] x_q;
  reg  [XW-1:0] w_q;
  wire [XW-1:0] x     = in_sol ? {XW{1'b0}} : x_q + 1'b1;
  wire [XW-1:0] cur_w = in_sof ? width : w_q;
  wire          tlast = (x == cur_w - 1'b1);

  wire          full;
  wire [LW-1:0] level;
  wire [17:0]   head;
  wire          wr = ce && in_real;
  wire          rd = m_axis_tvalid && m_axis_tready;

  sm_fifo #(
      .DATA_W(18),
      .DEPTH (FIFO_DEPTH)
  ) u_out_fifo (
      .clk       (clk),
      .rst_n     (rst_n),
      .wr_en     (wr),
      .din       ({in_sof, tlast, in_disp}),
      .full      (full),
      .rd_en     (m_axis_tready),
      .dout      (head),
      .dout_valid(m_axis_tvalid),
      .level     (level)
  );
  assign m_axis_tuser = head[17];
  assign m_axis_tlast = head[16];
  assign m_axis_tdata = head[15:0];

  // Level after this clock; room is registered, so it must already count this clock's
  // write and read to be exact for the next ce.
  wire          wr_ok = wr && !full;
  wire [LW-1:0] level_next = level + {{(LW-1){1'b0}}, wr_ok} - {{(LW-1){1'b0}}, rd};

  always @(posedge clk) begin
    if (!rst_n) begin
      x_q      <= {XW{1'b0}};
      w_q      <= MAX_WIDTH[XW-1:0];
      room     <= 1'b0;
      err_overflow <= 1'b0;
    end else begin
      room     <= (level_next <= CAP);
      err_overflow <= wr && full;
      if (wr) begin
        x_q <= x;
        if (in_sof) w_q <= width;
      end
    end
  end

`ifndef SYNTHESIS
  // Simulation-only AXI4-Stream rule (Verilator --assert builds): once tvalid is high it
  // stays high, with the same beat, until the sink takes it.
  reg        chk_wait_q;
  reg [17:0] chk_beat_q;
  always @(posedge clk) begin
    chk_wait_q <= rst_n && m_axis_tvalid && !m_axis_tready;
    chk_beat_q <= {m_axis_tuser, m_axis_tlast, m_axis_tdata};
    if (rst_n && chk_wait_q && (!m_axis_tvalid || chk_beat_q != {m_axis_tuser, m_axis_tlast, m_axis_tdata}))
      $error("sm_outfmt: m_axis beat withdrawn or changed before tready");
  end
`endif
endmodule
`default_nettype wire
