// fault_hooks: the deliberate faults of the harness's own tests, between shade_unit's modules.
// Instantiated only by a FAULT_HOOKS build (every other build, and synthesis, wires the
// boundaries straight through); one fault at a time, chosen at run time by fault_select, on row
// `row` (the sites are shade_pkg::Fault*; sim/harness/fault_site.h is the C++ twin).
module fault_hooks #(
  parameter int XY_BITS          = 12,
  parameter int LANES            = 1,
  parameter int CHANNELS         = 1,
  parameter int LIGHTS           = 1,
  parameter int OUT_BITS         = 8,
  parameter int N_SER            = 1,
  parameter int SERIES_WL        = 32,
  parameter int SERIES_IWL       = 4,
  parameter int SPECULAR_OUT_WL  = 17,
  parameter int SPECULAR_OUT_IWL = 1
) (
  input  logic                                    clk_i,
  input  logic                                    rst_ni,
  // setup stage 3 -> engines
  input  logic                                    s3_valid_i,
  input  logic [XY_BITS-1:0]                      s3_y_i,
  input  logic                                    s3_last_i,
  input  logic                                    eng_take_ready_i,
  output logic                                    eng_span_valid_o,
  input  logic [N_SER*SERIES_WL-1:0]              setup_v_i,
  output logic [N_SER*SERIES_WL-1:0]              start_v_o,
  // slots -> pixel combine -> output register
  input  logic [XY_BITS-1:0]                      out_y_i,
  input  logic [XY_BITS-1:0]                      out_x_i,
  input  logic                                    out_eor_i,
  input  logic [LANES*LIGHTS*SPECULAR_OUT_WL-1:0] spec_i,
  output logic [LANES*LIGHTS*SPECULAR_OUT_WL-1:0] spec_o,
  output logic                                    trunc_o,
  input  logic [LANES*CHANNELS*OUT_BITS-1:0]      colour_i,
  output logic [LANES*CHANNELS*OUT_BITS-1:0]      colour_o,
  output logic [XY_BITS-1:0]                      x_o,
  output logic [XY_BITS-1:0]                      y_o,
  output logic                                    eor_o
);
  localparam int LaneColW       = CHANNELS * OUT_BITS;
  // One output LSB of series 0; light 0's top specular fraction bit; the channel of FaultChannel2.
  localparam int SetupShift     = SERIES_WL - SERIES_IWL > OUT_BITS ?
                                  SERIES_WL - SERIES_IWL - OUT_BITS : 0;
  localparam int SpecBit        = SPECULAR_OUT_WL - SPECULAR_OUT_IWL - 1;
  localparam int Channel2       = CHANNELS > 2 ? 2 : 0;

  logic [shade_pkg::FaultSiteW-1:0] site;
  logic [XY_BITS-1:0]               row;
  logic                             s3_row, out_row, stall, done_q;
  fault_select #(.XY_BITS(XY_BITS)) u_fault_select (.site_o(site), .row_o(row));
  assign s3_row  = s3_y_i == row;
  assign out_row = out_y_i == row;

  /* verilator coverage_off */  // deliberate-fault hooks: taken only by a fault test
  // FaultStall: one extra engine stall before the row's first last_in_row span; FaultHang: the
  // engines never take a span of the row.
  assign stall = site == shade_pkg::FaultStall && !done_q && s3_last_i && s3_row;
  assign eng_span_valid_o = s3_valid_i && !stall && !(site == shade_pkg::FaultHang && s3_row);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) done_q <= 1'b0;
    else if (s3_valid_i && stall && eng_take_ready_i) done_q <= 1'b1;
  end
  always_comb begin
    // FaultSpanSetup: series 0's start value one output LSB high on the row.
    start_v_o = setup_v_i;
    if (site == shade_pkg::FaultSpanSetup && s3_row)
      start_v_o[SERIES_WL-1:0] = setup_v_i[SERIES_WL-1:0] + (SERIES_WL'(1) << SetupShift);
    // FaultSpecular: light 0's specular result of every lane, its top fraction bit flipped.
    // FaultLsb, FaultChannel2: channel 0 or 2 of every lane's pixel + 1 LSB.
    spec_o   = spec_i;
    colour_o = colour_i;
    if (out_row) begin
      for (int j = 0; j < LANES; j++) begin
        if (site == shade_pkg::FaultSpecular)
          spec_o[j*LIGHTS*SPECULAR_OUT_WL + SpecBit] = !spec_i[j*LIGHTS*SPECULAR_OUT_WL + SpecBit];
        if (site == shade_pkg::FaultLsb)
          colour_o[j*LaneColW +: OUT_BITS] = colour_i[j*LaneColW +: OUT_BITS] + OUT_BITS'(1);
        if (site == shade_pkg::FaultChannel2 && CHANNELS > 2)
          colour_o[j*LaneColW + Channel2*OUT_BITS +: OUT_BITS] =
              colour_i[j*LaneColW + Channel2*OUT_BITS +: OUT_BITS] + OUT_BITS'(1);
      end
    end
  end
  // FaultRounding: the row's output truncated; FaultX, FaultY, FaultEor: its position or end of
  // row wrong.
  assign trunc_o = site == shade_pkg::FaultRounding && out_row;
  assign x_o     = out_x_i + XY_BITS'(site == shade_pkg::FaultX && out_row);
  assign y_o     = out_y_i ^ XY_BITS'(site == shade_pkg::FaultY && out_row);
  assign eor_o   = out_eor_i ^ (site == shade_pkg::FaultEor && out_row);
  /* verilator coverage_on */
endmodule
