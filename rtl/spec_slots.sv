// spec_slots: shade_unit's specular slots - one specular_unit per light and lane, all started
// together (en_i), each reading its light's specular series of its lane and configured from the
// command decoder's MATERIAL / TABLE words. SPECULAR_KIND none: no slot (the configuration
// words are taken and dropped) and no specular value.
module spec_slots #(
  parameter int SPECULAR_KIND         = 0,
  parameter int LIGHTS                = 1,
  parameter int LANES                 = 1,
  parameter int N_DIFF                = 1,  // diffuse series per lane (before the specular)
  parameter int SERIES_PER_LIGHT      = 1,  // specular series per light
  parameter int SERIES_WL             = 32,
  parameter int SERIES_IWL            = 4,
  parameter int SPECULAR_OUT_WL       = 17,
  parameter int SPECULAR_OUT_IWL      = 1,
  parameter int SPECULAR_OUT_QUANT    = 0,
  parameter int SPECULAR_OUT_OVERFLOW = 0,
  parameter int MATERIAL_BUFFERS      = 1,
  parameter logic [shade_pkg::SpecParamW-1:0] SPEC_PARAMS = '0
) (
  input  logic                                    clk_i,
  input  logic                                    rst_ni,
  input  logic                                    en_i,
  // Lane j's series at j * LaneSerW, diffuse first: the slots read their lights' specular ones.
  // verilator lint_off UNUSEDSIGNAL
  input  logic [LANES*(N_DIFF+LIGHTS*SERIES_PER_LIGHT)*SERIES_WL-1:0] series_i,
  // verilator lint_on UNUSEDSIGNAL
  input  logic                                    bank_i,    // material bank of the beat
  input  logic                                    cfg_valid_i,
  input  logic                                    cfg_bank_i,
  input  logic                                    cfg_all_banks_i,
  input  logic                                    cfg_table_i,
  input  logic [15:0]                             cfg_addr_i,
  input  logic [shade_pkg::WordW-1:0]             cfg_data_i,
  output logic [LANES*LIGHTS*SPECULAR_OUT_WL-1:0] spec_o,  // lane j, light l at j * LIGHTS + l
  output logic                                    busy_o   // some slot cannot start
);
  localparam int LaneSerW = (N_DIFF + LIGHTS * SERIES_PER_LIGHT) * SERIES_WL;
  logic [LANES*LIGHTS-1:0] busy;
  assign busy_o = |busy;
  if (SPECULAR_KIND != shade_pkg::SpecNone) begin : g_slots
    for (genvar g = 0; g < LANES * LIGHTS; g++) begin : g_spec
      localparam int L = g % LIGHTS;
      localparam int J = g / LIGHTS;
      specular_unit #(
        .SPECULAR_KIND(SPECULAR_KIND), .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
        .SERIES_PER_LIGHT(SERIES_PER_LIGHT), .SPECULAR_OUT_WL(SPECULAR_OUT_WL),
        .SPECULAR_OUT_IWL(SPECULAR_OUT_IWL), .SPECULAR_OUT_QUANT(SPECULAR_OUT_QUANT),
        .SPECULAR_OUT_OVERFLOW(SPECULAR_OUT_OVERFLOW), .MATERIAL_BUFFERS(MATERIAL_BUFFERS),
        .SPEC_PARAMS(SPEC_PARAMS)
      ) u_slot (
        .clk_i, .rst_ni, .en_i,
        .series_i(series_i[J*LaneSerW + (N_DIFF + L*SERIES_PER_LIGHT)*SERIES_WL +:
                           SERIES_PER_LIGHT*SERIES_WL]), .bank_i,
        .cfg_valid_i, .cfg_bank_i, .cfg_all_banks_i, .cfg_table_i, .cfg_addr_i, .cfg_data_i,
        .spec_o(spec_o[g*SPECULAR_OUT_WL +: SPECULAR_OUT_WL]), .busy_o(busy[g])
      );
    end
  end else begin : g_no_slots
    assign spec_o = '0;
    assign busy   = '0;
    // verilator lint_off UNUSEDSIGNAL
    logic unused_in;  // reason: no slot reads the series, the bank or the configuration words
    assign unused_in = clk_i ^ rst_ni ^ en_i ^ (^series_i) ^ bank_i ^ cfg_valid_i ^ cfg_bank_i ^
                       cfg_all_banks_i ^ cfg_table_i ^ (^cfg_addr_i) ^ (^cfg_data_i);
    // verilator lint_on UNUSEDSIGNAL
  end

`ifndef SYNTHESIS
  initial begin
    if (SPECULAR_KIND < shade_pkg::SpecIdeal || SPECULAR_KIND > shade_pkg::SpecNone)
      $fatal(1, "spec_slots: SPECULAR_KIND %0d is not 0 ideal .. 3 wpow, 4 none", SPECULAR_KIND);
  end
`endif
endmodule
