// WpowUnit against double precision: an exhaustive sweep at small widths, a derived bound
// against the float W_m, the clamp at and below W_m's zero, t beyond [0, 1], small n, and the
// W16 epicentre figures of README "Checked numerical facts" (float, n in [16, 1000]).
#include "model/wpow_unit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "host/specular_setup.h"
#include "model/specular_unit.h"

namespace shadesim {
namespace {

const FixedFormat kOut{17, 1, false, Quantization::kTruncate, Overflow::kSaturate};

TEST(WpowUnit, ExhaustiveSmallWidthsMatchDoubleReference) {
  const FixedFormat series{14, 4, true, Quantization::kTruncate, Overflow::kWrap};  // s4.10
  for (int m : {2, 4}) {
    for (int squarings = 0; (1 << squarings) <= m; ++squarings) {
      for (int shift : {0, 3}) {
        WpowConfig c;
        c.max_m = m;
        c.base_bits = 5;
        WpowUnit unit(c, series, kOut);
        unit.load_params({shift, squarings});
        for (int64_t raw = series.raw_min(); raw <= series.raw_max(); ++raw) {
          // Reference: floor to 5 bits, clamp to [0, 1], square with floor to 5 bits.
          const double x = std::ldexp(static_cast<double>(raw), -(series.frac_bits() - shift));
          double b = std::clamp(std::floor(x * 32.0) / 32.0, 0.0, 1.0);
          for (int k = 0; k < squarings; ++k) b = std::floor(b * b * 32.0) / 32.0;
          ASSERT_EQ(kOut.to_double(unit.evaluate(raw)), b)
              << "raw " << raw << " m " << m << " s " << squarings << " shift " << shift;
        }
      }
    }
  }
}

struct Harness {
  UnitConfig cfg;
  SpecularSeriesPlan plan;
  SpecularUnit unit;
  Harness(const WpowConfig& w, double n) : cfg(make(w)), plan(plan_specular(cfg, n)), unit(cfg) {
    MaterialCmd m;
    m.exponent = static_cast<int64_t>(std::llround(std::ldexp(n, kExponentFracBits)));
    m.unit_params = plan.unit_params;
    unit.load_material(m);
  }
  static UnitConfig make(const WpowConfig& w) {
    UnitConfig c;
    c.specular.kind = SpecularUnitKind::kWpow;
    c.specular.wpow = w;
    return c;
  }
  double at(double t) const {
    const int64_t v = cfg.series.from_double(plan.affine[0].first * t + plan.affine[0].second);
    return cfg.specular.out.to_double(unit.evaluate(&v));
  }
};

// Bound: the base starts off by e0 <= 2^-B (truncation) + 2^-(28 - shift) (series truncation);
// a squaring of b <= 1 at most doubles an error and adds 2^-B truncation, so after s squarings
// |err| <= 2^s e0 + (2^s - 1) 2^-B; then 2^-16 output truncation.
TEST(WpowUnit, WithinDerivedBoundOfFloat) {
  for (int b : {8, 16}) {
    for (int m : {4, 16}) {
      for (double n : {1.0, 2.0, 2.5, 4.0, 16.0, 1000.0}) {
        for (FitObjective fit : {FitObjective::kNone, FitObjective::kAbsolute}) {
          WpowConfig w;
          w.max_m = m;
          w.base_bits = b;
          w.fit = fit;
          Harness h(w, n);
          const int s = static_cast<int>(h.plan.unit_params[1]);
          const int shift = static_cast<int>(h.plan.unit_params[0]);
          const double e0 = std::ldexp(1.0, -b) + std::ldexp(1.0, -(28 - shift));
          const double bound = std::ldexp(e0, s) + (std::ldexp(1.0, s) - 1) * std::ldexp(1.0, -b) +
                               std::ldexp(1.0, -16);
          for (int i = -200; i <= 4200; ++i) {
            const double t = i / 4000.0;
            const double want = wpow_float(t, h.plan.parameter, 1 << s);
            ASSERT_LE(std::fabs(h.at(t) - want), bound)
                << "t " << t << " n " << n << " m " << m << " B " << b << " fit " << to_string(fit);
          }
        }
      }
    }
  }
}

TEST(WpowUnit, ZeroAtAndBelowTheBaseZero) {
  for (int m : {4, 8, 16}) {
    for (double n : {static_cast<double>(m), 35.0, 1000.0}) {
      WpowConfig w;
      w.max_m = m;
      Harness h(w, n);
      const int me = h.plan.effective_m;
      const double zero = (n - me) / n;  // paper zeta = n / m
      EXPECT_EQ(h.at(zero), 0.0) << "m " << m << " n " << n;
      EXPECT_EQ(h.at(zero - 1e-6), 0.0);
      EXPECT_EQ(h.at(zero - 0.01), 0.0);
      EXPECT_EQ(h.at(0.0), 0.0);
      EXPECT_EQ(h.at(-1.0), 0.0);  // a very negative base: an unclamped even power would be huge
      // Base 0.9 (zeta = n / m_eff): well above zero, so the unit must not be stuck at 0.
      EXPECT_NEAR(h.at(1.0 - 0.1 * me / n), std::pow(0.9, me), 1e-3);
    }
  }
}

TEST(WpowUnit, OneAtAndAboveOne) {
  for (double n : {1.0, 2.0, 16.0, 1000.0}) {
    Harness h(WpowConfig{}, n);
    EXPECT_EQ(h.at(1.0), 1.0) << n;
    EXPECT_EQ(h.at(1.0005), 1.0) << n;
    EXPECT_EQ(h.at(1.2), 1.0) << n;
  }
}

TEST(WpowUnit, SmallExponentsPickAnExactOrSmallerM) {
  WpowConfig w;  // m = 16
  Harness one(w, 1.0), two(w, 2.0), three(w, 3.0), half(w, 0.5);
  EXPECT_EQ(one.plan.effective_m, 1);
  EXPECT_EQ(two.plan.effective_m, 2);
  EXPECT_EQ(three.plan.effective_m, 2);
  EXPECT_EQ(half.plan.effective_m, 1);
  for (int i = 0; i <= 100; ++i) {
    const double t = i / 100.0;
    EXPECT_NEAR(one.at(t), t, 3e-5);      // W_1 with zeta = 1 is t
    EXPECT_NEAR(two.at(t), t * t, 6e-5);  // W_2 with zeta = 1 is t^2
  }
  EXPECT_EQ(WpowUnit::multipliers(w), 4);
  w.timing = UnitTiming::kIterative;
  EXPECT_EQ(WpowUnit::multipliers(w), 1);
  EXPECT_EQ(WpowUnit::cycles_per_pixel(w), 5);  // base load + 4 squaring steps
}

TEST(WpowUnit, RejectsBadParams) {
  const FixedFormat series{32, 4, true, Quantization::kTruncate, Overflow::kWrap};
  WpowUnit unit(WpowConfig{}, series, kOut);
  EXPECT_THROW(unit.load_params({0, 5}), std::invalid_argument);
  EXPECT_THROW(unit.load_params({-1, 4}), std::invalid_argument);
  EXPECT_THROW(unit.load_params({3}), std::invalid_argument);
}

// README "Checked numerical facts": W16 with zeta = n/16 has epicentre max relative error
// ~1.51 % over n in [16, 1000]; a per-exponent fitted zeta brings it under 0.3 %.
TEST(WpowUnit, W16EpicentreFiguresInFloat) {
  double paper = 0, fitted = 0;
  for (int n = 16; n <= 1000; ++n) {
    paper = std::max(
        paper, measure_errors(n, [&](double t) { return wpow_float(t, n / 16.0, 16); }).epi_rel);
  }
  for (int n = 16; n <= 1000; n += 3) {
    const double z = fit_wpow_zeta(n, 16, FitObjective::kEpicentre);
    fitted =
        std::max(fitted, measure_errors(n, [&](double t) { return wpow_float(t, z, 16); }).epi_rel);
  }
  EXPECT_NEAR(paper, 0.0151, 0.0005);
  EXPECT_LT(fitted, 0.003);
}

}  // namespace
}  // namespace shadesim
