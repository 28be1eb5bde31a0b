// series_path: shade_unit's series datapath - per series one span_setup (three stages) and per
// lane one series_engine, with lane_fanout between them when LANES > 1 (lane j's start value and
// K-pixel differences). With host span setup (HOST_SETUP) there is no span_setup: v, d, d2 come
// from the start bank (bank_*_i) and the setup inputs are unused. The engines load on load_i
// and step on step_i (engine_ctrl); the start values leave and re-enter (setup_v_o ->
// start_v_i) so the harness can force an error onto them (shade_unit's start_v).
module series_path #(
  parameter int N_SER           = 1,
  parameter int LANES           = 1,
  parameter int COEF_WL         = 36,
  parameter int COEF_IWL        = 4,
  parameter int SERIES_WL       = 32,
  parameter int SERIES_IWL      = 4,
  parameter int SERIES_QUANT    = 0,  // Quantization: 0 truncate, 1 round to nearest
  parameter int SERIES_OVERFLOW = 1,  // Overflow: 0 saturate, 1 wrap
  parameter int OFS_BITS        = 17,
  parameter bit HOST_SETUP      = 1'b0
) (
  input  logic                              clk_i,
  // verilator lint_off UNUSEDSIGNAL
  // reason: with host setup the span setup inputs are unused, with unit setup the start bank's
  input  logic                              s1_en_i,  // setup stage enables (setup_ctrl)
  input  logic                              s2_en_i,
  input  logic                              s3_en_i,
  input  logic [N_SER*6*COEF_WL-1:0]        coef_i,   // series i's T0..T5 at 6*i*COEF_WL
  // The offsets dx = x0 - xo, dy = y - yo of the span entering stage 1 are taken modulo
  // 2^OFS_BITS (x0 and y zero-extended or cut, the origin sign-extended or cut): exact for every
  // stream CommandStream::validate accepts, whose offsets fit OFS_BITS signed bits.
  input  logic signed [OFS_BITS-1:0]        x_i,
  input  logic signed [OFS_BITS-1:0]        y_i,
  input  logic signed [OFS_BITS-1:0]        xo_i,  // ... its triangle's origin
  input  logic signed [OFS_BITS-1:0]        yo_i,
  input  logic [N_SER*SERIES_WL-1:0]        bank_v_i,   // host setup: the start bank's values
  input  logic [N_SER*SERIES_WL-1:0]        bank_d_i,
  input  logic [N_SER*SERIES_WL-1:0]        bank_d2_i,
  // verilator lint_on UNUSEDSIGNAL
  output logic [N_SER*SERIES_WL-1:0]        setup_v_o,  // stage 3's start values
  input  logic [N_SER*SERIES_WL-1:0]        start_v_i,  // ... as the engines take them
  input  logic                              load_i,
  input  logic                              step_i,
  output logic [LANES*N_SER*SERIES_WL-1:0]  v_o  // lane j's series at j * N_SER * SERIES_WL
);
  localparam int LaneSerW = N_SER * SERIES_WL;
  logic [N_SER*SERIES_WL-1:0] start_d, start_d2;


  for (genvar i = 0; i < N_SER; i++) begin : g_series
    if (HOST_SETUP) begin : g_host
      assign setup_v_o[i*SERIES_WL +: SERIES_WL] = bank_v_i[i*SERIES_WL +: SERIES_WL];
      assign start_d[i*SERIES_WL +: SERIES_WL]   = bank_d_i[i*SERIES_WL +: SERIES_WL];
      assign start_d2[i*SERIES_WL +: SERIES_WL]  = bank_d2_i[i*SERIES_WL +: SERIES_WL];
    end else begin : g_unit
      span_setup #(
        .COEF_WL(COEF_WL), .COEF_IWL(COEF_IWL), .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
        .SERIES_QUANT(SERIES_QUANT), .SERIES_OVERFLOW(SERIES_OVERFLOW), .OFS_W(OFS_BITS)
      ) u_setup (
        .clk_i, .s1_en_i, .s2_en_i, .s3_en_i, .coef_i(coef_i[6*i*COEF_WL +: 6*COEF_WL]), .x_i,
        .y_i, .xo_i, .yo_i, .v_o(setup_v_o[i*SERIES_WL +: SERIES_WL]),
        .d_o(start_d[i*SERIES_WL +: SERIES_WL]), .d2_o(start_d2[i*SERIES_WL +: SERIES_WL])
      );
    end
    if (LANES == 1) begin : g_one_lane
      series_engine #(.SERIES_WL(SERIES_WL), .SERIES_OVERFLOW(SERIES_OVERFLOW)) u_engine (
        .clk_i, .load_i, .step_i, .v_i(start_v_i[i*SERIES_WL +: SERIES_WL]),
        .d_i(start_d[i*SERIES_WL +: SERIES_WL]), .d2_i(start_d2[i*SERIES_WL +: SERIES_WL]),
        .v_o(v_o[i*SERIES_WL +: SERIES_WL])
      );
    end else begin : g_lanes
      for (genvar j = 0; j < LANES; j++) begin : g_lane
        logic [SERIES_WL-1:0] lane_v, lane_d, lane_d2;
        lane_fanout #(
          .SERIES_WL(SERIES_WL), .SERIES_OVERFLOW(SERIES_OVERFLOW), .LANES(LANES), .LANE(j)
        ) u_fanout (
          .v_i(start_v_i[i*SERIES_WL +: SERIES_WL]), .d_i(start_d[i*SERIES_WL +: SERIES_WL]),
          .d2_i(start_d2[i*SERIES_WL +: SERIES_WL]), .v_o(lane_v), .d_o(lane_d), .d2_o(lane_d2)
        );
        series_engine #(.SERIES_WL(SERIES_WL), .SERIES_OVERFLOW(SERIES_OVERFLOW)) u_engine (
          .clk_i, .load_i, .step_i, .v_i(lane_v), .d_i(lane_d), .d2_i(lane_d2),
          .v_o(v_o[j*LaneSerW + i*SERIES_WL +: SERIES_WL])
        );
      end
    end
  end

`ifndef SYNTHESIS
  initial begin
    if (OFS_BITS < 2 || OFS_BITS > 17)
      $fatal(1, "series_path: OFS_BITS %0d is not 2..17", OFS_BITS);
    if (SERIES_QUANT != 0 && SERIES_QUANT != 1)
      $fatal(1, "series_path: SERIES_QUANT %0d is not 0 (truncate) or 1 (round)", SERIES_QUANT);
    if (SERIES_OVERFLOW != 0 && SERIES_OVERFLOW != 1)
      $fatal(1, "series_path: SERIES_OVERFLOW %0d is not 0 (saturate) or 1 (wrap)",
             SERIES_OVERFLOW);
  end
`endif
endmodule
