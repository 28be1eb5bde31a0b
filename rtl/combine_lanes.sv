// combine_lanes: one pixel_combine per lane - each lane's diffuse series and specular results
// with the beat's material (ambient, specular colours, gate-only mask) into its output colour.
module combine_lanes #(
  parameter int CHANNELS         = 1,
  parameter int LIGHTS           = 1,
  parameter int LANES            = 1,
  parameter int SERIES_WL        = 32,
  parameter int SERIES_IWL       = 4,
  parameter int SERIES_QUANT     = 0,
  parameter int SERIES_OVERFLOW  = 1,
  parameter int SPEC_COLOUR_WL   = 13,
  parameter int SPEC_COLOUR_IWL  = 1,
  parameter int SPECULAR_OUT_WL  = 17,
  parameter int SPECULAR_OUT_IWL = 1,
  parameter int OUT_BITS         = 8,
  parameter bit SPECULAR         = 1'b1,  // a specular term
  parameter bit DIFFUSE_MULTIPLY = 1'b0,  // one N.L series per light, times kd_lc
  parameter int STAGES           = 0      // pixel_combine's registers (UnitConfig::combine_stages)
) (
  input  logic                                       clk_i,
  input  logic                                       en_i,  // the pipeline's advance
  // lane j's at j * LaneDiffW
  input  logic [LANES*(DIFFUSE_MULTIPLY ? LIGHTS : LIGHTS*CHANNELS)*SERIES_WL-1:0] diffuse_i,
  input  logic [LANES*LIGHTS*SPECULAR_OUT_WL-1:0]    spec_i,     // lane j, light l: j*LIGHTS+l
  input  logic [CHANNELS*SERIES_WL-1:0]              ambient_i,
  input  logic [LIGHTS*CHANNELS*SPEC_COLOUR_WL-1:0]  spec_colour_i,
  input  logic [LIGHTS*CHANNELS*SPEC_COLOUR_WL-1:0]  diffuse_colour_i,  // multiply only
  input  logic [LIGHTS-1:0]                          gate_only_i,
  output logic [LANES*CHANNELS*OUT_BITS-1:0]         colour_o  // lane j's at j * LaneColW
);
  localparam int LaneDiffW = (DIFFUSE_MULTIPLY ? LIGHTS : LIGHTS * CHANNELS) * SERIES_WL;
  localparam int LaneColW  = CHANNELS * OUT_BITS;
  for (genvar j = 0; j < LANES; j++) begin : g_combine
    pixel_combine #(
      .CHANNELS(CHANNELS), .LIGHTS(LIGHTS), .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
      .SERIES_QUANT(SERIES_QUANT), .SERIES_OVERFLOW(SERIES_OVERFLOW),
      .SPEC_COLOUR_WL(SPEC_COLOUR_WL), .SPEC_COLOUR_IWL(SPEC_COLOUR_IWL),
      .SPECULAR_OUT_WL(SPECULAR_OUT_WL), .SPECULAR_OUT_IWL(SPECULAR_OUT_IWL), .OUT_BITS(OUT_BITS),
      .SPECULAR(SPECULAR), .DIFFUSE_MULTIPLY(DIFFUSE_MULTIPLY), .STAGES(STAGES)
    ) u_combine (
      .clk_i, .en_i,
      .diffuse_i(diffuse_i[j*LaneDiffW +: LaneDiffW]),
      .spec_i(spec_i[j*LIGHTS*SPECULAR_OUT_WL +: LIGHTS*SPECULAR_OUT_WL]), .ambient_i,
      .spec_colour_i, .diffuse_colour_i, .gate_only_i,
      .colour_o(colour_o[j*LaneColW +: LaneColW])
    );
  end
endmodule
