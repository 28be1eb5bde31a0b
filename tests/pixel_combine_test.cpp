// PixelCombine against the same sum computed in double (exact for these widths) and rounded by
// the documented output rule: code = clamp(floor(x * 2^out_bits + 1/2), 0, 2^out_bits - 1).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/pixel_combine.h"

namespace shadesim {
namespace {

TEST(PixelCombine, MatchesDoubleSumAndOutputRule) {
  UnitConfig c;
  c.channels = 3;
  c.lights = 2;
  const PixelCombine combine(c);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> series(-1.5, 1.5);
  const double series_lsb = std::ldexp(1.0, -c.series.frac_bits());
  for (int trial = 0; trial < 20000; ++trial) {
    int64_t diffuse[6], spec[2], ambient[3], colour[6];
    for (auto& d : diffuse) d = c.series.from_double(series(rng));
    for (auto& a : ambient) a = c.series.from_double(0.3 * std::fabs(series(rng)));
    for (auto& s : spec) s = static_cast<int64_t>(rng() % (c.specular.out.raw_max() + 1));
    for (auto& k : colour) k = static_cast<int64_t>(rng() % (c.spec_colour.raw_max() + 1));
    const auto out = combine(diffuse, spec, ambient, colour);
    for (int ch = 0; ch < 3; ++ch) {
      double x = c.series.to_double(ambient[ch]);
      for (int l = 0; l < 2; ++l) {
        x += std::max(0.0, c.series.to_double(diffuse[l * 3 + ch]));
        // s * k has 16 + 12 = 28 fraction bits = the series' own: no rounding.
        x += c.specular.out.to_double(spec[l]) * c.spec_colour.to_double(colour[l * 3 + ch]);
      }
      const double code = std::clamp(std::floor(x * 256.0 + 0.5), 0.0, 255.0);
      ASSERT_EQ(out[ch], code) << "x=" << x << " lsb=" << series_lsb;
    }
  }
}

TEST(PixelCombine, GreyUsesOneChannelAndClampsNegativeDiffuse) {
  UnitConfig c;  // grey, one light
  const PixelCombine combine(c);
  const int64_t diffuse = c.series.from_double(-0.75);
  const int64_t spec = 0, colour = 0;
  const int64_t ambient = c.series.from_double(0.25);
  EXPECT_EQ(combine(&diffuse, &spec, &ambient, &colour)[0], 64);  // 0.25 * 256, diffuse clamped
}

}  // namespace
}  // namespace shadesim
