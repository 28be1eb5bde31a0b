// SpanSetup + SeriesEngine against direct evaluation of the quantized quadratic, and the drift
// bound 2^-F (1 + L(L-1)/2) of README "Checked numerical facts", on spans up to 2048 pixels.
#define SC_INCLUDE_FX
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <systemc>

#include "model/series_engine.h"
#include "model/span_setup.h"
#include "model/unit_config.h"

namespace shadesim {
namespace {

// Exact value of the quadratic with integer offsets, as a raw integer with coef fraction bits.
// Written out term by term, independently of SpanSetup's forward-difference form.
Int128 direct(const int64_t* t, int64_t x, int64_t y) {
  return Int128{t[0]} + Int128{t[1]} * y + Int128{t[2]} * x + Int128{t[3]} * y * y +
         Int128{t[4]} * x * y + Int128{t[5]} * x * x;
}

struct Drift {
  double worst_lsb = 0;  // worst |engine - exact| over the span, in series LSBs
};

// Runs one span of `len` pixels and returns the worst error against the direct evaluation.
Drift run_span(const FixedFormat& coef, const FixedFormat& series, const int64_t* t, int dx, int dy,
               int len) {
  SpanSetup setup(coef, series, UnitConfig::kMaxOffsetBits);
  SeriesEngine engine(series);
  engine.load(setup(t, dx, dy));
  Drift drift;
  const int shift = coef.frac_bits() - series.frac_bits();
  for (int k = 0; k < len; ++k) {
    const double exact_lsb = std::ldexp(static_cast<double>(direct(t, dx + k, dy)), -shift);
    drift.worst_lsb =
        std::max(drift.worst_lsb, std::fabs(static_cast<double>(engine.value()) - exact_lsb));
    engine.step();
  }
  return drift;
}

// Random coefficients typical of a shading series: T0 ~ 1, slopes ~ 1/L, curvature ~ 1/L^2, so
// that the quadratic stays inside the series range over the whole span and the start offsets
// (|dx|, |dy| <= 64) used below.
void random_coefficients(std::mt19937_64& rng, const FixedFormat& coef, int len, int64_t* t) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double l = len + 64;
  const double vals[6] = {0.5 + 0.4 * u(rng),     0.5 * u(rng) / l,       0.5 * u(rng) / l,
                          0.5 * u(rng) / (l * l), 0.5 * u(rng) / (l * l), 0.5 * u(rng) / (l * l)};
  for (int i = 0; i < 6; ++i) t[i] = coef.from_double(vals[i]);
}

TEST(Series, ExactWhenSeriesKeepsAllCoefficientBits) {
  const FixedFormat coef{32, 4, true};
  const FixedFormat series{32, 4, true, Quantization::kTruncate, Overflow::kWrap};
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    int64_t t[6];
    const int len = 1 + static_cast<int>(rng() % 2048);
    random_coefficients(rng, coef, len, t);
    const int dx = -static_cast<int>(rng() % 64), dy = static_cast<int>(rng() % 64) - 32;
    EXPECT_EQ(run_span(coef, series, t, dx, dy, len).worst_lsb, 0.0) << "len " << len;
  }
}

class DriftBound : public ::testing::TestWithParam<std::tuple<int, Quantization>> {};

TEST_P(DriftBound, ForwardDifferencesStayWithinProvenBound) {
  const auto [len, quant] = GetParam();
  const FixedFormat coef{40, 4, true};  // 36 fraction bits: rounding into the series loses 8
  const FixedFormat series{32, 4, true, quant, Overflow::kWrap};
  // Truncation: each of v, d, d2 is low by [0, 1) LSB, so after k steps the error is below
  // 1 + k + k(k-1)/2 = 1 + (k+1)k/2 <= 1 + L(L-1)/2 LSB for k <= L-1. Round-to-nearest halves it.
  const double bound =
      (1.0 + len * (len - 1) / 2.0) * (quant == Quantization::kTruncate ? 1.0 : 0.5);
  std::mt19937_64 rng(static_cast<uint64_t>(len) * 31 + static_cast<int>(quant));
  double worst = 0;
  for (int trial = 0; trial < 100; ++trial) {
    int64_t t[6];
    random_coefficients(rng, coef, len, t);
    const int dx = -static_cast<int>(rng() % 16), dy = static_cast<int>(rng() % 16) - 8;
    worst = std::max(worst, run_span(coef, series, t, dx, dy, len).worst_lsb);
  }
  EXPECT_LE(worst, bound) << "L=" << len;
  // The bound is not vacuous: long spans really drift by many LSBs.
  if (len >= 64) {
    EXPECT_GT(worst, 4.0) << "L=" << len;
  }
}

INSTANTIATE_TEST_SUITE_P(Lengths, DriftBound,
                         ::testing::Combine(::testing::Values(1, 2, 64, 256, 1024, 2048),
                                            ::testing::Values(Quantization::kTruncate,
                                                              Quantization::kRoundNearest)));

TEST(Series, DesignBriefFractionBitsKeepDriftUnderHalfAnEightBitStep) {
  // F >= 20, 24, 28, 30 for L = 64, 256, 1024, 2048 (truncation): bound * 2^-F <= 2^-9.
  const std::pair<int, int> cases[] = {{64, 20}, {256, 24}, {1024, 28}, {2048, 30}};
  for (const auto& [len, f] : cases) {
    const double bound = std::ldexp(1.0 + len * (len - 1) / 2.0, -f);
    EXPECT_LE(bound, std::ldexp(1.0, -9)) << "L=" << len << " F=" << f;
    EXPECT_GT(bound * 2, std::ldexp(1.0, -9)) << "F=" << f << " is not the smallest for L=" << len;
  }
}

TEST(Series, WrapAndSaturateFollowTheFormat) {
  const FixedFormat wrap{8, 2, true, Quantization::kTruncate, Overflow::kWrap};  // raw -128..127
  const FixedFormat sat{8, 2, true, Quantization::kTruncate, Overflow::kSaturate};
  SeriesEngine w(wrap), s(sat);
  w.load({120, 10, 0});
  s.load({120, 10, 0});
  w.step();
  s.step();
  EXPECT_EQ(w.value(), 130 - 256);
  EXPECT_EQ(s.value(), 127);
}

// The engines' adders against sc_fix (IEEE 1666) as an independent oracle of wrap and
// saturation: v <- fit(v + d) and d <- fit(d + d2), both from the old d, for a bank of engines
// and for single engines.
int64_t sc_fit(int64_t raw, const FixedFormat& f) {
  sc_dt::sc_fix v(f.wl, f.iwl, sc_dt::SC_TRN,
                  f.overflow == Overflow::kWrap ? sc_dt::SC_WRAP : sc_dt::SC_SAT);
  v = std::ldexp(static_cast<double>(raw), -f.frac_bits());  // exact: |raw| < 2^14
  return static_cast<int64_t>(std::ldexp(v.to_double(), f.frac_bits()));
}

TEST(Series, BankAndEnginesStepAsScFixAdders) {
  std::mt19937_64 rng(11);
  for (auto o : {Overflow::kWrap, Overflow::kSaturate}) {
    const FixedFormat f{12, 3, true, Quantization::kTruncate, o};  // narrow: overflow happens
    std::uniform_int_distribution<int64_t> raw(f.raw_min(), f.raw_max());
    const int n = 5;
    SeriesBank bank(f, n);
    std::vector<SeriesEngine> engines(n, SeriesEngine(f));
    std::vector<SeriesStart> want(n);
    for (int i = 0; i < n; ++i) {
      want[static_cast<size_t>(i)] = {raw(rng), raw(rng) / 16, raw(rng) / 256};
      bank.load(i, want[static_cast<size_t>(i)]);
      engines[static_cast<size_t>(i)].load(want[static_cast<size_t>(i)]);
    }
    int overflowed = 0;
    for (int k = 0; k < 500; ++k) {
      for (int i = 0; i < n; ++i) {
        const SeriesStart& w = want[static_cast<size_t>(i)];
        ASSERT_EQ(bank.values()[i], w.v) << "step " << k << " series " << i;
        ASSERT_EQ(engines[static_cast<size_t>(i)].value(), w.v) << "step " << k << " series " << i;
        ASSERT_EQ(engines[static_cast<size_t>(i)].state().d, w.d)
            << "step " << k << " series " << i;
      }
      bank.step();
      for (auto& e : engines) e.step();
      for (SeriesStart& w : want) {
        overflowed += !f.holds(w.v + w.d);
        const int64_t old_d = w.d;
        w.d = sc_fit(w.d + w.d2, f);
        w.v = sc_fit(w.v + old_d, f);
      }
    }
    EXPECT_GT(overflowed, 0) << "the test never reached the overflow rule";
  }
}

}  // namespace
}  // namespace shadesim
