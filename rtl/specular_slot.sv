// specular_slot: the place of one light's specular unit (model/specular_unit.h, class
// SpecularUnit). This milestone has no specular hardware: the slot outputs 0, so the unit is
// bit-exact with the model whenever MATERIAL's spec_colour is 0 (PixelCombine adds s*0 = 0).
// The ports are the ones the LUT / Schlick / W_m units will need: this light's specular series
// values, a per-pixel enable, and the configuration words of MATERIAL (exponent, unit
// parameters) and TABLE commands. Combinational today; LATENCY > 0 units must be matched by
// a delay line in shade_unit (see rtl.md).
module specular_slot #(
  // verilator lint_off UNUSED
  parameter int SPECULAR_KIND    = 0,  // SpecularUnitKind: 0 ideal, 1 lut, 2 schlick, 3 wpow
  // verilator lint_on UNUSED
  parameter int SERIES_WL        = 32,
  parameter int SERIES_PER_LIGHT = 1,
  parameter int SPECULAR_OUT_WL  = 17
) (
  input  logic                                  clk_i,
  input  logic                                  rst_ni,
  input  logic                                  en_i,
  input  logic [SERIES_PER_LIGHT*SERIES_WL-1:0] series_i,
  input  logic                                  cfg_valid_i,
  input  logic                                  cfg_table_i,  // 1: TABLE entry, 0: MATERIAL word
  input  logic [15:0]                           cfg_addr_i,   // table address / material index
  input  logic [63:0]                           cfg_data_i,
  output logic [SPECULAR_OUT_WL-1:0]            spec_o
);
  // verilator lint_off UNUSED
  logic unused_inputs;
  assign unused_inputs = clk_i ^ rst_ni ^ en_i ^ (^series_i) ^ cfg_valid_i ^ cfg_table_i ^
                         (^cfg_addr_i) ^ (^cfg_data_i);
  // verilator lint_on UNUSED
  assign spec_o = '0;
endmodule
