// End to end: scene -> host -> command stream -> bit-accurate model, against the float reference.
#include <gtest/gtest.h>

#include <filesystem>
#include <optional>

#include "host/frame.h"
#include "host/metrics.h"
#include "host/reference.h"
#include "model/shade_unit.h"
#include "tests/support/test_data.h"

namespace shadesim {
namespace {

ErrorStats render(const std::string& scene, const UnitConfig& base = UnitConfig{},
                  EncodeStats* encode_stats = nullptr,
                  std::optional<SpecularUnitKind> specular = std::nullopt) {
  FrameOptions o;
  o.base = base;
  o.specular_override = specular;
  const PreparedFrame f = prepare_frame(std::string(SHADESIM_SOURCE_DIR) + "/scenes/" + scene, o);
  if (encode_stats) *encode_stats = f.encoded.stats;
  ShadeUnit unit(f.config);
  const auto pixels = unit.run(f.encoded.stream);
  const auto ref = render_reference(f.setup.triangles, f.visibility, f.scene, f.config.channels);
  // compare_to_reference throws if a pixel is shaded twice, or if the model and visibility
  // disagree on which pixels are covered.
  return compare_to_reference(pixels, ref.values, f.visibility.owner, f.scene.width, f.scene.height,
                              f.config.channels, f.config.out_bits)
      .stats;
}

TEST(Render, DiffuseSphereWithinOneLsbOfTheReference) {
  const ErrorStats e = render("sphere.json");
  EXPECT_GT(e.pixels, 10000u);
  EXPECT_LE(e.max_code_lsb, 1);
  EXPECT_EQ(e.pixels_over_1lsb, 0u);
}

TEST(Render, NarrowSeriesWidthShowsUpAsError) {
  // The metric can fail: with as many series fraction bits as output bits, truncating v, d and
  // d2 at span setup alone is up to 3 output LSBs after one step, and it accumulates.
  UnitConfig c;
  c.coef = parse_fixed_format("s4.12:rnd", "coef");
  c.series = parse_fixed_format("s4.8", "series");
  EXPECT_GT(render("sphere.json", c).max_code_lsb, 1);
}

TEST(Render, RealMeshSliversAreExactThroughWrappingCoefficients) {
  SHADESIM_NEEDS_TEST_FILE(
      std::filesystem::path("/usr/share/assimp/models/BLEND/Suzanne_248.blend"));
  // Setup keeps the Taylor error under 1 LSB; fixed-point error is far smaller, so the real
  // error stays under 1 LSB and the rounded codes differ by at most 1.
  EncodeStats wrapped;
  const ErrorStats e = render("suzanne.json", UnitConfig{}, &wrapped);
  EXPECT_GT(wrapped.coefficients_out_of_range, 0u) << "the scene no longer has sliver triangles";
  EXPECT_LE(e.max_code_lsb, 1);
  // The same coefficients saturated instead of wrapped break those pixels, and are counted.
  UnitConfig sat;
  sat.coef.overflow = Overflow::kSaturate;
  EncodeStats saturated;
  const ErrorStats es = render("suzanne.json", sat, &saturated);
  EXPECT_EQ(saturated.coefficients_out_of_range, wrapped.coefficients_out_of_range);
  EXPECT_GT(es.max_code_lsb, 1);
}

TEST(Render, EveryShippedSceneWithEveryUnitShadesEachVisiblePixelOnce) {
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(SHADESIM_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    if (entry.path().filename() == "suzanne.json") {
      SHADESIM_NEEDS_TEST_FILE(
          std::filesystem::path("/usr/share/assimp/models/BLEND/Suzanne_248.blend"));
    }
    for (const auto unit : {SpecularUnitKind::kIdeal, SpecularUnitKind::kLut,
                            SpecularUnitKind::kSchlick, SpecularUnitKind::kWpow}) {
      SCOPED_TRACE(entry.path().string() + " with " + to_string(unit));
      const ErrorStats e = render(entry.path().filename().string(), UnitConfig{}, nullptr, unit);
      EXPECT_GT(e.pixels, 1000u);
    }
  }
}

}  // namespace
}  // namespace shadesim
