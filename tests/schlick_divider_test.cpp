// SchlickDivider against integer division and double precision: the bit-serial divider over all
// operand pairs at small widths, a derived bound against t / (n - n t + t), and the clamps.
#include "model/schlick_divider.h"

#include <gtest/gtest.h>

#include <cmath>

#include "host/specular_setup.h"
#include "model/specular_unit.h"

namespace shadesim {
namespace {

TEST(SchlickDivider, BitSerialDivideIsFloorQuotientExhaustive) {
  for (int q : {1, 4, 8}) {
    for (uint64_t den = 1; den < 256; ++den) {
      for (uint64_t num = 0; num < den; ++num) {
        ASSERT_EQ(SchlickDivider::divide(num, den, q), (num << q) / den)
            << num << "/" << den << " Q " << q;
      }
    }
  }
}

struct Harness {
  UnitConfig cfg;
  SpecularSeriesPlan plan;
  SpecularUnit unit;
  Harness(const SchlickConfig& s, double n)
      : cfg(make(s)), plan(plan_specular(cfg, n)), unit(cfg) {}
  static UnitConfig make(const SchlickConfig& s) {
    UnitConfig c;
    c.specular.kind = SpecularUnitKind::kSchlick;
    c.specular.schlick = s;
    return c;
  }
  double at(double t) const {
    int64_t v[2];
    for (int i = 0; i < 2; ++i)
      v[i] = cfg.series.from_double(plan.affine[i].first * t + plan.affine[i].second);
    return cfg.specular.out.to_double(unit.evaluate(v));
  }
};

// Bound: each operand is off by at most e = 2^-D (divider truncation) + 2^-28 (series
// truncation), so num/den is off by at most S (e/num + e/den) / (1 - e/den); then the quotient
// truncation 2^-Q and the output truncation 2^-16.
TEST(SchlickDivider, WithinDerivedBoundOfDouble) {
  for (int q : {8, 16}) {
    for (int d : {12, 24}) {
      for (double n : {1.0, 2.0, 2.5, 16.0, 1000.0}) {
        SchlickConfig s;
        s.quotient_bits = q;
        s.operand_bits = d;
        Harness h(s, n);
        const double e = std::ldexp(1.0, -d) + std::ldexp(1.0, -28);
        for (int i = 1; i < 4000; ++i) {
          const double t = i / 4000.0;
          const double num = t / n, den = (n - (n - 1) * t) / n;
          const double exact = t / (n - n * t + t);
          const double bound = exact * (e / num + e / den) / (1 - e / den) + std::ldexp(1.0, -q) +
                               std::ldexp(1.0, -16);
          ASSERT_LE(std::fabs(h.at(t) - exact), bound)
              << "t " << t << " n " << n << " Q " << q << " D " << d;
        }
      }
    }
  }
}

TEST(SchlickDivider, ClampsAndEnds) {
  SchlickConfig s;
  for (double n : {1.0, 8.0, 1000.0}) {
    Harness h(s, n);
    EXPECT_EQ(h.at(0.0), 0.0) << n;
    EXPECT_EQ(h.at(-0.2), 0.0) << n;   // numerator <= 0
    EXPECT_EQ(h.at(1.0), 1.0) << n;    // numerator == denominator: quotient saturates at 1
    EXPECT_EQ(h.at(1.001), 1.0) << n;  // numerator > denominator
    EXPECT_EQ(h.at(3.0), 1.0) << n;    // denominator <= 0 for n > 1.5
  }
}

TEST(SchlickDivider, DenominatorTowardZeroAndDirectOperands) {
  const FixedFormat series{32, 4, true, Quantization::kTruncate, Overflow::kWrap};
  const FixedFormat out{17, 1, false, Quantization::kTruncate, Overflow::kSaturate};
  SchlickConfig s;
  s.operand_bits = 8;
  SchlickDivider div(s, series, out);
  const int64_t one = int64_t{1} << 28;
  EXPECT_EQ(div.evaluate(one / 4, 0), int64_t{1} << 16);          // den == 0
  EXPECT_EQ(div.evaluate(one / 4, -5), int64_t{1} << 16);         // den < 0
  EXPECT_EQ(div.evaluate(1, 1), 0);                               // both below the operand LSB
  EXPECT_EQ(div.evaluate(one >> 6, one >> 7), int64_t{1} << 16);  // quotient 2 >= 1
  EXPECT_EQ(div.evaluate(one >> 7, one >> 6), int64_t{1} << 15);  // 1/2 exactly (2 / 4 LSBs)
  EXPECT_EQ(div.evaluate(one >> 9, one >> 6), 0);                 // numerator below the LSB
  EXPECT_EQ(div.evaluate(0, one), 0);
  EXPECT_THROW(div.load_params({1}), std::invalid_argument);
}

TEST(SchlickDivider, TimingStylesSameBitsDifferentCycles) {
  SchlickConfig iter, pipe;
  iter.quotient_bits = pipe.quotient_bits = 12;
  pipe.timing = UnitTiming::kPipelined;
  EXPECT_EQ(SchlickDivider::cycles_per_pixel(iter), 12);
  EXPECT_EQ(SchlickDivider::cycles_per_pixel(pipe), 1);
  EXPECT_EQ(SchlickDivider::latency(iter), 12);
  EXPECT_EQ(SchlickDivider::latency(pipe), 12);
  Harness a(iter, 37.0), b(pipe, 37.0);
  for (int i = 0; i <= 1000; ++i) ASSERT_EQ(a.at(i / 1000.0), b.at(i / 1000.0));
}

TEST(SchlickDivider, SmallestWidths) {
  SchlickConfig s;
  s.quotient_bits = 1;
  s.operand_bits = 2;
  Harness h(s, 4.0);
  for (int i = 0; i <= 100; ++i) {
    const double t = i / 100.0;
    const double v = h.at(t);
    EXPECT_TRUE(v == 0.0 || v == 0.5 || v == 1.0) << t;
  }
  EXPECT_EQ(h.at(1.0), 1.0);
}

// Schlick's lobe is not t^n: ~52 8-bit LSB worst at equal n (README "Checked numerical facts");
// fitting n' for the absolute error about halves it.
TEST(SchlickDivider, FittedExponentHalvesAbsoluteError) {
  double paper = 0, fitted = 0;
  for (double n : {16.0, 100.0, 1000.0}) {
    paper =
        std::max(paper, measure_errors(n, [&](double t) { return schlick_float(t, n); }).abs_lsb);
    const double np = fit_schlick_n(n, FitObjective::kAbsolute);
    fitted =
        std::max(fitted, measure_errors(n, [&](double t) { return schlick_float(t, np); }).abs_lsb);
  }
  EXPECT_NEAR(paper, 52.0, 1.0);
  EXPECT_LT(fitted, 0.6 * paper);
}

}  // namespace
}  // namespace shadesim
