// Icarus Verilog speed testbench for sm_top (bench/sim_speed.sh): programs RECT_ENABLE = 0
// over AXI4-Lite (every other register keeps its reset value), streams FRAMES frames
// from IN_HEX as a continuous camera (one pixel per clock whenever s_axis_tready), keeps
// the outputs always ready, writes every output word to OUT_HEX and prints the cycle
// count, so the script can divide it by the wall time and diff the words against the
// model. Icarus only (uses $readmemh/$fopen/$time); not part of the synthesised IP.
`timescale 1ns / 1ps
`default_nettype none
module sm_bench_tb;
  parameter MAX_WIDTH   = 64;   // must match the vectors (bench_icarus_vectors)
  parameter MAX_HEIGHT  = 48;   // active size = maximum size (reset values of WIDTH/HEIGHT)
  parameter DISP        = 16;   // disparity levels
  parameter CENSUS      = 7;    // census window side
  parameter SW          = 3;    // support-weight window side
  parameter RECT_RADIUS = 4;    // rectifier row radius
  parameter FRAMES      = 2;    // frames in IN_HEX
  parameter IN_HEX      = "in.hex";   // stimulus: {right, left} per pixel
  parameter OUT_HEX     = "out.hex";  // output words, one per line
  localparam NPIX = MAX_WIDTH * MAX_HEIGHT * FRAMES;

  reg         clk = 1'b0;
  reg         aresetn = 1'b0;
  reg  [15:0] s_tdata = 16'd0;
  reg         s_tuser = 1'b0, s_tlast = 1'b0, s_tvalid = 1'b0;
  wire        s_tready;
  wire [31:0] m_tdata;
  wire        m_tuser, m_tlast, m_tvalid;
  wire [31:0] obj_tdata;
  wire        obj_tlast, obj_tvalid;
  reg  [15:0] awaddr = 16'd0;
  reg         awvalid = 1'b0;
  wire        awready;
  reg  [31:0] wdata = 32'd0;
  reg         wvalid = 1'b0;
  wire        wready;
  wire [1:0]  bresp;
  wire        bvalid;
  wire        arready, rvalid;
  wire [31:0] rdata;
  wire [1:0]  rresp;

  sm_top #(
      .MAX_WIDTH(MAX_WIDTH), .MAX_HEIGHT(MAX_HEIGHT), .DISP(DISP), .CENSUS(CENSUS), .SW(SW),
      .RECT_RADIUS(RECT_RADIUS)
  ) dut (
      .aclk(clk), .aresetn(aresetn),
      .s_axis_tdata(s_tdata), .s_axis_tuser(s_tuser), .s_axis_tlast(s_tlast),
      .s_axis_tvalid(s_tvalid), .s_axis_tready(s_tready),
      .m_axis_tdata(m_tdata), .m_axis_tuser(m_tuser), .m_axis_tlast(m_tlast),
      .m_axis_tvalid(m_tvalid), .m_axis_tready(1'b1),
      .m_axis_obj_tdata(obj_tdata), .m_axis_obj_tlast(obj_tlast), .m_axis_obj_tvalid(obj_tvalid),
      .m_axis_obj_tready(1'b1),
      .s_axil_awaddr(awaddr), .s_axil_awvalid(awvalid), .s_axil_awready(awready),
      .s_axil_wdata(wdata), .s_axil_wstrb(4'hf), .s_axil_wvalid(wvalid), .s_axil_wready(wready),
      .s_axil_bresp(bresp), .s_axil_bvalid(bvalid), .s_axil_bready(1'b1),
      .s_axil_araddr(16'd0), .s_axil_arvalid(1'b0), .s_axil_arready(arready),
      .s_axil_rdata(rdata), .s_axil_rresp(rresp), .s_axil_rvalid(rvalid), .s_axil_rready(1'b1)
  );

  always #5 clk = ~clk;

  reg [15:0] mem [0:NPIX-1];
  integer    fo, nin, nout, cycles, first_cycle;

  always @(posedge clk) cycles <= cycles + 1;

  task axil_write(input [15:0] a, input [31:0] d);
    begin
      @(negedge clk);
      awaddr = a; awvalid = 1'b1; wdata = d; wvalid = 1'b1;
      while (awvalid || wvalid) begin
        @(posedge clk);
        if (awready) awvalid <= 1'b0;
        if (wready) wvalid <= 1'b0;
        @(negedge clk);
      end
      while (!bvalid) @(negedge clk);
      @(negedge clk);
    end
  endtask

  // Input side: a pixel is offered every clock; it advances when the IP takes it.
  always @(posedge clk) begin
    if (s_tvalid && s_tready) begin
      nin = nin + 1;
      if (nin == NPIX) begin
        s_tvalid <= 1'b0;
      end else begin
        s_tdata <= mem[nin];
        s_tuser <= (nin % (MAX_WIDTH * MAX_HEIGHT)) == 0;
        s_tlast <= (nin % MAX_WIDTH) == MAX_WIDTH - 1;
      end
    end
    if (m_tvalid) begin
      $fwrite(fo, "%08x\n", m_tdata);
      nout = nout + 1;
    end
  end

  initial begin
    $readmemh(IN_HEX, mem);
    fo = $fopen(OUT_HEX, "w");
    nin = 0; nout = 0; cycles = 0;
    repeat (4) @(posedge clk);
    aresetn = 1'b1;
    repeat (4) @(posedge clk);
    axil_write(16'h0058, 32'd0);  // RECT_ENABLE = 0 (the grid RAMs are not written)
    repeat (8) @(posedge clk);
    @(negedge clk);
    first_cycle = cycles;
    s_tdata = mem[0]; s_tuser = 1'b1; s_tlast = (MAX_WIDTH == 1); s_tvalid = 1'b1;
    while (nout < NPIX && cycles - first_cycle < 40 * NPIX + 100000) @(posedge clk);
    $fclose(fo);
    $display("sm_bench_tb: %0d pixels in, %0d out, %0d cycles", nin, nout, cycles - first_cycle);
    $finish;
  end
endmodule
`default_nettype wire
