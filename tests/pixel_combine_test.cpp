// PixelCombine against the same sum computed in double (exact for these widths) and rounded by
// the documented output rule: code = clamp(floor(x * 2^out_bits + 1/2), 0, 2^out_bits - 1).
// The specular gate as documented: light l's specular term counts only where the sum of its
// channels' diffuse values is > 0; a gate-only light's diffuse values are not added.
#include "model/pixel_combine.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

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
    // A third of the trials: light l's channels all of one sign, so the gate is that sign.
    if (trial % 3 == 0) {
      for (int l = 0; l < 2; ++l) {
        const bool negative = rng() % 2 == 0;
        for (int ch = 0; ch < 3; ++ch) {
          const int64_t a = diffuse[l * 3 + ch] < 0 ? -diffuse[l * 3 + ch] : diffuse[l * 3 + ch];
          diffuse[l * 3 + ch] = negative ? -a : a;
        }
      }
    }
    const uint32_t gate_only = static_cast<uint32_t>(rng() % 4);
    const auto out = combine(diffuse, spec, ambient, colour, nullptr, gate_only);
    for (int ch = 0; ch < 3; ++ch) {
      double x = c.series.to_double(ambient[ch]);
      for (int l = 0; l < 2; ++l) {
        const bool gate_only_light = (gate_only & (1u << l)) != 0;
        if (!gate_only_light) x += std::max(0.0, c.series.to_double(diffuse[l * 3 + ch]));
        double nl = 0.0;
        for (int k = 0; k < 3; ++k) nl += c.series.to_double(diffuse[l * 3 + k]);
        const bool lit = nl > 0.0;
        // s * k has 16 + 12 = 28 fraction bits = the series' own: no rounding.
        if (lit)
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
  EXPECT_EQ(combine(&diffuse, &spec, &ambient, &colour, nullptr, 0)[0],
            64);  // 0.25 * 256, diffuse clamped
}

TEST(PixelCombine, SpecularOnlyWhereSomeDiffuseIsPositive) {
  UnitConfig c;  // grey, one light
  const PixelCombine combine(c);
  const int64_t spec = c.specular.out.from_double(0.5);
  const int64_t colour = c.spec_colour.from_double(0.5);
  const int64_t ambient = 0;
  const int64_t behind = c.series.from_double(-0.001), zero = 0, lit = 1;  // lit: one LSB
  EXPECT_EQ(combine(&behind, &spec, &ambient, &colour, nullptr, 0)[0], 0);
  EXPECT_EQ(combine(&zero, &spec, &ambient, &colour, nullptr, 0)[0], 0);  // N.L = 0 is not lit
  EXPECT_EQ(combine(&lit, &spec, &ambient, &colour, nullptr, 0)[0], 64);  // 0.25 * 256
  // Gate only: the diffuse value opens the gate and is not added.
  const int64_t half = c.series.from_double(0.5);
  EXPECT_EQ(combine(&half, &spec, &ambient, &colour, nullptr, 1)[0], 64);
  EXPECT_EQ(combine(&half, &spec, &ambient, &colour, nullptr, 0)[0], 192);  // (0.5 + 0.25) * 256
  EXPECT_EQ(combine(&behind, &spec, &ambient, &colour, nullptr, 1)[0], 0);
}

TEST(PixelCombine, GateIsTheSignOfTheLightsChannelSum) {
  UnitConfig c;
  c.channels = 3;
  c.lights = 2;
  const PixelCombine combine(c);
  const int64_t one = c.series.from_double(0.25);
  // Light 0: only the blue channel is lit (red and green colour 0). Light 1: behind.
  const int64_t diffuse[6] = {0, 0, one, -one, 0, -one};
  const int64_t spec[2] = {c.specular.out.from_double(0.5), c.specular.out.from_double(0.5)};
  const int64_t ambient[3] = {0, 0, 0};
  const int64_t k = c.spec_colour.from_double(0.5);
  const int64_t colour[6] = {k, k, k, k, k, k};
  const auto out = combine(diffuse, spec, ambient, colour, nullptr, 0);
  EXPECT_EQ(out[0], 64);  // light 0's specular only: 0.25
  EXPECT_EQ(out[1], 64);
  EXPECT_EQ(out[2], 64 + 64);  // + blue diffuse 0.25
  // Channels that disagree near the terminator: the sum decides (a small scale's rounding
  // cannot open the gate on its own).
  const int64_t mixed[6] = {1, -one, -one, 0, 0, 0};
  EXPECT_EQ(combine(mixed, spec, ambient, colour, nullptr, 0)[0], 0);
}

// Diffuse colour multiply: one N.L series per light; each channel adds max(0, N.L), truncated to
// the colour's 12 fraction bits, times kd_lc (24 fraction bits: within the series' 28, so
// exact), and N.L > 0 alone gates the light's specular term.
TEST(PixelCombine, MultipliedDiffuseIsTheTruncatedProductAndGatesOnNDotL) {
  UnitConfig c;
  c.channels = 3;
  c.lights = 2;
  c.diffuse_colour = DiffuseColour::kMultiply;
  ASSERT_EQ(c.diffuse_series(), 2);
  const PixelCombine combine(c);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> series(-1.2, 1.2);
  for (int trial = 0; trial < 20000; ++trial) {
    int64_t n_dot_l[2], spec[2], ambient[3], spec_colour[6], diffuse_colour[6];
    for (auto& n : n_dot_l) n = c.series.from_double(series(rng));
    if (trial % 7 == 0) n_dot_l[trial % 2] = 0;  // N.L = 0: neither lit nor added
    for (auto& a : ambient) a = c.series.from_double(0.2 * std::fabs(series(rng)));
    for (auto& s : spec) s = static_cast<int64_t>(rng() % (c.specular.out.raw_max() + 1));
    for (auto& k : spec_colour) k = static_cast<int64_t>(rng() % (c.spec_colour.raw_max() + 1));
    for (auto& k : diffuse_colour) k = static_cast<int64_t>(rng() % (c.spec_colour.raw_max() + 1));
    // A gate-only mask means nothing here: every light's series is N.L and is added.
    const auto out = combine(n_dot_l, spec, ambient, spec_colour, diffuse_colour, 3);
    for (int ch = 0; ch < 3; ++ch) {
      double x = c.series.to_double(ambient[ch]);
      for (int l = 0; l < 2; ++l) {
        const double nl = c.series.to_double(n_dot_l[l]);
        if (nl <= 0.0) continue;
        const double nl_12 = std::floor(nl * 4096.0) / 4096.0;
        x += nl_12 * c.spec_colour.to_double(diffuse_colour[l * 3 + ch]);
        x += c.specular.out.to_double(spec[l]) * c.spec_colour.to_double(spec_colour[l * 3 + ch]);
      }
      const double code = std::clamp(std::floor(x * 256.0 + 0.5), 0.0, 255.0);
      ASSERT_EQ(out[ch], code) << "trial " << trial << " x=" << x;
    }
  }
}

// The same with a derived unit's colour formats: colour words u3.15 hold kd_c L_c and
// ks_c L_c up to 8, and the series s4.20 has fewer fraction bits than the products: N.L truncated
// to 15 bits times a 15-bit colour has 30, the specular s (16) times its colour 31. Each product
// is truncated to the series' 20 fraction bits (the series rule) before the exact sum: here in
// double, where every product (at most 35 significant bits) is exact, floor() is truncation of
// a two's-complement value, and the sum of multiples of 2^-20 is exact.
TEST(PixelCombine, MultipliedProductsWiderThanTheSeriesAreTruncatedToIt) {
  UnitConfig c;
  c.channels = 3;
  c.lights = 2;
  c.diffuse_colour = DiffuseColour::kMultiply;
  c.series = FixedFormat{24, 4, true, Quantization::kTruncate, Overflow::kWrap};
  c.coef = FixedFormat{28, 4, true, Quantization::kRoundNearest, Overflow::kWrap};
  c.spec_colour = FixedFormat{18, 3, false, Quantization::kRoundNearest, Overflow::kSaturate};
  c.validate();
  const PixelCombine combine(c);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> series(-1.2, 1.2);
  const auto truncate20 = [](double x) { return std::floor(std::ldexp(x, 20)) / 1048576.0; };
  int rounded = 0;  // products that lost bits: the rule is exercised
  for (int trial = 0; trial < 20000; ++trial) {
    int64_t n_dot_l[2], spec[2], ambient[3], spec_colour[6], diffuse_colour[6];
    for (auto& n : n_dot_l) n = c.series.from_double(series(rng));
    for (auto& a : ambient) a = c.series.from_double(0.2 * std::fabs(series(rng)));
    for (auto& v : spec) v = static_cast<int64_t>(rng() % (c.specular.out.raw_max() / 2 + 1));
    for (auto& k : spec_colour) k = static_cast<int64_t>(rng() % (c.spec_colour.raw_max() / 8));
    for (auto& k : diffuse_colour) k = static_cast<int64_t>(rng() % (c.spec_colour.raw_max() / 8));
    const auto out = combine(n_dot_l, spec, ambient, spec_colour, diffuse_colour, 0);
    for (int ch = 0; ch < 3; ++ch) {
      double x = c.series.to_double(ambient[ch]);
      for (int l = 0; l < 2; ++l) {
        const double nl = c.series.to_double(n_dot_l[l]);
        if (nl <= 0.0) continue;
        const double nl_15 = std::floor(std::ldexp(nl, 15)) / 32768.0;
        const double diffuse = nl_15 * c.spec_colour.to_double(diffuse_colour[l * 3 + ch]);
        const double specular =
            c.specular.out.to_double(spec[l]) * c.spec_colour.to_double(spec_colour[l * 3 + ch]);
        rounded += (truncate20(diffuse) != diffuse) + (truncate20(specular) != specular);
        x += truncate20(diffuse) + truncate20(specular);
      }
      const double code = std::clamp(std::floor(x * 256.0 + 0.5), 0.0, 255.0);
      ASSERT_EQ(out[ch], code) << "trial " << trial << " x=" << x;
    }
  }
  EXPECT_GT(rounded, 10000);
}

}  // namespace
}  // namespace shadesim
