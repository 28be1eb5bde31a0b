// The UnitConfig -> shade_unit parameter mapping (model/rtl_parameters.h) against the codes
// rtl/shade_unit.sv documents for its parameters, written out here by hand.
#include "model/rtl_parameters.h"

#include <gtest/gtest.h>

#include <map>
#include <stdexcept>
#include <string>

namespace shadesim {
namespace {

std::map<std::string, int64_t> as_map(const std::vector<VerilogParameter>& params) {
  std::map<std::string, int64_t> m;
  for (const auto& p : params) {
    EXPECT_TRUE(m.emplace(p.name, p.value).second) << "parameter " << p.name << " given twice";
  }
  return m;
}

TEST(RtlParameters, DefaultUnitMapsToItsWidthsAndCodes) {
  const auto m = as_map(shade_unit_parameters(UnitConfig{}));
  // UnitConfig's defaults: coef s4.32, series s4.28 truncate + wrap, spec colour u1.12,
  // specular out u1.16, 8-bit output, 12-bit coordinates, ideal unit, one-word port.
  const std::map<std::string, int64_t> want = {
      {"CHANNELS", 1},        {"LIGHTS", 1},           {"XY_BITS", 12},
      {"COEF_WL", 36},        {"COEF_IWL", 4},         {"SERIES_WL", 32},
      {"SERIES_IWL", 4},      {"SERIES_QUANT", 0},     {"SERIES_OVERFLOW", 1},
      {"SPEC_COLOUR_WL", 13}, {"SPEC_COLOUR_IWL", 1},  {"OUT_BITS", 8},
      {"SPECULAR_KIND", 0},   {"SPECULAR_OUT_WL", 17}, {"SPECULAR_OUT_IWL", 1},
      {"PORT_WORDS", 1},      {"TRI_QUEUE", 1},        {"LANES", 1}};
  EXPECT_EQ(m, want);
}

TEST(RtlParameters, EachUnitGetsOnlyItsOwnParameters) {
  UnitConfig u;
  u.channels = 3;
  u.lights = 2;
  u.series = parse_fixed_format("s3.20:rnd", "test");  // round, saturate
  u.specular.out = parse_fixed_format("u1.12:rnd", "test");
  u.specular.kind = SpecularUnitKind::kLut;
  u.specular.lut.index = LutIndex::kNearest;
  u.specular.lut.interp_bits = 4;
  auto m = as_map(shade_unit_parameters(u));
  EXPECT_EQ(m.at("SPECULAR_KIND"), 1);
  EXPECT_EQ(m.at("SERIES_QUANT"), 1);
  EXPECT_EQ(m.at("SERIES_OVERFLOW"), 0);
  EXPECT_EQ(m.at("SPECULAR_OUT_QUANT"), 1);
  EXPECT_EQ(m.at("SPECULAR_OUT_OVERFLOW"), 0);
  EXPECT_EQ(m.at("LUT_INDEX"), 1);
  EXPECT_EQ(m.at("LUT_INTERP_BITS"), 4);
  EXPECT_EQ(m.count("WPOW_MAX_M") + m.count("SCHLICK_TIMING"), 0u);

  u.specular.kind = SpecularUnitKind::kSchlick;
  u.specular.schlick.timing = UnitTiming::kPipelined;
  m = as_map(shade_unit_parameters(u));
  EXPECT_EQ(m.at("SPECULAR_KIND"), 2);
  EXPECT_EQ(m.at("SCHLICK_TIMING"), 0);
  EXPECT_EQ(m.count("LUT_INDEX"), 0u);

  u.specular.kind = SpecularUnitKind::kWpow;
  u.specular.wpow.timing = UnitTiming::kIterative;
  u.specular.wpow.base_bits = 12;
  m = as_map(shade_unit_parameters(u));
  EXPECT_EQ(m.at("SPECULAR_KIND"), 3);
  EXPECT_EQ(m.at("WPOW_TIMING"), 1);
  EXPECT_EQ(m.at("WPOW_BASE_BITS"), 12);
  EXPECT_EQ(m.count("SCHLICK_TIMING"), 0u);
}

TEST(RtlParameters, MaterialBuffersMapOnlyWhenTwo) {
  UnitConfig u;
  EXPECT_EQ(as_map(shade_unit_parameters(u)).count("MATERIAL_BUFFERS"), 0u);  // RTL default: 1
  u.material_buffers = 2;
  EXPECT_EQ(as_map(shade_unit_parameters(u)).at("MATERIAL_BUFFERS"), 2);
  u.material_buffers = 3;
  try {
    shade_unit_parameters(u);
    FAIL() << "material_buffers 3 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("material_buffers must be 1 or 2, got 3"),
              std::string::npos)
        << e.what();
  }
}

TEST(RtlParameters, NarrowedCoefficientTermsMapToTheirWidths) {
  UnitConfig u;
  u.coef = parse_fixed_format("s2.15:rnd:wrap", "test");
  u.series = parse_fixed_format("s2.14:wrap", "test");
  EXPECT_EQ(as_map(shade_unit_parameters(u)).count("COEF_T0_WL"), 0u);  // RTL default: COEF_WL
  u.coef_term_iwl = {2, 1, 0, -1, -2, -3};
  const auto m = as_map(shade_unit_parameters(u));
  // 15 fraction bits plus each term's integer bits.
  EXPECT_EQ(m.at("COEF_T0_WL"), 17);
  EXPECT_EQ(m.at("COEF_T1_WL"), 16);
  EXPECT_EQ(m.at("COEF_T2_WL"), 15);
  EXPECT_EQ(m.at("COEF_T3_WL"), 14);
  EXPECT_EQ(m.at("COEF_T4_WL"), 13);
  EXPECT_EQ(m.at("COEF_T5_WL"), 12);
  u.coef_term_iwl = {3, 1, 0, -1, -2, -3};  // more integer bits than coef
  EXPECT_THROW(shade_unit_parameters(u), std::invalid_argument);
}

TEST(RtlParameters, FaultsOnlyWhenInjectedAndToolSyntax) {
  EXPECT_EQ(as_map(shade_unit_parameters(UnitConfig{})).count("FAULT_LSB_ROW"), 0u);
  InjectedFaults f;
  f.stall_row = 23;
  const auto params = shade_unit_parameters(UnitConfig{}, f);
  const auto m = as_map(params);
  EXPECT_EQ(m.at("FAULT_STALL_ROW"), 23);
  EXPECT_EQ(m.count("FAULT_LSB_ROW"), 0u);
  EXPECT_EQ(m.count("FAULT_HANG_ROW"), 0u);
  InjectedFaults hang;
  hang.hang_row = 100;
  EXPECT_TRUE(hang.any());
  EXPECT_EQ(as_map(shade_unit_parameters(UnitConfig{}, hang)).at("FAULT_HANG_ROW"), 100);
  EXPECT_EQ(verilator_parameter_args(params).front(), "-GCHANNELS=1");
  EXPECT_EQ(iverilog_parameter_args(params, "tb").front(), "-Ptb.CHANNELS=1");
  EXPECT_EQ(yosys_chparam_args({{"A", 1}, {"B", -1}}), "-set A 1 -set B -1");
}

TEST(RtlParameters, AnInvalidUnitIsRefusedNamingTheField) {
  UnitConfig u;
  u.channels = 2;
  try {
    shade_unit_parameters(u);
    FAIL() << "channels = 2 was mapped";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("channels"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace shadesim
