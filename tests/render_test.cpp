// End to end: scene -> host -> command stream -> bit-accurate model, against the float reference.
#include <gtest/gtest.h>

#include <filesystem>

#include "host/frame.h"
#include "host/metrics.h"
#include "host/reference.h"
#include "model/shade_unit.h"

namespace shadesim {
namespace {

ErrorStats render(const std::string& scene, const UnitConfig& base = UnitConfig{}) {
  FrameOptions o;
  o.base = base;
  const PreparedFrame f = prepare_frame(std::string(SHADESIM_SOURCE_DIR) + "/scenes/" + scene, o);
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

TEST(Render, EveryShippedSceneShadesEachVisiblePixelOnce) {
  for (const auto& entry : std::filesystem::directory_iterator(std::string(SHADESIM_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    if (entry.path().filename() == "suzanne.json" && !std::filesystem::exists("/usr/share/assimp/models")) {
      std::cout << "skipping " << entry.path() << ": assimp-testmodels not installed\n";
      continue;
    }
    SCOPED_TRACE(entry.path().string());
    const ErrorStats e = render(entry.path().filename().string());
    EXPECT_GT(e.pixels, 1000u);
  }
}

}  // namespace
}  // namespace shadesim
