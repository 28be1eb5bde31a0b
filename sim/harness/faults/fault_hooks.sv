// fault_hooks: the deliberate faults of the harness's own tests, forced onto the nets between
// shade_unit's modules. Test apparatus, outside rtl/: Verilator builds with fault hooks bind it
// into shade_unit (fault_bind.sv); Icarus 11, which has no bind, instantiates it beside the unit
// in its testbench. `SHADESIM_FAULT_DUT names the unit's instance (default: shade_unit, the
// bound module's parent). One fault at a time, chosen at run time by fault_select, on row `row`
// (the sites are fault_pkg::Fault*; sim/harness/fault_site.h is the C++ twin). With no fault
// chosen every forced net carries what the unit drives onto it.
//
// Each forced value is a variable of this module (Icarus 11 evaluates any other right-hand side
// only once), computed from the net that drives the forced one (shade_unit: setup_v drives
// start_v, ...), never from the forced net itself.
`ifndef SHADESIM_FAULT_DUT
`define SHADESIM_FAULT_DUT shade_unit
`endif
`ifdef VERILATOR
// Under Verilator 5.006 a force evaluates its right-hand side once, when the force runs: run
// it again whenever that side changes.
`define SHADESIM_FORCE(target, value) always @* force target = value;
`else
`define SHADESIM_FORCE(target, value) initial force target = value;
`endif
module fault_hooks #(
  parameter int XY_BITS          = 12,
  parameter int LANES            = 1,
  parameter int CHANNELS         = 1,
  parameter int LIGHTS           = 1,
  parameter int OUT_BITS         = 8,
  parameter int SERIES_WL        = 32,
  parameter int SERIES_IWL       = 4,
  parameter int SPECULAR_KIND    = 0,
  parameter int SPECULAR_OUT_WL  = 17,
  parameter int SPECULAR_OUT_IWL = 1,
  parameter int DIFFUSE_MULTIPLY = 0
) ();
  localparam int NSer      = shade_pkg::series_count(SPECULAR_KIND, LIGHTS, CHANNELS,
                                                     DIFFUSE_MULTIPLY != 0);
  localparam int LaneColW  = CHANNELS * OUT_BITS;
  // One output LSB of series 0; light 0's top specular fraction bit; the channel of FaultChannel2.
  localparam int SetupShift = SERIES_WL - SERIES_IWL > OUT_BITS ?
                              SERIES_WL - SERIES_IWL - OUT_BITS : 0;
  localparam int SpecBit    = SPECULAR_OUT_WL - SPECULAR_OUT_IWL - 1;
  localparam int Channel2   = CHANNELS > 2 ? 2 : 0;
  // pixel_combine's exact sum and the bits its output rounding drops (its AccW and OutDrop).
  localparam int AccW       = SERIES_WL + $clog2(2 * LIGHTS + 1) + 1;
  localparam int OutDrop    = SERIES_WL - SERIES_IWL - OUT_BITS;

  logic [fault_pkg::FaultSiteW-1:0] site;
  logic [XY_BITS-1:0]               row;
  logic                             s3_row, out_row, stall, done_q;
  fault_select #(.XY_BITS(XY_BITS)) u_fault_select (.site_o(site), .row_o(row));

  /* verilator coverage_off */  // deliberate-fault hooks: taken only by a fault test
  assign s3_row  = `SHADESIM_FAULT_DUT.s3_span.y == row;
  assign out_row = `SHADESIM_FAULT_DUT.meta_out.y == row;

  // FaultStall: one extra engine stall before the row's first last_in_row span; FaultHang: the
  // engines never take a span of the row.
  assign stall = site == fault_pkg::FaultStall && !done_q && `SHADESIM_FAULT_DUT.s3_span.last &&
                 s3_row;
  always_ff @(posedge `SHADESIM_FAULT_DUT.clk_i or negedge `SHADESIM_FAULT_DUT.rst_ni) begin
    if (!`SHADESIM_FAULT_DUT.rst_ni) done_q <= 1'b0;
    else if (`SHADESIM_FAULT_DUT.s3_v && stall && `SHADESIM_FAULT_DUT.u_engine_ctrl.take_ready)
      done_q <= 1'b1;
  end
  logic span_valid;
  assign span_valid = `SHADESIM_FAULT_DUT.s3_v && !stall &&
                      !(site == fault_pkg::FaultHang && s3_row);
  `SHADESIM_FORCE(`SHADESIM_FAULT_DUT.eng_span_valid, span_valid)

  // FaultSpanSetup: series 0's start value one output LSB high on the row.
  logic [NSer*SERIES_WL-1:0] start_v;
  always_comb begin
    start_v = `SHADESIM_FAULT_DUT.setup_v;
    if (site == fault_pkg::FaultSpanSetup && s3_row)
      start_v[SERIES_WL-1:0] = start_v[SERIES_WL-1:0] + (SERIES_WL'(1) << SetupShift);
  end
  `SHADESIM_FORCE(`SHADESIM_FAULT_DUT.start_v, start_v)

  // FaultSpecular: light 0's specular result of every lane, its top fraction bit flipped.
  // FaultLsb, FaultChannel2: channel 0 or 2 of every lane's pixel + 1 LSB.
  logic [LANES*LIGHTS*SPECULAR_OUT_WL-1:0] spec;
  logic [LANES*LaneColW-1:0]               colour;
  always_comb begin
    spec   = `SHADESIM_FAULT_DUT.slot_spec;
    colour = `SHADESIM_FAULT_DUT.colour;
    if (out_row) begin
      for (int j = 0; j < LANES; j++) begin
        if (site == fault_pkg::FaultSpecular)
          spec[j*LIGHTS*SPECULAR_OUT_WL + SpecBit] = !spec[j*LIGHTS*SPECULAR_OUT_WL + SpecBit];
        if (site == fault_pkg::FaultLsb)
          colour[j*LaneColW +: OUT_BITS] = colour[j*LaneColW +: OUT_BITS] + OUT_BITS'(1);
        if (site == fault_pkg::FaultChannel2 && CHANNELS > 2)
          colour[j*LaneColW + Channel2*OUT_BITS +: OUT_BITS] =
              colour[j*LaneColW + Channel2*OUT_BITS +: OUT_BITS] + OUT_BITS'(1);
      end
    end
  end
  `SHADESIM_FORCE(`SHADESIM_FAULT_DUT.spec, spec)
  `SHADESIM_FORCE(`SHADESIM_FAULT_DUT.colour_out, colour)

  // FaultRounding: the row's output truncated instead of rounded to nearest. pixel_combine rounds
  // its exact sum by adding half an output LSB and dropping bits (fixed_round): without the half
  // that is a truncation. Verilator only: Icarus 11 cannot name a generate-loop instance by a
  // genvar, and runs only the lsb and stall faults (cmake/icarus.cmake).
`ifdef VERILATOR
// Lane j, channel c's output rounding (a fixed_round).
`define SHADESIM_ROUND_OUT(j, c) \
    `SHADESIM_FAULT_DUT.u_combine_lanes.g_combine[j].u_combine.g_chan[c].u_round_out
  if (OutDrop > 0) begin : g_rounding
    localparam logic [AccW:0] Half = (AccW + 1)'(1) << (OutDrop - 1);
    logic [AccW:0] bias;
    assign bias = site == fault_pkg::FaultRounding && out_row ? '0 : Half;
    for (genvar j = 0; j < LANES; j++) begin : g_lane
      for (genvar c = 0; c < CHANNELS; c++) begin : g_chan
        `SHADESIM_FORCE(`SHADESIM_ROUND_OUT(j, c).g_drop.g_rnd.biased,
                        `SHADESIM_ROUND_OUT(j, c).g_drop.ext + bias)
      end
    end
  end
`undef SHADESIM_ROUND_OUT
`endif

  // FaultX, FaultY, FaultEor: the row's position or end of row wrong.
  logic [XY_BITS-1:0] x, y;
  logic               eor;
  assign x   = `SHADESIM_FAULT_DUT.meta_out.x + XY_BITS'(site == fault_pkg::FaultX && out_row);
  assign y   = `SHADESIM_FAULT_DUT.meta_out.y ^ XY_BITS'(site == fault_pkg::FaultY && out_row);
  assign eor = `SHADESIM_FAULT_DUT.meta_out.eor ^ (site == fault_pkg::FaultEor && out_row);
  `SHADESIM_FORCE(`SHADESIM_FAULT_DUT.out_x, x)
  `SHADESIM_FORCE(`SHADESIM_FAULT_DUT.out_y, y)
  `SHADESIM_FORCE(`SHADESIM_FAULT_DUT.out_eor, eor)
  /* verilator coverage_on */
endmodule
`undef SHADESIM_FORCE
