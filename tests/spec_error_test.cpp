// The error yardstick and the setup plans: the Bishop & Weimer figures from the metric
// computation, metric sanity on known functions, plan affine maps, table splitting, the config
// JSON round trip of the unit widths.
#include <gtest/gtest.h>

#include <cmath>

#include "host/specular_setup.h"
#include "model/command_stream.h"

namespace shadesim {
namespace {

TEST(SpecError, BishopTableFiguresReproduce) {
  EXPECT_EQ(bishop_n_max(1024, 0.01, true), 20);
  EXPECT_EQ(bishop_n_max(8192, 0.01, true), 164);
  EXPECT_EQ(bishop_n_max_closed_form(1024, 0.01), 20);
  EXPECT_EQ(bishop_n_max_closed_form(8192, 0.01), 164);
  // Real 8-bit entries lose part of the budget to rounding (the top entry is 255/256).
  EXPECT_LT(bishop_n_max(1024, 0.01, false), 20);
  EXPECT_LT(bishop_n_max(8192, 0.01, false), 164);
}

TEST(SpecError, MetricsOnKnownFunctions) {
  for (double n : {1.0, 7.5, 500.0}) {
    const SpecErrors exact = measure_errors(n, [&](double t) { return std::pow(t, n); });
    EXPECT_EQ(exact.epi_rel, 0.0);
    EXPECT_EQ(exact.bloom_rel, 0.0);
    EXPECT_EQ(exact.abs_lsb, 0.0);
    const SpecErrors scaled = measure_errors(n, [&](double t) { return 1.01 * std::pow(t, n); });
    EXPECT_NEAR(scaled.epi_rel, 0.01, 1e-12);
    EXPECT_NEAR(scaled.bloom_rel, 0.01, 1e-12);
    EXPECT_NEAR(scaled.abs_lsb, 2.56, 1e-9);  // 1 % of full scale at t = 1
    const SpecErrors zero = measure_errors(n, [](double) { return 0.0; });
    EXPECT_NEAR(zero.epi_rel, 1.0, 1e-12);
    EXPECT_NEAR(zero.abs_lsb, 256.0, 1e-9);
  }
}

TEST(SpecError, PlansMapTheSeriesAsDocumented) {
  UnitConfig cfg;
  cfg.specular.kind = SpecularUnitKind::kWpow;
  const SpecularSeriesPlan w = plan_specular(cfg, 1000.0);
  ASSERT_EQ(w.affine.size(), 1u);
  const double zeta = 1000.0 / 16;
  const double k = std::ldexp(1.0, static_cast<int>(w.unit_params[0]));
  for (double t : {-1.0, 0.0, 0.5, 0.99, 1.0}) {
    EXPECT_NEAR((w.affine[0].first * t + w.affine[0].second) * k, zeta * (t - 1) + 1, 1e-9);
    EXPECT_LE(std::fabs(w.affine[0].first * t + w.affine[0].second),
              4.0);  // fits s4.28 with margin
  }
  EXPECT_EQ(w.unit_params[1], 4);

  cfg.specular.kind = SpecularUnitKind::kSchlick;
  const SpecularSeriesPlan s = plan_specular(cfg, 100.0);
  ASSERT_EQ(s.affine.size(), 2u);
  for (double t : {0.0, 0.3, 0.9, 1.0}) {
    const double num = s.affine[0].first * t + s.affine[0].second;
    const double den = s.affine[1].first * t + s.affine[1].second;
    EXPECT_NEAR(num / den, t / (100 - 100 * t + t), 1e-12);
  }
  EXPECT_TRUE(s.unit_params.empty());

  EXPECT_THROW(plan_specular(cfg, 0.0), std::invalid_argument);
  EXPECT_THROW(plan_specular(cfg, 2000.0), std::invalid_argument);
}

TEST(SpecError, LargeTablesSplitIntoCommands) {
  std::vector<int64_t> e(131072, 3);
  const auto cmds = to_table_commands(e);
  ASSERT_EQ(cmds.size(), 3u);
  EXPECT_EQ(cmds[0].base, 0u);
  EXPECT_EQ(cmds[1].base, 65535u);
  EXPECT_EQ(cmds[0].entries.size() + cmds[1].entries.size() + cmds[2].entries.size(), e.size());
}

TEST(SpecError, IdealUnitMeasuresNearZero) {
  UnitConfig cfg;
  const SpecErrors e = measure_unit(cfg, 50.0, 512);
  EXPECT_LT(e.abs_lsb, 0.01);
  EXPECT_LT(e.epi_rel, 1e-4);
}

TEST(SpecError, ConfigJsonRoundTripsUnitWidths) {
  UnitConfig c;
  c.specular.kind = SpecularUnitKind::kWpow;
  c.specular.wpow.max_m = 8;
  c.specular.wpow.base_bits = 12;
  c.specular.wpow.fit = FitObjective::kEpicentre;
  c.specular.lut.addr_bits = 13;
  c.specular.lut.addressing = LutAddressing::kShared;
  c.specular.schlick.quotient_bits = 9;
  c.specular.schlick.timing = UnitTiming::kPipelined;
  const UnitConfig d = config_from_json(config_to_json(c), "test: ");
  EXPECT_EQ(d.specular.wpow.max_m, 8);
  EXPECT_EQ(d.specular.wpow.base_bits, 12);
  EXPECT_EQ(d.specular.wpow.fit, FitObjective::kEpicentre);
  EXPECT_EQ(d.specular.lut.addr_bits, 13);
  EXPECT_EQ(d.specular.lut.addressing, LutAddressing::kShared);
  EXPECT_EQ(d.specular.schlick.quotient_bits, 9);
  EXPECT_EQ(d.specular.schlick.timing, UnitTiming::kPipelined);
  // Absent keys keep the defaults.
  const UnitConfig old = config_from_json(
      R"({"channels":1,"lights":1,"xy_bits":12,"coef":"s4.32:rnd:sat","series":"s4.28",)"
      R"("spec_colour":"u1.12:rnd:sat","out_bits":8,"specular":{"kind":"lut","out":"u1.16:sat"}})",
      "test: ");
  EXPECT_EQ(old.specular.lut.addr_bits, LutConfig{}.addr_bits);
  EXPECT_EQ(old.specular.wpow.max_m, 16);
  // Bad values name the field.
  try {
    config_from_json(
        R"({"channels":1,"lights":1,"xy_bits":12,"coef":"s4.32:rnd:sat","series":"s4.28",)"
        R"("spec_colour":"u1.12:rnd:sat","out_bits":8,"specular":{"kind":"wpow","out":"u1.16:sat","wpow":{"max_m":12}}})",
        "test: ");
    FAIL() << "expected an error";
  } catch (const CommandStreamError& e) {
    EXPECT_NE(std::string(e.what()).find("wpow.max_m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace shadesim
