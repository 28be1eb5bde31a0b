// The UnitConfig -> shade_unit parameter mapping (model/rtl_parameters.h) against the codes
// rtl/shade_unit.sv documents for its parameters, written out here by hand.
#include "model/rtl_parameters.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace shadesim {
namespace {

// parameter_map's form: SPEC_PARAMS as "SPEC_PARAMS[k]", one entry per slot.
std::map<std::string, int64_t> as_map(const std::vector<VerilogParameter>& params) {
  std::set<std::string> names;
  for (const auto& p : params) {
    EXPECT_TRUE(names.insert(p.name).second) << "parameter " << p.name << " given twice";
  }
  return parameter_map(params);
}

// The selected unit's SPEC_PARAMS slots, in slot order.
std::vector<int64_t> spec_slots(const std::vector<VerilogParameter>& params) {
  for (const auto& p : params) {
    if (p.name == "SPEC_PARAMS") return p.slots;
  }
  ADD_FAILURE() << "no SPEC_PARAMS";
  return {};
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
  u.series = parse_fixed_format("s3.20:rnd:sat", "test");  // round, saturate
  u.specular.out = parse_fixed_format("u1.12:rnd:sat", "test");
  u.specular.kind = SpecularUnitKind::kLut;
  u.specular.lut.index = LutIndex::kNearest;
  u.specular.lut.interp_bits = 4;
  auto m = as_map(shade_unit_parameters(u));
  EXPECT_EQ(m.at("SPECULAR_KIND"), 1);
  EXPECT_EQ(m.at("SERIES_QUANT"), 1);
  EXPECT_EQ(m.at("SERIES_OVERFLOW"), 0);
  EXPECT_EQ(m.at("SPECULAR_OUT_QUANT"), 1);
  EXPECT_EQ(m.at("SPECULAR_OUT_OVERFLOW"), 0);
  // rtl/exponent_lut.sv's slots: 0 ADDR_BITS, 1 ENTRY_BITS, 2 INTERP_BITS, 3 INDEX; the rest 0.
  EXPECT_EQ(spec_slots(shade_unit_parameters(u)), (std::vector<int64_t>{10, 8, 4, 1, 0, 0, 0, 0}));

  u.specular.kind = SpecularUnitKind::kSchlick;
  u.specular.schlick.timing = UnitTiming::kPipelined;
  m = as_map(shade_unit_parameters(u));
  EXPECT_EQ(m.at("SPECULAR_KIND"), 2);
  // rtl/schlick_divider.sv's slots: 0 QUOTIENT_BITS, 1 OPERAND_BITS, 2 TIMING.
  EXPECT_EQ(spec_slots(shade_unit_parameters(u)), (std::vector<int64_t>{16, 24, 0, 0, 0, 0, 0, 0}));

  u.specular.kind = SpecularUnitKind::kWpow;
  u.specular.wpow.timing = UnitTiming::kIterative;
  u.specular.wpow.base_bits = 12;
  m = as_map(shade_unit_parameters(u));
  EXPECT_EQ(m.at("SPECULAR_KIND"), 3);
  // rtl/wpow_unit.sv's slots: 0 MAX_M, 1 BASE_BITS, 2 TIMING, 3 SQUARE_STAGES.
  EXPECT_EQ(spec_slots(shade_unit_parameters(u)), (std::vector<int64_t>{16, 12, 1, 1, 0, 0, 0, 0}));
  EXPECT_EQ(m.at("SPEC_PARAMS[1]"), 12);

  // The ideal unit has no hardware and no SPEC_PARAMS (shade_unit's default, '0).
  u.specular.kind = SpecularUnitKind::kIdeal;
  EXPECT_EQ(as_map(shade_unit_parameters(u)).count("SPEC_PARAMS[0]"), 0u);
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

// START_DEPTH only with host span setup (a unit-setup unit has no start bank), from start_depth.
TEST(RtlParameters, StartDepthMapsOnlyWithHostSetup) {
  UnitConfig u;
  u.start_depth = 1;
  EXPECT_EQ(as_map(shade_unit_parameters(u)).count("START_DEPTH"), 0u);
  u.span_setup = SpanSetupSite::kHost;
  u.tri_queue = 1;
  EXPECT_EQ(as_map(shade_unit_parameters(u)).at("START_DEPTH"), 1);
  u.start_depth = 2;
  EXPECT_EQ(as_map(shade_unit_parameters(u)).at("START_DEPTH"), 2);
  u.start_depth = 0;
  EXPECT_THROW(shade_unit_parameters(u), std::invalid_argument);
}

// COMBINE_STAGES only when pipelined (unpipelined units keep their parameter list and build key).
TEST(RtlParameters, CombineStagesMapOnlyWhenPipelined) {
  UnitConfig u;
  EXPECT_EQ(as_map(shade_unit_parameters(u)).count("COMBINE_STAGES"), 0u);
  u.combine_stages = 1;
  EXPECT_EQ(as_map(shade_unit_parameters(u)).at("COMBINE_STAGES"), 1);
  u.combine_stages = 2;
  EXPECT_EQ(as_map(shade_unit_parameters(u)).at("COMBINE_STAGES"), 2);
  u.combine_stages = 3;
  EXPECT_THROW(shade_unit_parameters(u), std::invalid_argument);
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

TEST(RtlParameters, ToolSyntax) {
  const auto params = shade_unit_parameters(UnitConfig{});
  EXPECT_EQ(verilator_parameter_args(params).front(), "-GCHANNELS=1");
  EXPECT_EQ(iverilog_parameter_args(params, "tb").front(), "-Ptb.CHANNELS=1");
  EXPECT_EQ(yosys_chparam_args({{"A", 1}, {"B", -1}}), "-set A 1 -set B -1");
}

TEST(RtlParameters, PackedSpecParamsIsOneSizedHexLiteralInEveryTool) {
  // Slot k is bits [32k +: 32] of a 256-bit value (rtl/shade_pkg.sv SpecSlots 8, SpecSlotW 32),
  // written out by hand: slot 0 (10 = 0xa) is the last 8 hex digits.
  const VerilogParameter p{"SPEC_PARAMS", std::vector<int64_t>{10, 8, 4, 1, 0, 0, 0, 0}};
  const std::string want =
      "256'h00000000000000000000000000000000000000010000000400000008"
      "0000000a";
  EXPECT_EQ(p.literal(), want);
  EXPECT_EQ(verilator_parameter_args({p}).front(), "-GSPEC_PARAMS=" + want);
  EXPECT_EQ(iverilog_parameter_args({p}, "tb").front(), "-Ptb.SPEC_PARAMS=" + want);
  EXPECT_EQ(yosys_chparam_args({p}), "-set SPEC_PARAMS " + want);
  EXPECT_EQ(VerilogParameter("X", std::vector<int64_t>{0xFFFFFFFFLL}).literal(), "32'hffffffff");
  EXPECT_THROW(VerilogParameter("X", std::vector<int64_t>{-1}).literal(), std::logic_error);
  const auto m = parameter_map({p, VerilogParameter("LANES", 2)});
  EXPECT_EQ(m.at("SPEC_PARAMS[0]"), 10);
  EXPECT_EQ(m.at("SPEC_PARAMS[3]"), 1);
  EXPECT_EQ(m.at("SPEC_PARAMS[7]"), 0);
  EXPECT_EQ(m.at("LANES"), 2);
  EXPECT_EQ(m.count("SPEC_PARAMS"), 0u);
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
