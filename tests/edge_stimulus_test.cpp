// The "edge" scenario of sim/harness/random_stream.h reaches the corners it promises,
// measured on the streams and on what the model makes of them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "model/shade_unit.h"
#include "sim/harness/random_stream.h"
#include "sim/harness/rtl_config.h"

namespace shadesim {
namespace {

RtlConfig build(const std::string& name) {
  return named_build(std::string(SHADESIM_SOURCE_DIR) + "/sim/harness/builds.json", name);
}

CommandStream edge_stream(const UnitConfig& unit, uint64_t seed) {
  return random_stream(unit, scenario_by_name("edge").shape, seed);
}

TEST(EdgeStimulus, FullWidthSpansAndTheBottomRightCornerAt12Bits) {
  const UnitConfig unit = build("grey_s428w").unit;
  ASSERT_EQ(unit.xy_bits, 12);
  const int width = 1 << unit.xy_bits;
  bool full_width = false, corner = false, top_bit_x = false;
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    for (const Command& cmd : edge_stream(unit, seed).commands) {
      if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
        full_width = full_width || (s->x0 == 0 && s->length == width);
        corner = corner || (s->y == width - 1 && s->x0 + s->length == width);
        top_bit_x = top_bit_x || s->x0 >= width / 2;  // x0's MSB set
      }
    }
  }
  EXPECT_TRUE(full_width) << "no span of " << width << " pixels";
  EXPECT_TRUE(corner) << "no span ends at (" << width - 1 << ", " << width - 1 << ")";
  EXPECT_TRUE(top_bit_x) << "no span starts at x >= " << width / 2;
}

TEST(EdgeStimulus, SeveralFramesAndCommandsAfterEndFrame) {
  const CommandStream stream = edge_stream(build("lut_n").unit, 1);
  size_t frames = 0, spans_after_first_end = 0, commands_after_first_end = 0;
  for (const Command& cmd : stream.commands) {
    if (std::holds_alternative<EndFrameCmd>(cmd)) {
      ++frames;
    } else if (frames > 0) {
      ++commands_after_first_end;
      if (std::holds_alternative<SpanCmd>(cmd)) ++spans_after_first_end;
    }
  }
  EXPECT_EQ(frames, 3u);
  EXPECT_GT(spans_after_first_end, 0u);
  EXPECT_GT(commands_after_first_end, spans_after_first_end);  // triangles, materials too
}

// Schlick's divider with a numerator that is positive yet 0 in its operands (below 2^-D), beside
// a denominator at or below 0: the pair where the rules "den <= 0 gives 1" and "num_op = 0 gives
// 0" disagree, so their order shows. A triangle gives it where light l's numerator series is
// flat at such a value and its denominator series starts at or below 0.
TEST(EdgeStimulus, SchlickNumeratorBelowTheOperandLsbBesideADenominatorAtOrBelowZero) {
  const UnitConfig unit = build("schlick_iter_n").unit;
  ASSERT_EQ(unit.specular.kind, SpecularUnitKind::kSchlick);
  const double operand_lsb = std::ldexp(1.0, -unit.specular.schlick.operand_bits);
  const int per_light = unit.specular.series_per_light();
  int pairs = 0;
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    for (const Command& cmd : edge_stream(unit, seed).commands) {
      const auto* t = std::get_if<TriangleCmd>(&cmd);
      if (t == nullptr) continue;
      for (int l = 0; l < unit.lights; ++l) {
        const size_t num =
            static_cast<size_t>(unit.diffuse_series() + l * per_light) * kTermsPerSeries;
        const size_t den = num + kTermsPerSeries;
        const double num0 = unit.coef_term(0).to_double(t->coef[num]);
        bool flat = true;
        for (int k = 1; k < kTermsPerSeries; ++k) flat = flat && t->coef[num + k] == 0;
        pairs += flat && num0 > 0 && num0 < operand_lsb &&
                 unit.coef_term(0).to_double(t->coef[den]) <= 0;
      }
    }
  }
  EXPECT_GT(pairs, 0);
}

// Schlick's divider with a partial remainder exactly equal to the shifted denominator (the
// restoring step's r2 == den): the division ends with remainder 0 within Q steps, which for
// 0 < num < den happens exactly when num 2^Q / den is an integer (closed form, in double: every
// value here is a short dyadic). A triangle gives it where light l's numerator and denominator
// series are both flat at such a pair.
TEST(EdgeStimulus, SchlickRemainderMeetsTheDenominatorExactly) {
  for (const char* name : {"schlick_iter_n", "schlick_pipe_d"}) {
    const UnitConfig unit = build(name).unit;
    ASSERT_EQ(unit.specular.kind, SpecularUnitKind::kSchlick) << name;
    const int per_light = unit.specular.series_per_light();
    int pairs = 0;
    for (uint64_t seed = 1; seed <= 3; ++seed) {
      for (const Command& cmd : edge_stream(unit, seed).commands) {
        const auto* t = std::get_if<TriangleCmd>(&cmd);
        if (t == nullptr) continue;
        for (int l = 0; l < unit.lights; ++l) {
          const size_t num =
              static_cast<size_t>(unit.diffuse_series() + l * per_light) * kTermsPerSeries;
          const size_t den = num + kTermsPerSeries;
          bool flat = true;
          for (int k = 1; k < kTermsPerSeries; ++k)
            flat = flat && t->coef[num + k] == 0 && t->coef[den + k] == 0;
          const double n = unit.coef_term(0).to_double(t->coef[num]);
          const double d = unit.coef_term(0).to_double(t->coef[den]);
          const double scaled = std::ldexp(n / d, unit.specular.schlick.quotient_bits);
          pairs += flat && n > 0 && n < d && scaled == std::floor(scaled);
        }
      }
    }
    EXPECT_GT(pairs, 0) << name;
  }
}

// TABLE with no entry and with one (the payload FSM's shortest payloads), per-material and
// shared, in LUT and other units' streams; and the LUT's whole table (its most entries).
TEST(EdgeStimulus, TablesOfZeroOneAndAllEntries) {
  for (const char* name : {"lut_n", "grey_s428w", "wpow16_n"}) {
    const UnitConfig unit = build(name).unit;
    const size_t whole = size_t{1} << unit.specular.lut.addr_bits;
    bool empty = false, one = false, per_material = false, shared = false, all = false;
    for (uint64_t seed = 1; seed <= 3; ++seed) {
      for (const Command& cmd : edge_stream(unit, seed).commands) {
        const auto* t = std::get_if<TableCmd>(&cmd);
        if (t == nullptr) continue;
        empty = empty || t->entries.empty();
        one = one || t->entries.size() == 1;
        per_material = per_material || (t->entries.size() <= 1 && t->per_material);
        shared = shared || (t->entries.size() <= 1 && !t->per_material);
        all = all || t->entries.size() == whole;
      }
    }
    EXPECT_TRUE(empty) << name;
    EXPECT_TRUE(one) << name;
    EXPECT_TRUE(per_material && shared) << name;
    if (unit.specular.kind == SpecularUnitKind::kLut) EXPECT_TRUE(all) << name;
  }
}

// Output codes at both clamps: totals below 0 (negative ambient) give 0, totals above 1 give
// all ones; and the negative totals really are there (a negative ambient word).
TEST(EdgeStimulus, OutputClampsAtBothEnds) {
  for (const char* name : {"grey_s428w", "rgb2_s320s", "wpow16_n"}) {
    const UnitConfig unit = build(name).unit;
    const CommandStream stream = edge_stream(unit, 1);
    bool negative_ambient = false;
    for (const Command& cmd : stream.commands) {
      if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
        negative_ambient = negative_ambient || std::any_of(m->ambient.begin(), m->ambient.end(),
                                                           [](int64_t a) { return a < 0; });
      }
    }
    ShadeUnit model(unit);
    const uint16_t top = static_cast<uint16_t>((1 << unit.out_bits) - 1);
    bool zero = false, saturated = false;
    for (const PixelOut& p : model.run(stream)) {
      for (int c = 0; c < unit.channels; ++c) {
        zero = zero || p.colour[c] == 0;
        saturated = saturated || p.colour[c] == top;
      }
    }
    EXPECT_TRUE(negative_ambient) << name;
    EXPECT_TRUE(zero) << name << ": no output code 0";
    EXPECT_TRUE(saturated) << name << ": no output code " << top;
  }
}

// In a saturating build the series leave their format: the same stream shaded with the series
// wrapping instead gives different pixels.
TEST(EdgeStimulus, SeriesSaturateInSaturatingBuilds) {
  for (const char* name : {"rgb2_s320s", "lut_n", "wpow16_n"}) {
    const UnitConfig unit = build(name).unit;
    ASSERT_EQ(unit.series.overflow, Overflow::kSaturate) << name;
    const CommandStream stream = edge_stream(unit, 1);
    UnitConfig wrapping = unit;
    wrapping.series.overflow = Overflow::kWrap;
    ShadeUnit sat_model(unit), wrap_model(wrapping);
    const std::vector<PixelOut> sat = sat_model.run(stream), wrap = wrap_model.run(stream);
    ASSERT_EQ(sat.size(), wrap.size());
    size_t differing = 0;
    for (size_t i = 0; i < sat.size(); ++i) differing += sat[i].colour != wrap[i].colour;
    EXPECT_GT(differing, 0u) << name << ": no series ever left the series format";
  }
}

// Every LUT and W_m shift 0..frac_bits(series), every squaring count, fractional exponents,
// and non-zero specular colour in the hardware units' streams.
TEST(EdgeStimulus, FullRangeOfUnitParameters) {
  for (const char* name : {"lut_d", "wpow16_n"}) {
    const UnitConfig unit = build(name).unit;
    const int fs = unit.series.frac_bits();
    std::vector<bool> shifts(static_cast<size_t>(fs) + 1, false);
    bool fractional = false, spec_colour = false;
    for (uint64_t seed = 1; seed <= 40; ++seed) {
      for (const Command& cmd : edge_stream(unit, seed).commands) {
        if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
          if (!m->unit_params.empty()) shifts.at(static_cast<size_t>(m->unit_params[0])) = true;
          fractional = fractional || (m->exponent & 0xffff) != 0;
          spec_colour = spec_colour || std::any_of(m->spec_colour.begin(), m->spec_colour.end(),
                                                   [](int64_t k) { return k > 0; });
        }
      }
    }
    EXPECT_TRUE(shifts.front() && shifts.back())
        << name << ": shifts 0 and " << fs << " not both used";
    EXPECT_GE(std::count(shifts.begin(), shifts.end(), true), fs * 3 / 4) << name;
    EXPECT_TRUE(fractional) << name;
    EXPECT_TRUE(spec_colour) << name;
  }
}

}  // namespace
}  // namespace shadesim

namespace shadesim {
namespace {

// The cosim tests of the hardware specular builds demand that the specular term change at
// least 25 % of the pixels of every run (--min-spec-pct 25 in cmake/rtl.cmake), "edge" included.
// In the grey one-light form (C++ only: there is no such RTL build) it must show too, in at
// least 10 % of the pixels.
TEST(EdgeStimulus, SpecularTermShowsInHardwareBuilds) {
  const std::vector<RtlConfig> builds =
      load_named_builds(std::string(SHADESIM_SOURCE_DIR) + "/sim/harness/builds.json");
  for (const RtlConfig& named : builds) {
    if (named.unit.specular.kind == SpecularUnitKind::kIdeal) continue;
    const char* name = named.name.c_str();
    for (const bool grey : {false, true}) {
      UnitConfig unit = named.unit;
      if (grey) unit.channels = unit.lights = 1;
      const CommandStream stream = edge_stream(unit, 21);
      CommandStream dark = stream;
      for (Command& cmd : dark.commands) {
        if (auto* m = std::get_if<MaterialCmd>(&cmd))
          std::fill(m->spec_colour.begin(), m->spec_colour.end(), 0);
      }
      ShadeUnit lit_model(unit), dark_model(unit);
      const std::vector<PixelOut> lit = lit_model.run(stream), unlit = dark_model.run(dark);
      size_t changed = 0;
      for (size_t i = 0; i < lit.size(); ++i) changed += lit[i].colour != unlit[i].colour;
      const double pct = 100.0 * static_cast<double>(changed) / static_cast<double>(lit.size());
      std::printf("%s%s: specular changes %.1f%% of %zu pixels\n", name, grey ? " grey1L" : "", pct,
                  lit.size());
      if (unit.specular.kind == SpecularUnitKind::kNone) {
        EXPECT_EQ(changed, 0u) << name << (grey ? " grey1L" : "") << ": none has no specular term";
        continue;
      }
      EXPECT_GE(pct, grey ? 10.0 : 25.0) << name << (grey ? " grey1L" : "");
    }
  }
}

}  // namespace
}  // namespace shadesim
