// ShadeUnit against the independent golden model (tests/golden/): every named build's
// configuration of sim/harness/builds.json, on the co-simulation's random streams.
#include <gtest/gtest.h>

#include <cctype>
#include <ostream>
#include <string>
#include <vector>

#include "model/host_setup.h"
#include "model/shade_unit.h"
#include "model/unit_config_file.h"
#include "sim/harness/random_stream.h"
#include "sim/harness/rtl_config.h"
#include "tests/golden/golden_unit.h"

namespace shadesim {

// gtest prints a parameter that fails; the name is all a reader needs.
void PrintTo(const RtlConfig& build, std::ostream* os) { *os << build.name; }

namespace {

FixedFormat format(int wl, int iwl, bool is_signed, Quantization q, Overflow o) {
  FixedFormat f;
  f.wl = wl;
  f.iwl = iwl;
  f.is_signed = is_signed;
  f.quant = q;
  f.overflow = o;
  return f;
}

// The oracle's sc_fix conversion on values worked out by hand.
TEST(GoldenQuantize, HandWorkedValues) {
  const FixedFormat s4_0_trn = format(4, 4, true, Quantization::kTruncate, Overflow::kWrap);
  const FixedFormat s4_0_rnd = format(4, 4, true, Quantization::kRoundNearest, Overflow::kWrap);
  const FixedFormat s4_0_sat = format(4, 4, true, Quantization::kTruncate, Overflow::kSaturate);
  EXPECT_EQ(golden::sc_quantize(-5, 1, s4_0_trn), -3);  // -2.5 toward -inf
  EXPECT_EQ(golden::sc_quantize(-5, 1, s4_0_rnd), -2);  // -2.5 half up
  EXPECT_EQ(golden::sc_quantize(5, 1, s4_0_rnd), 3);    // 2.5 half up
  EXPECT_EQ(golden::sc_quantize(9, 0, s4_0_trn), -7);   // 9 mod 16 = 9 -> -7
  EXPECT_EQ(golden::sc_quantize(9, 0, s4_0_sat), 7);
  EXPECT_EQ(golden::sc_quantize(-100, 0, s4_0_sat), -8);
  const FixedFormat u0_8 = format(8, 0, false, Quantization::kRoundNearest, Overflow::kSaturate);
  EXPECT_EQ(golden::sc_quantize(-1, 0, u0_8), 0);
  EXPECT_EQ(golden::sc_quantize(255, 8, u0_8), 255);
  EXPECT_EQ(golden::sc_quantize(511, 9, u0_8), 255);  // 0.998 rounds to 1.0, saturates
  EXPECT_EQ(golden::sc_quantize(0.5, u0_8), 128);
  // A 100-bit value: the conversion keeps every bit before it reduces.
  const __int128 big = (__int128{1} << 100) + 3;
  const FixedFormat s8_0 = format(8, 8, true, Quantization::kTruncate, Overflow::kWrap);
  EXPECT_EQ(golden::sc_quantize(big, 0, s8_0), 3);
  EXPECT_EQ(golden::sc_quantize(-big, 0, s8_0), -3);
}

struct Mismatch {
  size_t compared = 0;
  size_t differing = 0;
  std::string first;
};

Mismatch compare(const CommandStream& stream, const UnitConfig& model_config) {
  // A host-setup unit's model runs on the stream's host-setup form; the golden model, which
  // has only its own span setup, on the unit-setup stream itself.
  ShadeUnit unit(model_config);
  const std::vector<PixelOut> model =
      model_config.host_setup() ? unit.run(with_host_setup(stream)) : unit.run(stream);
  const std::vector<golden::Pixel> gold = golden::shade(stream);
  Mismatch m;
  if (model.size() != gold.size()) {
    m.differing = 1;
    m.first = "pixel counts differ: model " + std::to_string(model.size()) + ", golden " +
              std::to_string(gold.size());
    return m;
  }
  for (size_t i = 0; i < model.size(); ++i) {
    ++m.compared;
    bool same = model[i].x == gold[i].x && model[i].y == gold[i].y &&
                model[i].end_of_row == gold[i].end_of_row;
    for (int c = 0; c < stream.config.channels; ++c)
      same = same && model[i].colour[c] == gold[i].colour[c];
    if (!same) {
      if (m.differing++ == 0) {
        // every channel: the one that differs need not be the first
        std::string model_colour, gold_colour;
        for (int c = 0; c < stream.config.channels; ++c) {
          model_colour += (c ? "," : "") + std::to_string(model[i].colour[c]);
          gold_colour += (c ? "," : "") + std::to_string(gold[i].colour[c]);
        }
        m.first = "pixel " + std::to_string(i) + " (" + std::to_string(gold[i].x) + "," +
                  std::to_string(gold[i].y) + "): model " + model_colour + " golden " + gold_colour;
      }
    }
  }
  return m;
}

// Every configuration of builds.json, and (C++ only: there is no such RTL build) the grey
// one-light variant of each with a hardware specular unit, so specular colour is exercised there.
std::vector<RtlConfig> configurations() {
  std::vector<RtlConfig> all =
      load_named_builds(std::string(SHADESIM_SOURCE_DIR) + "/sim/harness/builds.json");
  const size_t named = all.size();
  for (size_t i = 0; i < named; ++i) {
    if (all[i].unit.specular.kind == SpecularUnitKind::kIdeal) continue;
    RtlConfig grey = all[i];
    grey.name += "+grey1L";
    grey.unit.channels = 1;
    grey.unit.lights = 1;
    all.push_back(grey);
  }
  return all;
}

// One seed of each: "edge" covers the corners (full-width spans, saturation, every shift),
// "switch" the material switches and TABLE reloads, "short" / "mixed" the common case.
const std::vector<std::string> kScenarios = {"mixed", "short", "switch", "edge"};

class GoldenModelOnBuild : public testing::TestWithParam<RtlConfig> {};

TEST_P(GoldenModelOnBuild, AgreesWithShadeUnitOnRandomStreams) {
  const RtlConfig& build = GetParam();
  size_t pixels = 0;
  // The golden model shades the unit-setup stream of the same frame (random_stream makes a
  // host-setup build's stream from it with the same seed).
  UnitConfig unit_setup = build.unit;
  unit_setup.span_setup = SpanSetupSite::kUnit;
  for (const std::string& name : kScenarios) {
    const CommandStream stream = random_stream(unit_setup, scenario_by_name(name).shape, 1);
    const Mismatch m = compare(stream, build.unit);
    EXPECT_EQ(m.differing, 0u) << build.name << " " << name << ": " << m.differing << " of "
                               << m.compared << " pixels differ; first " << m.first;
    pixels += m.compared;
  }
  EXPECT_GT(pixels, 1000u);
}

INSTANTIATE_TEST_SUITE_P(Builds, GoldenModelOnBuild, testing::ValuesIn(configurations()),
                         [](const testing::TestParamInfo<RtlConfig>& info) {
                           std::string name = info.param.name;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

// The comparison can fail: the model run with the series' rounding flipped (truncate <-> round
// to nearest) disagrees with the golden model of the stream's own configuration.
TEST(GoldenModel, DetectsAWrongRoundingOfTheSeries) {
  const RtlConfig build =
      named_build(std::string(SHADESIM_SOURCE_DIR) + "/sim/harness/builds.json", "grey_s428w");
  const CommandStream stream = random_stream(build.unit, scenario_by_name("mixed").shape, 1);
  UnitConfig wrong = build.unit;
  wrong.series.quant = wrong.series.quant == Quantization::kTruncate ? Quantization::kRoundNearest
                                                                     : Quantization::kTruncate;
  const Mismatch m = compare(stream, wrong);
  EXPECT_GT(m.differing, 0u) << "a rounding change in the model went unnoticed";
}

}  // namespace
}  // namespace shadesim
