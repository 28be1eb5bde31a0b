// The encoder's fixed-point series against the double quadratics they come from, pixel by pixel,
// within a bound derived from the coefficient rounding and the forward-difference drift.
#include <gtest/gtest.h>

#include <cmath>

#include "host/frame.h"
#include "model/series_engine.h"
#include "model/shade_unit.h"
#include "model/span_setup.h"

namespace shadesim {
namespace {

double channel(const Vec3& v, int c) { return c == 0 ? v.x : (c == 1 ? v.y : v.z); }

void check_scene(const std::string& name, const UnitConfig& base) {
  FrameOptions o;
  o.base = base;
  const PreparedFrame f = prepare_frame(std::string(SHADESIM_SOURCE_DIR) + "/scenes/" + name, o);
  const UnitConfig& cfg = f.config;
  const SpanSetup setup(cfg.coef, cfg.series, cfg.offset_bits);
  SeriesBank bank(cfg.series, cfg.series_per_triangle());
  const double coef_half_lsb =
      std::ldexp(cfg.coef.quant == Quantization::kRoundNearest ? 0.5 : 1.0, -cfg.coef.frac_bits());
  const double series_lsb = std::ldexp(1.0, -cfg.series.frac_bits());
  const double drift_unit = cfg.series.quant == Quantization::kRoundNearest ? 0.5 : 1.0;

  const TriangleCmd* tri = nullptr;
  size_t span_index = 0, checked = 0;
  double worst_ratio = 0;
  for (const auto& cmd : f.encoded.stream.commands) {
    if (const auto* t = std::get_if<TriangleCmd>(&cmd)) tri = t;
    const auto* s = std::get_if<SpanCmd>(&cmd);
    if (!s) continue;
    ASSERT_NE(tri, nullptr);
    const Span& vs = f.visibility.spans.at(span_index++);
    ASSERT_EQ(vs.y, s->y);
    ASSERT_EQ(vs.x0, s->x0);
    const ScreenTriangle& st = f.setup.triangles[vs.triangle];
    const TriangleSeries& series = f.setup.series[vs.triangle];
    const Material& m = f.scene.materials[static_cast<size_t>(st.material)];
    for (int i = 0; i < bank.size(); ++i) {
      bank.load(i, setup(&tri->coef[static_cast<size_t>(i) * kTermsPerSeries], s->x0 - tri->xo,
                         s->y - tri->yo));
    }
    for (int k = 0; k < s->length; ++k) {
      const double px = s->x0 + k + 0.5, py = s->y + 0.5;
      const double dx = s->x0 + k - tri->xo, dy = s->y - tri->yo;
      // Rounded coefficients times their monomials, plus truncation drift after k steps.
      const double coef_bound = coef_half_lsb * (1 + std::fabs(dx) + std::fabs(dy) + dx * dx +
                                                 std::fabs(dx * dy) + dy * dy);
      const double drift_bound = drift_unit * series_lsb * (1.0 + k + k * (k - 1) / 2.0);
      const double bound = (coef_bound + drift_bound) * 1.000001 + 1e-12;  // + double rounding
      int idx = 0;
      for (int l = 0; l < cfg.lights; ++l) {
        const double t = series.diffuse[static_cast<size_t>(l)].eval(px, py);
        for (int c = 0; c < cfg.channels; ++c, ++idx) {
          const double scale =
              channel(m.diffuse, c) * channel(f.scene.lights[static_cast<size_t>(l)].colour, c);
          const double got = cfg.series.to_double(bank.values()[idx]);
          const double err = std::fabs(got - scale * t);
          ASSERT_LE(err, bound) << name << " tri " << vs.triangle << " pixel (" << px << "," << py
                                << ")";
          worst_ratio = std::max(worst_ratio, err / bound);
        }
      }
      for (int l = 0; l < cfg.lights; ++l, ++idx) {
        const double t = series.specular[static_cast<size_t>(l)].eval(px, py);
        ASSERT_LE(std::fabs(cfg.series.to_double(bank.values()[idx]) - t), bound) << name;
      }
      ++checked;
      bank.step();
    }
  }
  EXPECT_EQ(span_index, f.visibility.spans.size());
  EXPECT_GT(checked, 1000u) << name;
  // The bound is met with room, but not by orders of magnitude more than rounding explains.
  EXPECT_GT(worst_ratio, 1e-3) << name;
}

TEST(Encode, GreySphereSeriesTrackTheQuadratics) { check_scene("sphere.json", UnitConfig{}); }
TEST(Encode, RgbTwoLightSeriesTrackTheQuadratics) { check_scene("multi.json", UnitConfig{}); }

TEST(Encode, NarrowTruncatedFormatsStayInsideTheirLargerBound) {
  UnitConfig c;
  c.coef = parse_fixed_format("s4.20:sat", "coef");
  c.series = parse_fixed_format("s4.16:sat", "series");
  check_scene("torus.json", c);
}

TEST(Encode, GreyOneLightSceneOnALargerFixedUnitShadesTheSame) {
  // A fixed RTL build (RGB, two lights) must give a grey one-light scene the same pixels in every
  // channel as the unit sized for it: the extra light's series are zero.
  FrameOptions small;
  const PreparedFrame a =
      prepare_frame(std::string(SHADESIM_SOURCE_DIR) + "/scenes/sphere.json", small);
  FrameOptions big;
  big.fixed_unit = true;
  big.base.channels = 3;
  big.base.lights = 2;
  const PreparedFrame b =
      prepare_frame(std::string(SHADESIM_SOURCE_DIR) + "/scenes/sphere.json", big);
  const auto pa = ShadeUnit(a.config).run(a.encoded.stream);
  const auto pb = ShadeUnit(b.config).run(b.encoded.stream);
  ASSERT_EQ(pa.size(), pb.size());
  for (size_t i = 0; i < pa.size(); ++i) {
    ASSERT_EQ(pa[i].x, pb[i].x);
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(pb[i].colour[static_cast<size_t>(c)], pa[i].colour[0]) << i;
  }
  // And a scene that needs more than the unit has is refused with a reason.
  FrameOptions tiny;
  tiny.fixed_unit = true;  // grey, one light
  EXPECT_THROW(prepare_frame(std::string(SHADESIM_SOURCE_DIR) + "/scenes/multi.json", tiny),
               std::invalid_argument);
}

TEST(Encode, NarrowOffsetsReoriginTrianglesAndStillTrackTheQuadratics) {
  // 5-bit offsets (-16..15) on multi, whose spans start up to 60 px from their triangles'
  // centroid pixels: the large triangles' spans need several origins.
  UnitConfig narrow;
  narrow.offset_bits = 5;
  check_scene("multi.json", narrow);
  FrameOptions o;
  o.base = narrow;
  const std::string path = std::string(SHADESIM_SOURCE_DIR) + "/scenes/multi.json";
  const PreparedFrame f = prepare_frame(path, o);
  const PreparedFrame wide = prepare_frame(path, FrameOptions{});
  EXPECT_GT(f.encoded.stats.reorigins, 0u);
  EXPECT_EQ(f.encoded.stats.triangles, wide.encoded.stats.triangles + f.encoded.stats.reorigins);
  EXPECT_EQ(f.encoded.stats.spans, wide.encoded.stats.spans);
  EXPECT_EQ(f.encoded.stats.pixels, wide.encoded.stats.pixels);
  const TriangleCmd* tri = nullptr;
  for (const Command& cmd : f.encoded.stream.commands) {
    if (const auto* t = std::get_if<TriangleCmd>(&cmd)) tri = t;
    if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
      ASSERT_NE(tri, nullptr);
      EXPECT_GE(s->x0 - tri->xo, -16);
      EXPECT_LE(s->x0 - tri->xo, 15);
      EXPECT_GE(s->y - tri->yo, -16);
      EXPECT_LE(s->y - tri->yo, 15);
    }
  }
}

TEST(Encode, AStreamWhoseOffsetsDoNotFitIsRejectedNamingTheTriangle) {
  CommandStream cs;
  cs.config.offset_bits = 4;  // -8..7
  cs.config.specular.kind = SpecularUnitKind::kIdeal;
  TriangleCmd t;
  t.xo = 10;
  t.yo = 20;
  t.coef.assign(static_cast<size_t>(cs.config.series_per_triangle()) * kTermsPerSeries, 0);
  cs.commands = {MaterialCmd{}, t, SpanCmd{27, 17, 3, true}, SpanCmd{28, 18, 1, true}};
  auto& m = std::get<MaterialCmd>(cs.commands[0]);
  m.ambient.assign(1, 0);
  m.spec_colour.assign(1, 0);
  // Command 2: dx = dy = 7 fit; command 3: dx = dy = 8 do not.
  try {
    cs.validate("s");
    FAIL() << "expected a CommandStreamError";
  } catch (const CommandStreamError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("command 3"), std::string::npos) << what;
    EXPECT_NE(what.find("dx=8"), std::string::npos) << what;
    EXPECT_NE(what.find("triangle at command 1"), std::string::npos) << what;
    EXPECT_NE(what.find("offset_bits=4 (-8..7)"), std::string::npos) << what;
  }
  std::get<SpanCmd>(cs.commands[3]) = SpanCmd{13, 3, 1, true};  // dx = dy = -7
  EXPECT_NO_THROW(cs.validate("s"));
}

TEST(Encode, GreySceneUsesOneChannelAndRgbSceneThree) {
  FrameOptions o;
  EXPECT_EQ(
      prepare_frame(std::string(SHADESIM_SOURCE_DIR) + "/scenes/sphere.json", o).config.channels,
      1);
  EXPECT_EQ(
      prepare_frame(std::string(SHADESIM_SOURCE_DIR) + "/scenes/multi.json", o).config.channels, 3);
}

}  // namespace
}  // namespace shadesim
