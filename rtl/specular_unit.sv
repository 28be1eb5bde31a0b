// specular_unit: one light's specular unit, whichever the configuration selects
// (model/specular_unit.h, class SpecularUnit). SPECULAR_KIND: 0 ideal, 1 lut (exponent_lut),
// 2 schlick (schlick_divider), 3 wpow (wpow_unit). Ideal is pow() in double, not hardware: the
// slot outputs 0 for it (bit-exact with the model whenever spec_colour is 0). Kind 4 (none) has
// no specular_unit at all: shade_unit instantiates none.
//
// SPEC_PARAMS: the selected unit's own fields, packed (shade_pkg::SpecSlots slots), passed on
// untouched; the unit module decodes its slots (model/specular_units.cpp gives each field its
// slot). The out format is SPECULAR_OUT_WL/IWL/QUANT/OVERFLOW (unsigned), the series format
// SERIES_WL/IWL.
//
// Timing contract (the README's RTL timing table gives it per unit):
//   LATENCY  = shade_pkg::spec_latency(...): registers between series_i and spec_o.
//   INTERVAL = shade_pkg::spec_interval(...): cycles per pixel (1 unless the unit is iterative).
//   INTERVAL == 1: en_i is the pipeline's advance (clock enable of every stage); spec_o is the
//              result for the series_i sampled at the LATENCY-th most recent en_i edge.
//   INTERVAL > 1 (iterative, LATENCY == INTERVAL): en_i starts a computation on series_i when
//              busy_o is low (ignored while busy_o is high). Started in cycle c: busy_o is high in
//              cycles c+1 .. c+LATENCY-1, the result is on spec_o from cycle c+LATENCY until the
//              edge that ends the next start cycle. busy_o depends only on registers.
// cfg port: MATERIAL words after ambient/spec_colour (cfg_table_i = 0, cfg_addr_i = 0 for the
// exponent, 1.. for unit_params[0..]) and TABLE entries (cfg_table_i = 1, cfg_addr_i = base + i).
// The exponent word resets the unit parameters to their defaults (empty unit_params).
// MATERIAL_BUFFERS = 2: the unit's per-material registers have two banks; cfg_bank_i is the bank
// MATERIAL words write, bank_i the bank of the pixel on series_i (it travels with the pixel
// through the unit's stages). Schlick has no per-material state. The LUT's table is per bank
// too: TABLE entries write bank cfg_bank_i, or every bank when cfg_all_banks_i is high.
module specular_unit #(
  // Each unit's parameters are unused when another unit is selected.
  // verilator lint_off UNUSEDPARAM
  parameter int SPECULAR_KIND         = 0,  // SpecularUnitKind: 0 ideal, 1 lut, 2 schlick, 3 wpow
  parameter int SERIES_WL             = 32,
  parameter int SERIES_IWL            = 4,
  parameter int SERIES_PER_LIGHT      = 1,  // 2 for schlick: [0] numerator, [1] denominator
  parameter int SPECULAR_OUT_WL       = 17,
  parameter int SPECULAR_OUT_IWL      = 1,
  parameter int SPECULAR_OUT_QUANT    = 0,  // Quantization: 0 truncate, 1 round to nearest
  parameter int SPECULAR_OUT_OVERFLOW = 0,  // Overflow: 0 saturate, 1 wrap
  parameter int MATERIAL_BUFFERS      = 1,  // material banks, 1 or 2
  parameter     LUT_TABLE_FILE        = "", // optional $readmemh file (ExponentLut::write_hex)
  // The unit's fields ('0 for ideal; a hardware unit's range checks reject '0).
  parameter logic [shade_pkg::SpecParamW-1:0] SPEC_PARAMS = '0
  // verilator lint_on UNUSEDPARAM
) (
  input  logic                                  clk_i,
  input  logic                                  rst_ni,
  input  logic                                  en_i,
  input  logic [SERIES_PER_LIGHT*SERIES_WL-1:0] series_i,
  input  logic                                  bank_i,       // material bank of series_i
  input  logic                                  cfg_valid_i,
  input  logic                                  cfg_bank_i,   // material bank cfg writes
  input  logic                                  cfg_all_banks_i,  // TABLE: write every bank
  input  logic                                  cfg_table_i,  // 1: TABLE entry, 0: MATERIAL word
  input  logic [15:0]                           cfg_addr_i,   // table address / material index
  input  logic [63:0]                           cfg_data_i,
  output logic [SPECULAR_OUT_WL-1:0]            spec_o,
  output logic                                  busy_o
);
  if (SPECULAR_KIND == shade_pkg::SpecLut) begin : g_lut
    exponent_lut #(
      .SPEC_PARAMS(SPEC_PARAMS), .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
      .OUT_WL(SPECULAR_OUT_WL), .OUT_IWL(SPECULAR_OUT_IWL), .OUT_QUANT(SPECULAR_OUT_QUANT),
      .OUT_OVERFLOW(SPECULAR_OUT_OVERFLOW), .CFG_ADDR_W(16), .BANKS(MATERIAL_BUFFERS),
      .TABLE_FILE(LUT_TABLE_FILE)
    ) u_lut (
      .clk_i, .rst_ni, .en_i, .series_i(series_i[SERIES_WL-1:0]), .bank_i,
      .cfg_valid_i, .cfg_bank_i, .cfg_all_banks_i, .cfg_table_i, .cfg_addr_i, .cfg_data_i,
      .spec_o
    );
    assign busy_o = 1'b0;
    if (SERIES_PER_LIGHT > 1) begin : g_unused_series
      // verilator lint_off UNUSEDSIGNAL
      logic unused_series;
      assign unused_series = ^series_i[SERIES_PER_LIGHT*SERIES_WL-1:SERIES_WL];
      // verilator lint_on UNUSEDSIGNAL
    end
  end else if (SPECULAR_KIND == shade_pkg::SpecSchlick) begin : g_schlick
    schlick_divider #(
      .SPEC_PARAMS(SPEC_PARAMS), .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
      .OUT_WL(SPECULAR_OUT_WL), .OUT_IWL(SPECULAR_OUT_IWL), .OUT_QUANT(SPECULAR_OUT_QUANT),
      .OUT_OVERFLOW(SPECULAR_OUT_OVERFLOW)
    ) u_schlick (
      .clk_i, .rst_ni, .en_i, .num_i(series_i[SERIES_WL-1:0]),
      .den_i(series_i[SERIES_PER_LIGHT*SERIES_WL-1 -: SERIES_WL]), .spec_o, .busy_o
    );
    // No per-material parameters and no table: the cfg port and the banks are not used.
    // verilator lint_off UNUSEDSIGNAL
    logic unused_cfg;
    assign unused_cfg = cfg_valid_i ^ cfg_table_i ^ (^cfg_addr_i) ^ (^cfg_data_i) ^ bank_i ^
                        cfg_bank_i ^ cfg_all_banks_i;
    // verilator lint_on UNUSEDSIGNAL
  end else if (SPECULAR_KIND == shade_pkg::SpecWpow) begin : g_wpow
    wpow_unit #(
      .SPEC_PARAMS(SPEC_PARAMS), .SERIES_WL(SERIES_WL), .SERIES_IWL(SERIES_IWL),
      .OUT_WL(SPECULAR_OUT_WL), .OUT_IWL(SPECULAR_OUT_IWL), .OUT_QUANT(SPECULAR_OUT_QUANT),
      .OUT_OVERFLOW(SPECULAR_OUT_OVERFLOW), .CFG_ADDR_W(16), .BANKS(MATERIAL_BUFFERS)
    ) u_wpow (
      .clk_i, .rst_ni, .en_i, .series_i(series_i[SERIES_WL-1:0]), .bank_i,
      .cfg_valid_i, .cfg_bank_i, .cfg_table_i, .cfg_addr_i, .cfg_data_i, .spec_o, .busy_o
    );
    // verilator lint_off UNUSEDSIGNAL
    logic unused_all_banks;  // W_m has no table
    assign unused_all_banks = cfg_all_banks_i;
    // verilator lint_on UNUSEDSIGNAL
    if (SERIES_PER_LIGHT > 1) begin : g_unused_series
      // verilator lint_off UNUSEDSIGNAL
      logic unused_series;
      assign unused_series = ^series_i[SERIES_PER_LIGHT*SERIES_WL-1:SERIES_WL];
      // verilator lint_on UNUSEDSIGNAL
    end
  end else begin : g_ideal
    // verilator lint_off UNUSEDSIGNAL
    logic unused_inputs;
    assign unused_inputs = clk_i ^ rst_ni ^ en_i ^ (^series_i) ^ cfg_valid_i ^ cfg_table_i ^
                           (^cfg_addr_i) ^ (^cfg_data_i) ^ bank_i ^ cfg_bank_i ^ cfg_all_banks_i;
    // verilator lint_on UNUSEDSIGNAL
    assign spec_o = '0;
    assign busy_o = 1'b0;
  end

`ifndef SYNTHESIS
  initial begin
    if (SPECULAR_KIND < shade_pkg::SpecIdeal || SPECULAR_KIND > shade_pkg::SpecWpow)
      $fatal(1, "specular_unit: SPECULAR_KIND %0d is not a unit (0 ideal .. 3 wpow)",
             SPECULAR_KIND);
    if (SPECULAR_KIND == shade_pkg::SpecSchlick && SERIES_PER_LIGHT != 2)
      $fatal(1, "specular_unit: schlick needs SERIES_PER_LIGHT = 2 (numerator, denominator)");
  end
`endif
endmodule
