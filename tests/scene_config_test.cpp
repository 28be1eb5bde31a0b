// derive_config on shipped scenes: every field follows its stated rule, checked against numbers
// computed here independently (image sizes and lights read from the scene JSON, the longest span
// and pixel offsets walked from the host's own visibility and stream, the drift bound's closed
// form), and the derived unit shades the scenes within the budget.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "derive/budget.h"
#include "derive/derive_config.h"
#include "host/frame.h"
#include "host/metrics.h"
#include "host/reference.h"
#include "host/scene_error.h"
#include "model/shade_unit.h"
#include "tests/support/render_at.h"

namespace shadesim {
namespace {

std::string scene(const std::string& name) {
  return std::string(SHADESIM_SOURCE_DIR) + "/scenes/" + name;
}

nlohmann::json scene_json(const std::string& path) {
  std::ifstream is(path);
  return nlohmann::json::parse(is);
}

// Unsigned bits for coordinates 0..size-1 (size <= 2^b), at least 4: by doubling.
int xy_bits_for(int size) {
  int b = 4;
  while ((int64_t{1} << b) < size) ++b;
  return b;
}

// The closed-form F: F >= log2(G (1 + L(L-1)/2) 2^out / share), share in output LSBs.
int closed_form_series_frac(int L, double gain, double share_lsb, int out_bits) {
  const double steps = 1.0 + 0.5 * L * (L - 1.0);
  return std::max(
      out_bits,
      static_cast<int>(std::ceil(std::log2(gain * steps * std::ldexp(1.0, out_bits) / share_lsb))));
}

// Longest span, from the host's visibility (not from the stream derive_config walks).
int longest_span(const std::string& path) {
  const PreparedFrame f = prepare_frame(path, FrameOptions{});
  int longest = 0;
  for (const Span& s : f.visibility.spans) longest = std::max(longest, s.length);
  return longest;
}

// Largest 1+|dx|+|dy|+dx^2+|dx dy|+dy^2 of a pixel from its triangle's origin, with the origin
// recomputed here from the set-up triangle's centroid (the encoder's documented rule).
double max_monomial_sum(const std::string& path) {
  const PreparedFrame f = prepare_frame(path, FrameOptions{});
  double worst = 0;
  for (const Span& s : f.visibility.spans) {
    const ScreenTriangle& t = f.setup.triangles[s.triangle];
    const double xo = std::floor((t.v[0].x + t.v[1].x + t.v[2].x) / 3.0);
    const double yo = std::floor((t.v[0].y + t.v[1].y + t.v[2].y) / 3.0);
    const double dy = std::fabs(s.y - yo);
    for (int x = s.x0; x < s.x0 + s.length; ++x) {
      const double dx = std::fabs(x - xo);
      worst = std::max(worst, 1 + dx + dy + dx * dx + dx * dy + dy * dy);
    }
  }
  return worst;
}

const FieldReason& reason_of(const DerivedConfig& d, const std::string& field) {
  for (const auto& r : d.reasons)
    if (r.field == field) return r;
  throw std::logic_error("no reason for " + field);
}

TEST(SceneConfig, StructureAndXyBitsFollowTheSceneJson) {
  for (const char* name : {"sphere.json", "torus.json", "multi.json", "specular.json",
                           "suzanne.json", "hard/long_span.json"}) {
    const std::string path = scene(name);
    const auto j = scene_json(path);
    const DerivedConfig d = derive_config({path}, DeriveOptions{});
    const int w = j["image"]["width"], h = j["image"]["height"];
    EXPECT_EQ(d.config.xy_bits, xy_bits_for(std::max(w, h))) << name;
    EXPECT_EQ(d.config.lights, static_cast<int>(j["lights"].size())) << name;
    EXPECT_EQ(d.config.out_bits, 8) << name;
    // Every reason is there and says something.
    for (const char* field : {"budget", "channels", "lights", "xy_bits", "coef", "series",
                              "spec_colour", "out_bits", "specular"}) {
      EXPECT_FALSE(reason_of(d, field).reason.empty()) << name << " " << field;
    }
  }
  // multi.json has a red material; the others are grey.
  EXPECT_EQ(derive_config({scene("multi.json")}, {}).config.channels, 3);
  EXPECT_EQ(derive_config({scene("sphere.json")}, {}).config.channels, 1);
  // Several scenes: the union of their needs (multi: RGB, 2 lights, 480 wide).
  const DerivedConfig both = derive_config({scene("sphere.json"), scene("multi.json")}, {});
  EXPECT_EQ(both.config.channels, 3);
  EXPECT_EQ(both.config.lights, 2);
  EXPECT_EQ(both.config.xy_bits, 9);
  DeriveOptions out10;
  out10.out_bits = 10;
  EXPECT_EQ(derive_config({scene("sphere.json")}, out10).config.out_bits, 10);
}

TEST(SceneConfig, IdealBecomesTheFirstHardwareUnitThatMeetsTheBudget) {
  // torus: W_16 B=16 pipelined meets 1 LSB and is kept.
  const DerivedConfig torus = derive_config({scene("torus.json")}, {});
  EXPECT_EQ(torus.config.specular.kind, SpecularUnitKind::kWpow);
  EXPECT_EQ(torus.config.specular.wpow.max_m, 16);
  EXPECT_EQ(torus.config.specular.wpow.base_bits, 16);
  EXPECT_EQ(torus.config.specular.wpow.timing, UnitTiming::kPipelined);
  const std::string why = reason_of(torus, "specular").reason;
  EXPECT_NE(why.find("ideal"), std::string::npos) << why;
  EXPECT_NE(why.find("not hardware"), std::string::npos) << why;
  EXPECT_LE(render_at(scene("torus.json"), torus.config).max_code_lsb, 1);
  // specular: W_16 alone misses the budget (measured on its own derived unit), so the unit moves
  // to the first fallback that meets it, and the reason names both with their errors.
  DeriveOptions w16_only;
  w16_only.ideal_fallbacks.clear();
  const DerivedConfig w16 = derive_config({scene("specular.json")}, w16_only);
  EXPECT_EQ(w16.config.specular.wpow.max_m, 16);
  EXPECT_GT(render_at(scene("specular.json"), w16.config).max_code_lsb, 1);
  const DerivedConfig spec = derive_config({scene("specular.json")}, {});
  EXPECT_NE(spec.config.specular.describe(), w16.config.specular.describe());
  EXPECT_LE(render_at(scene("specular.json"), spec.config).max_code_lsb, 1);
  const std::string tried = reason_of(spec, "specular").reason;
  EXPECT_NE(tried.find(w16.config.specular.describe()), std::string::npos) << tried;
  EXPECT_NE(tried.find("the first within 1 LSB"), std::string::npos) << tried;
  // An asked-for substitute and no fallbacks: kept as asked.
  DeriveOptions lut;
  lut.ideal_substitute.kind = SpecularUnitKind::kLut;
  lut.ideal_fallbacks.clear();
  EXPECT_EQ(derive_config({scene("specular.json")}, lut).config.specular.kind,
            SpecularUnitKind::kLut);
}

class SceneConfigFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("shadesim_scene_config_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // A mesh-free shipped scene with every material naming `unit`, written to the test's folder.
  std::string with_unit(const std::string& name, const std::string& unit) const {
    auto j = scene_json(scene(name));
    for (auto& m : j["materials"]) m["unit"] = unit;
    std::string path =  // returned: moved
        (dir_ / (std::filesystem::path(name).stem().string() + "_" + unit + ".json")).string();
    std::ofstream(path) << j.dump(1);
    return path;
  }
  std::filesystem::path dir_;
};

TEST_F(SceneConfigFiles, AHardwareUnitIsKeptAndDifferentUnitsAreAnError) {
  // specular.json has a specular term (sphere.json has none: it gets no unit, whatever it names).
  const std::string lut = with_unit("specular.json", "lut");
  EXPECT_EQ(derive_config({lut}, {}).config.specular.kind, SpecularUnitKind::kLut);
  const std::string schlick = with_unit("specular.json", "schlick");
  try {
    (void)derive_config({lut, schlick}, {});
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    for (const std::string& needle : {lut, schlick, std::string("lut"), std::string("schlick")}) {
      EXPECT_NE(msg.find(needle), std::string::npos) << needle << " in " << msg;
    }
  }
}

TEST(SceneConfig, SeriesAndCoefficientBitsFollowTheClosedFormsOnADiffuseScene) {
  // sphere.json: specular 0, so the gain is 1 per light (one light); budget 1 LSB.
  const std::string path = scene("sphere.json");
  const DerivedConfig d = derive_config({path}, {});
  const int L = longest_span(path);
  EXPECT_EQ(d.measured.longest_span, L);
  EXPECT_DOUBLE_EQ(d.measured.gain, 1.0);
  EXPECT_EQ(d.config.series.frac_bits(), closed_form_series_frac(L, 1.0, 0.25, 8)) << "L = " << L;
  // Coefficients round (:rnd): 2^-(F+1) S <= 0.25 * 2^-8.
  const double S = max_monomial_sum(path);
  EXPECT_DOUBLE_EQ(d.measured.max_monomial_sum, S);
  EXPECT_EQ(d.config.coef.frac_bits(), static_cast<int>(std::ceil(std::log2(S * 256 / 0.25))) - 1)
      << "S = " << S;
  // Wrapping coefficients need exactly the series' integer bits.
  EXPECT_EQ(d.config.coef.overflow, Overflow::kWrap);
  EXPECT_EQ(d.config.coef.iwl, d.config.series.iwl);
  // Diffuse N.L/|N| and the specular base stay within (-2, 2): two integer bits (sign + 1).
  EXPECT_EQ(d.config.series.iwl, 2);
}

TEST(SceneConfig, LongSpanIsWithinOneLsbOnItsOwnConfiguration) {
  // 2048-pixel spans: at the default s4.28 series the drift reaches 5 LSB.
  const std::string path = scene("hard/long_span.json");
  const auto j = scene_json(path);
  const DerivedConfig d = derive_config({path}, {});
  const int L = longest_span(path);
  EXPECT_EQ(L, 2048);
  // Gain: 1 (diffuse) + ks 0.3 x W_8 slope. n = 8 on W_16: m = 8, zeta = n/m = 1; setup pre-shifts
  // the base (reach 1.25 at t = +-1.25) by s bits until it fits 2^(iwl-2): the slope is m 2^s.
  const double ks = j["materials"][0]["specular"];
  const int iwl = d.config.series.iwl;
  int shift = 0;
  while (1.25 > std::ldexp(1.0, iwl - 2 + shift)) ++shift;
  const double gain = 1.0 + ks * 8 * std::ldexp(1.0, shift);
  EXPECT_NEAR(d.measured.gain, gain, 1e-9);
  const double budget = j["error_budget_lsb"];
  EXPECT_EQ(d.config.series.frac_bits(), closed_form_series_frac(L, gain, budget / 4, 8));
  EXPECT_GE(d.config.series.frac_bits(), 30)
      << "the drift bound (README \"Checked numerical facts\"): F >= 30 for L = 2048";
  const ErrorStats e = render_at(path, d.config);
  EXPECT_LE(e.max_code_lsb, 1) << d.config.to_string();
  EXPECT_EQ(e.pixels_over_1lsb, 0u);
}

TEST(SceneConfig, ShippedScenesShadeOnTheirConfigurationAsWellAsOnTheDefaults) {
  // The derived widths add no error beyond the default widths': same unit, compare max codes.
  for (const char* name :
       {"sphere.json", "torus.json", "multi.json", "specular.json", "suzanne.json"}) {
    const std::string path = scene(name);
    const DerivedConfig d = derive_config({path}, {});
    UnitConfig defaults;
    defaults.channels = d.config.channels;
    defaults.lights = d.config.lights;
    defaults.specular = d.config.specular;
    const ErrorStats on_derived = render_at(path, d.config);
    const ErrorStats on_defaults = render_at(path, defaults);
    EXPECT_LE(on_derived.max_code_lsb, on_defaults.max_code_lsb)
        << name << ": " << d.config.to_string();
    // And with the exact-pow yardstick on the same widths, within one code of the reference.
    UnitConfig ideal = d.config;
    ideal.specular.kind = SpecularUnitKind::kIdeal;
    EXPECT_LE(render_at(path, ideal).max_code_lsb, 1) << name;
  }
}

// Every shipped and hard scene (the hard set has the long spans and sliver triangles).
std::vector<std::string> shipped_and_hard_scenes() {
  std::vector<std::string> out;
  for (const char* dir : {"", "hard/"}) {
    for (const auto& e : std::filesystem::directory_iterator(scene(dir))) {
      if (e.path().extension() == ".json") out.push_back(e.path().string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The smallest and largest dx, dy of a span's first pixel from its triangle's origin.
std::pair<int, int> start_offset_range(const CommandStream& stream) {
  const TriangleCmd* tri = nullptr;
  int lo = 0, hi = 0;
  for (const Command& cmd : stream.commands) {
    if (const auto* t = std::get_if<TriangleCmd>(&cmd)) tri = t;
    if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
      lo = std::min({lo, s->x0 - tri->xo, s->y - tri->yo});
      hi = std::max({hi, s->x0 - tri->xo, s->y - tri->yo});
    }
  }
  return {lo, hi};
}

// Pixels of two frames' models that differ in position, colour or end of row; every pixel
// differs when the counts differ, and two empty frames are an error (nothing compared).
size_t differing_pixels(const PreparedFrame& fa, const PreparedFrame& fb) {
  const auto a = ShadeUnit(fa.config).run(fa.encoded.stream);
  const auto b = ShadeUnit(fb.config).run(fb.encoded.stream);
  if (a.empty() && b.empty()) throw std::logic_error("differing_pixels: no pixels to compare");
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  size_t differ = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    differ += a[i].x != b[i].x || a[i].y != b[i].y || a[i].colour != b[i].colour ||
              a[i].end_of_row != b[i].end_of_row;
  }
  return differ;
}

TEST(SceneConfig, OffsetBitsAreTheFewestThatHoldEverySpanStart) {
  // Unit span setup: the stream's TRIANGLEs carry the origins the offsets are measured from.
  DeriveOptions unit_setup;
  unit_setup.span_setup = SpanSetupSite::kUnit;
  for (const std::string& path : shipped_and_hard_scenes()) {
    const DerivedConfig d = derive_config({path}, unit_setup);
    FrameOptions o;
    o.base = d.config;
    o.base.offset_bits = UnitConfig::kMaxOffsetBits;
    o.fixed_unit = true;
    const auto [lo, hi] = start_offset_range(prepare_frame(path, o).encoded.stream);
    // Closed form: signed b bits hold -2^(b-1) .. 2^(b-1) - 1: b = 1 + ceil(log2(-lo)) for the
    // negative side, 2 + floor(log2(hi)) for the positive one, at least 2.
    const int neg = lo < -1 ? 1 + static_cast<int>(std::ceil(std::log2(-lo))) : 2;
    const int pos = hi > 1 ? 2 + static_cast<int>(std::floor(std::log2(hi))) : 2;
    EXPECT_EQ(d.config.offset_bits, std::max(neg, pos)) << path << ": " << lo << ".." << hi;
    EXPECT_EQ(d.measured.start_offset_min, lo) << path;
    EXPECT_EQ(d.measured.start_offset_max, hi) << path;
    o.base = d.config;
    const PreparedFrame sized = prepare_frame(path, o);
    EXPECT_EQ(sized.encoded.stats.reorigins, 0u) << path;
    // One bit fewer: some triangle's centroid origin no longer holds its spans, so the encoder
    // moves that origin (or splits the triangle) and the stream changes.
    if (d.config.offset_bits > 2) {
      o.base.offset_bits = d.config.offset_bits - 1;
      EXPECT_NE(prepare_frame(path, o).encoded.stream.encode(), sized.encoded.stream.encode())
          << path;
    }
  }
}

TEST(SceneConfig, SizedOffsetsShadeEveryPixelAsScreenSizedOnes) {
  // The same unit with offset_bits 17 (the screen-sized span setup every unit had before) and
  // with its derived offset_bits: the same stream, and every pixel bit-identical (unit setup,
  // whose span setup the offsets size).
  DeriveOptions unit_setup;
  unit_setup.span_setup = SpanSetupSite::kUnit;
  for (const std::string& path : shipped_and_hard_scenes()) {
    const DerivedConfig d = derive_config({path}, unit_setup);
    FrameOptions o;
    o.fixed_unit = true;
    o.base = d.config;
    const PreparedFrame sized = prepare_frame(path, o);
    o.base.offset_bits = UnitConfig::kMaxOffsetBits;
    const PreparedFrame wide = prepare_frame(path, o);
    EXPECT_EQ(sized.encoded.stream.encode(), wide.encoded.stream.encode()) << path;
    EXPECT_EQ(differing_pixels(sized, wide), 0u)
        << path << " (offset_bits " << d.config.offset_bits << ")";
  }
}

TEST_F(SceneConfigFiles, ADiffuseOnlySceneGetsNoSpecularUnitWhateverItNames) {
  for (const char* unit : {"ideal", "lut", "schlick", "wpow", "none"}) {
    const std::string path = with_unit("sphere.json", unit);
    const DerivedConfig d = derive_config({path}, {});
    EXPECT_EQ(d.config.specular.kind, SpecularUnitKind::kNone) << unit;
    EXPECT_NE(reason_of(d, "specular").reason.find("no specular term"), std::string::npos)
        << reason_of(d, "specular").reason;
  }
  // Different names do not matter when no material has a specular term.
  EXPECT_EQ(
      derive_config({with_unit("sphere.json", "lut"), with_unit("sphere.json", "schlick")}, {})
          .config.specular.kind,
      SpecularUnitKind::kNone);
  // One scene with a specular term keeps the unit for all of them.
  EXPECT_EQ(derive_config({scene("sphere.json"), scene("specular.json")}, {}).config.specular.kind,
            SpecularUnitKind::kWpow);
}

TEST(SceneConfig, DiffuseOnlyScenesShadeOnNoSpecularUnitAsOnTheW16One) {
  // A scene whose materials have no specular term gets specular kind none (no unit, no specular
  // series); its image is bit-identical to the one of the same unit with a W_16 unit (whose
  // specular contribution is 0 there). Scenes with a specular term keep their unit.
  int diffuse_only = 0;
  for (const std::string& path : shipped_and_hard_scenes()) {
    const DerivedConfig d = derive_config({path}, {});
    const Scene scene = load_scene(path);
    bool specular_term = false;
    for (const Material& m : scene.materials) {
      for (const DirectionalLight& l : scene.lights) {
        specular_term = specular_term || m.specular.x * l.colour.x != 0 ||
                        m.specular.y * l.colour.y != 0 || m.specular.z * l.colour.z != 0;
      }
    }
    if (specular_term) {
      EXPECT_NE(d.config.specular.kind, SpecularUnitKind::kNone) << path;
      continue;
    }
    ++diffuse_only;
    ASSERT_EQ(d.config.specular.kind, SpecularUnitKind::kNone) << path;
    UnitConfig old_style = d.config;
    old_style.specular = DeriveOptions{}.ideal_substitute;  // W_16, B = 16, pipelined
    ASSERT_EQ(old_style.specular.kind, SpecularUnitKind::kWpow);
    FrameOptions o;
    o.fixed_unit = true;
    o.base = d.config;
    const PreparedFrame none = prepare_frame(path, o);
    o.base = old_style;
    const PreparedFrame w16 = prepare_frame(path, o);
    // The new stream carries no specular series and no unit parameters.
    for (const Command& cmd : none.encoded.stream.commands) {
      if (const auto* t = std::get_if<TriangleCmd>(&cmd)) {
        ASSERT_EQ(t->coef.size(), static_cast<size_t>(d.config.diffuse_series() * kTermsPerSeries))
            << path;
      }
      if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
        EXPECT_TRUE(m->unit_params.empty()) << path;
      }
    }
    EXPECT_EQ(differing_pixels(none, w16), 0u) << path << ": " << d.config.to_string();
  }
  ASSERT_GE(diffuse_only, 1) << "no shipped or hard scene without a specular term";
}

// With colour, config multiplies the diffuse colour in the unit (one N.L series per light in
// place of one per light and channel) and the unit still meets the budget against the double
// reference; grey scenes keep the colour in their one series; --diffuse-colour overrides.
TEST(SceneConfig, ColourScenesMultiplyTheDiffuseColourAndMeetTheBudget) {
  const std::string multi = scene("multi.json");
  const DerivedConfig d = derive_config({multi}, DeriveOptions{});
  EXPECT_TRUE(d.config.diffuse_multiply());
  EXPECT_EQ(d.config.diffuse_series(), d.config.lights);
  EXPECT_EQ(d.config.series_per_triangle(), d.config.lights + d.config.specular_series());
  EXPECT_LE(render_at(multi, d.config).max_code_lsb, code_budget(d.measured.budget_lsb));
  EXPECT_NE(reason_of(d, "diffuse_colour").reason.find("N.L"), std::string::npos);

  DeriveOptions in_series;
  in_series.diffuse_colour = DiffuseColour::kSeries;
  const DerivedConfig s = derive_config({multi}, in_series);
  EXPECT_FALSE(s.config.diffuse_multiply());
  EXPECT_EQ(s.config.diffuse_series(), s.config.lights * s.config.channels);

  EXPECT_FALSE(derive_config({scene("sphere.json")}, {}).config.diffuse_multiply());
}

TEST(SceneConfig, BadBudgetIsAnError) {
  DeriveOptions o;
  o.budget_lsb = 0;
  EXPECT_THROW(derive_config({scene("sphere.json")}, o), std::invalid_argument);
  EXPECT_THROW(derive_config({}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace shadesim
