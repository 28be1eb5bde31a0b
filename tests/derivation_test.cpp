// The derivation's formats and specular search, and the warnings on the unit under
// test, on scenes nobody tuned for (made here). Expected values are computed here from the scene
// numbers (colour products, the colour rule's closed form) or measured independently by shading
// the scene on the chosen unit against the double reference (render_at).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "derive/accuracy_checks.h"
#include "derive/budget.h"
#include "derive/derive_config.h"
#include "host/frame.h"
#include "host/scene_error.h"
#include "tests/support/render_at.h"
#include "tests/support/sphere_scene.h"

namespace shadesim {
namespace {

class Derivation : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("shadesim_derivation_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // A 96x96 sphere of `tessellation` under one light with one material.
  std::string write_scene(const std::string& name, const nlohmann::json& light_colour,
                          const nlohmann::json& material, int tessellation = 24) const {
    nlohmann::json s = test::sphere_scene(light_colour, material, tessellation);
    std::string path = (dir_ / (name + ".json")).string();  // returned: moved
    std::ofstream(path) << s.dump();
    return path;
  }

  static nlohmann::json material(const std::string& unit, double exponent, double specular = 0.6,
                                 double diffuse = 0.5) {
    return {{"name", "m"},          {"ambient", 0.05},      {"diffuse", diffuse},
            {"specular", specular}, {"exponent", exponent}, {"unit", unit}};
  }

  std::filesystem::path dir_;
};

double top_of(const FixedFormat& f) {
  return std::ldexp(static_cast<double>(f.raw_max()), -f.frac_bits());
}

std::string specular_reason(const DerivedConfig& d) {
  for (const auto& r : d.reasons) {
    if (r.field == "specular") return r.reason;
  }
  return "";
}

TEST_F(Derivation, OverbrightRgbLightGetsColourAndSeriesFormatsThatHoldIt) {
  // Light (30, 15, 7.5), kd 0.5, ks 0.6: kd_c L_c reaches 15 and ks_c L_c 18 (computed here).
  const std::string path = write_scene("rgb", {30, 15, 7.5}, material("ideal", 60));
  const DerivedConfig d = derive_config({path}, DeriveOptions{});
  const UnitConfig& u = d.config;
  ASSERT_TRUE(u.diffuse_multiply());
  const double colour_max = 0.6 * 30;
  EXPECT_GE(top_of(u.spec_colour), colour_max) << u.spec_colour.to_string();
  EXPECT_LT(top_of(u.spec_colour) / 2, colour_max) << "one integer bit fewer would hold it";
  // The series brings each colour product into its format: it holds 18 too.
  EXPECT_GT(std::ldexp(1.0, u.series.iwl - 1), colour_max) << u.series.to_string();
  // The colour rule's closed form: per light, 1/2 (specular rounding) + 1/2 + kd_c L_c
  // (multiplied rounding and N.L truncation), times 2^-F, within 3/16 LSB at 8 bits.
  const double weight = 0.5 + 0.5 + 0.5 * 30;
  const int frac = u.spec_colour.frac_bits();
  EXPECT_LE(weight * std::ldexp(1.0, -frac), 0.1875 / 256);
  EXPECT_GT(weight * std::ldexp(1.0, -(frac - 1)), 0.1875 / 256) << "F is the fewest";
  // Independently: the derived unit shades the scene within the 1 LSB budget.
  EXPECT_LE(render_at(path, u).max_code_lsb, 1);
}

TEST_F(Derivation, WarningsCheckTheUnitUnderTestNotATrialUnit) {
  // At default widths (one channel would be the trial's; this unit has three and the colour in
  // the series), a colour of 30 overflows s4.28 and saturates u1.12: both named, with widths.
  const std::string path = write_scene("rgb", {30, 15, 7.5}, material("ideal", 60));
  UnitConfig unit;
  unit.channels = 3;
  FrameOptions fo;
  fo.base = unit;
  fo.fixed_unit = true;
  const PreparedFrame frame = prepare_frame(path, fo);
  const ErrorStats e = render_at(path, frame.config);
  ASSERT_GT(e.max_code_lsb, 100);
  const PreparedScene prepared(path, PrepareKey{std::nullopt, 12, frame.config.out_bits});
  const auto w = accuracy_warnings(prepared, frame.config, frame.encoded.stream, e);
  auto has = [&w](const std::string& text) {
    return std::any_of(w.begin(), w.end(),
                       [&](const std::string& s) { return s.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(has("series s4.28: series values")) << ::testing::PrintToString(w);
  EXPECT_TRUE(has("spec_colour u1.12:rnd:sat")) << ::testing::PrintToString(w);
  EXPECT_TRUE(has("u5.12 would hold them")) << ::testing::PrintToString(w);  // 18 < 2^5
  EXPECT_TRUE(has("the unit's formats")) << ::testing::PrintToString(w);
  // The scene's own unit holds it: no warning.
  const UnitConfig own = derive_config({path}, DeriveOptions{}).config;
  FrameOptions own_fo;
  own_fo.base = own;
  own_fo.fixed_unit = true;
  const PreparedFrame own_frame = prepare_frame(path, own_fo);
  const ErrorStats own_e = render_at(path, own);
  const PreparedScene own_prepared(path, PrepareKey{std::nullopt, 12, own.out_bits});
  EXPECT_TRUE(accuracy_warnings(own_prepared, own, own_frame.encoded.stream, own_e).empty());
}

TEST_F(Derivation, AMissIsExplainedByTheSpecularUnitWhenExactPowMeetsTheBudget) {
  // Schlick's lobe at n = 60 is far from t^n: its default unit is tens of LSB off.
  const std::string path = write_scene("schlick", 1.0, material("schlick", 60));
  UnitConfig unit;
  unit.specular.kind = SpecularUnitKind::kSchlick;
  const ErrorStats e = render_at(path, unit);
  ASSERT_GT(e.max_code_lsb, 1);
  UnitConfig exact = unit;
  exact.specular.kind = SpecularUnitKind::kIdeal;
  ASSERT_LE(render_at(path, exact).max_code_lsb, 1);  // the premise, measured
  const std::string why =
      explain_miss(PreparedScene(path, PrepareKey{std::nullopt, 12, unit.out_bits}), unit, e);
  EXPECT_NE(why.find("approximates t^n too coarsely"), std::string::npos) << why;
}

TEST_F(Derivation, AMissNeitherUnitNorFormatsCauseIsMeasuredOnTheTaylorSetup) {
  // No subdivision (--max-depth 0) on a coarse sphere: the Taylor error alone misses 1 LSB, on
  // exact pow and formats that lose nothing alike, and still four levels deeper (measured here
  // on the default unit): no cause is verified, so none is named (tests/miss_causes_test.cpp
  // has the one deeper subdivision mends).
  const std::string path = write_scene("coarse", 1.0, material("ideal", 60), 4);
  UnitConfig unit;
  const ErrorStats e = render_at(path, unit, std::nullopt, 0);
  ASSERT_GT(e.max_code_lsb, 1);
  ASSERT_GT(render_at(path, unit, std::nullopt, 4).max_code_lsb, 1);
  const std::string why =
      explain_miss(PreparedScene(path, PrepareKey{std::nullopt, 0, unit.out_bits}), unit, e);
  EXPECT_NE(why.find("the cause is unknown"), std::string::npos) << why;
  EXPECT_NE(why.find("at --max-depth 4 it is"), std::string::npos) << why;
  EXPECT_NE(why.find("at --max-depth 0"), std::string::npos) << why;
}

TEST_F(Derivation, WhereExactPowMissesTooNoOtherUnitIsTried) {
  // The same Taylor miss through derive_config: no specular unit can mend it, so none is tried
  // after the first, and the unit misses the budget (measured independently).
  const std::string path = write_scene("coarse", 1.0, material("ideal", 60), 4);
  DeriveOptions o;
  o.max_depth = 0;
  const DerivedConfig d = derive_config({path}, o);
  EXPECT_NE(specular_reason(d).find("no other unit is tried"), std::string::npos)
      << specular_reason(d);
  EXPECT_GT(render_at(path, d.config, std::nullopt, 0).max_code_lsb, 1);
}

TEST_F(Derivation, ANamedLutIsSearchedToTheBudget) {
  // n = 500 on the LUT's defaults (A=10 B=8, no interpolation) is over 1 LSB; the search finds
  // fields that meet it, and render confirms them.
  const std::string path = write_scene("lut", 1.0, material("lut", 500));
  UnitConfig defaults;
  defaults.specular.kind = SpecularUnitKind::kLut;
  ASSERT_GT(render_at(path, defaults).max_code_lsb, 1);
  const DerivedConfig d = derive_config({path}, DeriveOptions{});
  EXPECT_EQ(d.config.specular.kind, SpecularUnitKind::kLut);
  EXPECT_LE(render_at(path, d.config).max_code_lsb, 1) << d.config.specular.describe();
  DeriveOptions keep;
  keep.search_named_units = false;
  EXPECT_EQ(derive_config({path}, keep).config.specular.lut.entry_bits, 8);
}

TEST_F(Derivation, SchlickThatNoFieldsMendKeepsTheClosestAndNamesTheLimit) {
  const std::string path = write_scene("schlick", 1.0, material("schlick", 60));
  const DerivedConfig d = derive_config({path}, DeriveOptions{});
  const std::string why = specular_reason(d);
  EXPECT_NE(why.find("What limits it is the schlick unit's function"), std::string::npos) << why;
  // The closest kept: no candidate tried is better (its error, measured here, is the least).
  const int kept = render_at(path, d.config).max_code_lsb;
  UnitConfig plain;
  plain.specular.kind = SpecularUnitKind::kSchlick;
  EXPECT_LT(kept, render_at(path, plain).max_code_lsb);
}

TEST_F(Derivation, ColourProductsWithTheTaylorOvershootFitTheSeries) {
  // A random scene (kept: tests/data/random_scenes/) with seven lights and kd_c L_c up to 1.88,
  // multiplied: N.L's series overshoots 1 (1.35), so a product reaches 2.5 and wrapped a s2
  // series (255 LSB) while every colour word and series value fit it. The derived unit holds it.
  const std::string path =
      std::string(SHADESIM_SOURCE_DIR) + "/tests/data/random_scenes/s1_i00882.json";
  const DerivedConfig d = derive_config({path}, DeriveOptions{});
  ASSERT_TRUE(d.config.diffuse_multiply());
  EXPECT_GE(d.measured.product_max, 2.0);
  EXPECT_GT(std::ldexp(1.0, d.config.series.iwl - 1), d.measured.product_max);
  EXPECT_LE(render_at(path, d.config).max_code_lsb, 1) << d.config.to_string();
}

TEST_F(Derivation, BudgetsOtherThanOneLsb) {
  // A looser budget derives narrower series and coefficients; each unit meets its own budget
  // (in output codes: ceil) by the independent measurement.
  const std::string path = write_scene("grey", 1.0, material("ideal", 20));
  DeriveOptions tight, loose;
  tight.budget_lsb = 0.5;
  loose.budget_lsb = 3;
  const DerivedConfig t = derive_config({path}, tight);
  const DerivedConfig l = derive_config({path}, loose);
  EXPECT_LT(l.config.series.frac_bits(), t.config.series.frac_bits());
  EXPECT_LT(l.config.coef.frac_bits(), t.config.coef.frac_bits());
  EXPECT_LE(render_at(path, t.config, 0.5, 12).max_code_lsb, code_budget(0.5));
  EXPECT_LE(render_at(path, l.config, 3.0, 12).max_code_lsb, code_budget(3.0));
}

}  // namespace
}  // namespace shadesim
