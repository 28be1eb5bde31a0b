// FixedFormat's quantization and overflow rules against SystemC's sc_fix (IEEE 1666) as oracle.
#define SC_INCLUDE_FX
#include "model/fixed_point.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <systemc>

namespace shadesim {
namespace {

sc_dt::sc_q_mode to_sc(Quantization q) {
  return q == Quantization::kTruncate ? sc_dt::SC_TRN : sc_dt::SC_RND;
}
sc_dt::sc_o_mode to_sc(Overflow o) {
  return o == Overflow::kSaturate ? sc_dt::SC_SAT : sc_dt::SC_WRAP;
}

// The raw integer sc_fix holds, read back through its double value (exact for wl <= 53).
int64_t sc_raw(double x, const FixedFormat& f) {
  if (f.is_signed) {
    sc_dt::sc_fix v(f.wl, f.iwl, to_sc(f.quant), to_sc(f.overflow));
    v = x;
    return static_cast<int64_t>(std::ldexp(v.to_double(), f.frac_bits()));
  }
  sc_dt::sc_ufix v(f.wl, f.iwl, to_sc(f.quant), to_sc(f.overflow));
  v = x;
  return static_cast<int64_t>(std::ldexp(v.to_double(), f.frac_bits()));
}

struct Case {
  int wl, iwl;
  bool is_signed;
};

class FixedVsScFix : public ::testing::TestWithParam<Case> {};

TEST_P(FixedVsScFix, FromDoubleMatchesAllRules) {
  const Case c = GetParam();
  std::mt19937_64 rng(1234 + c.wl * 100 + c.iwl);
  for (auto q : {Quantization::kTruncate, Quantization::kRoundNearest}) {
    for (auto o : {Overflow::kSaturate, Overflow::kWrap}) {
      FixedFormat f{c.wl, c.iwl, c.is_signed, q, o};
      // Span well past the representable range so both overflow rules are exercised, and
      // values with bits below the LSB so both quantization rules are.
      const double range = std::ldexp(1.0, c.iwl + 2);
      std::uniform_real_distribution<double> dist(-range, range);
      for (int i = 0; i < 4000; ++i) {
        double x = dist(rng);
        if (i % 7 == 0)
          x = std::ldexp(std::round(std::ldexp(x, f.frac_bits() + 1)),
                         -(f.frac_bits() + 1));  // exact ties
        ASSERT_EQ(f.from_double(x), sc_raw(x, f)) << f.to_string() << " x=" << x;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, FixedVsScFix,
                         ::testing::Values(Case{8, 1, true}, Case{8, 0, false}, Case{12, 4, true},
                                           Case{17, 1, false}, Case{32, 4, true}, Case{36, 4, true},
                                           Case{20, 8, false}, Case{6, 6, true},
                                           Case{10, -2, true}));

TEST(FixedPoint, QuantizeRawMatchesScFixOnShiftedIntegers) {
  // quantize(raw, src_frac) is what the datapaths call; check it against sc_fix on values that
  // are exactly raw * 2^-src_frac.
  std::mt19937_64 rng(99);
  std::uniform_int_distribution<int64_t> dist(-(int64_t{1} << 40), int64_t{1} << 40);
  for (auto q : {Quantization::kTruncate, Quantization::kRoundNearest}) {
    for (auto o : {Overflow::kSaturate, Overflow::kWrap}) {
      const FixedFormat f{16, 3, true, q, o};
      for (int i = 0; i < 5000; ++i) {
        const int64_t raw = dist(rng);
        const int src_frac = 30;
        const double x = std::ldexp(static_cast<double>(raw), -src_frac);  // exact: 41 bits
        ASSERT_EQ(f.quantize(raw, src_frac), sc_raw(x, f)) << f.to_string() << " raw=" << raw;
      }
    }
  }
}

TEST(FixedPoint, RawOverflowHelpersMatchScFix) {
  // wrap / saturate / fit on a raw value already at the format's fraction bits (the per-pixel
  // path), against sc_fix fed the exact value raw * 2^-frac: every raw in [-4 2^wl, 4 2^wl) for
  // narrow formats, random raws up to 2^52 for wide ones (exact in a double), signed and unsigned.
  std::mt19937_64 rng(5);
  for (const Case c :
       {Case{5, 2, true}, Case{5, 2, false}, Case{8, 8, true}, Case{1, 1, false},
        Case{12, -3, true}, Case{32, 4, true}, Case{36, 4, true}, Case{40, 3, false}}) {
    for (auto o : {Overflow::kSaturate, Overflow::kWrap}) {
      const FixedFormat f{c.wl, c.iwl, c.is_signed, Quantization::kTruncate, o};
      auto check = [&](int64_t raw) {
        const int64_t want = sc_raw(std::ldexp(static_cast<double>(raw), -f.frac_bits()), f);
        const FixedFormat w{f.wl, f.iwl, f.is_signed, f.quant, Overflow::kWrap};
        const FixedFormat s{f.wl, f.iwl, f.is_signed, f.quant, Overflow::kSaturate};
        ASSERT_EQ(f.fit(raw), want) << f.to_string() << " raw=" << raw;
        ASSERT_EQ(f.fit(Int128{raw}), want) << f.to_string() << " raw=" << raw << " (Int128)";
        ASSERT_EQ(o == Overflow::kWrap ? f.wrap(raw) : f.saturate(raw), want) << f.to_string();
        ASSERT_EQ((o == Overflow::kWrap ? w : s).fit(raw), want) << f.to_string();
        ASSERT_EQ(f.holds(raw), raw >= f.raw_min() && raw <= f.raw_max()) << f.to_string();
      };
      if (c.wl <= 12) {
        for (int64_t raw = -(int64_t{4} << c.wl); raw < (int64_t{4} << c.wl); ++raw) check(raw);
      } else {
        std::uniform_int_distribution<int64_t> dist(-(int64_t{1} << 52), int64_t{1} << 52);
        for (int i = 0; i < 20000; ++i) check(i % 2 ? dist(rng) : dist(rng) >> (i % 50));
      }
    }
  }
  // Int128 sums far outside int64: wrap keeps the low wl bits (closed form: the value modulo
  // 2^wl, brought into [-2^(wl-1), 2^(wl-1))), saturate clamps.
  const FixedFormat w{36, 4, true, Quantization::kTruncate, Overflow::kWrap};
  const FixedFormat s{36, 4, true, Quantization::kTruncate, Overflow::kSaturate};
  for (const Int128 big :
       {(Int128{1} << 100) + 12345, -(Int128{1} << 90) - 7, (Int128{3} << 70) - 1}) {
    const Int128 m = Int128{1} << 36;
    const Int128 low = ((big % m) + m) % m;
    const int64_t want = static_cast<int64_t>(low >= m / 2 ? low - m : low);
    EXPECT_EQ(w.wrap(big), want);
    EXPECT_EQ(s.saturate(big), big > 0 ? s.raw_max() : s.raw_min());
  }
}

TEST(FixedPoint, ExhaustiveSmallFormatAgainstClosedForm) {
  // Every 10-bit source value into a 5-bit format: closed forms for floor/round and clamp/wrap.
  for (auto q : {Quantization::kTruncate, Quantization::kRoundNearest}) {
    for (auto o : {Overflow::kSaturate, Overflow::kWrap}) {
      const FixedFormat f{5, 2, true, q, o};  // s2.3: raw -16..15
      for (int64_t raw = -512; raw < 512; ++raw) {
        const double x = raw / 64.0;  // src_frac 6
        double r = x * 8.0;
        r = q == Quantization::kTruncate ? std::floor(r) : std::floor(r + 0.5);
        int64_t expect = static_cast<int64_t>(r);
        if (o == Overflow::kSaturate) {
          expect = std::clamp<int64_t>(expect, -16, 15);
        } else {
          expect = ((expect + 16) % 32 + 32) % 32 - 16;
        }
        ASSERT_EQ(f.quantize(raw, 6), expect) << f.to_string() << " raw=" << raw;
      }
    }
  }
}

TEST(FixedPoint, ParseAndPrintRoundTrip) {
  for (const char* text : {"s4.28", "u1.16", "s4.32:rnd", "u0.8:rnd:wrap", "s1.7:wrap"}) {
    EXPECT_EQ(parse_fixed_format(text, "t").to_string(), text);
  }
  const auto f = parse_fixed_format("s4.28", "t");
  EXPECT_EQ(f.wl, 32);
  EXPECT_EQ(f.iwl, 4);
  EXPECT_TRUE(f.is_signed);
}

// What a width without suffixes means, against SystemC's own defaults (sc_fix(wl, iwl) with no
// modes given: SC_TRN, SC_WRAP in IEEE 1666's default sc_fxtype_context). shadesim reads "s4.28"
// as truncate and saturate (its stream headers and UnitConfig files write saturating formats
// without a suffix), so the quantization agrees with sc_fix and the overflow does not: the width
// options warn when given a width with no overflow suffix (sim/jobs/unit_widths.h), and
// "s4.28:wrap" is what sc_fix's s4.28 means.
TEST(FixedPoint, SuffixlessWidthTruncatesLikeScFixButSaturatesWhereScFixWraps) {
  const FixedFormat plain = parse_fixed_format("s2.4", "t");
  const FixedFormat wrap = parse_fixed_format("s2.4:wrap", "t");
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> dist(-8.0, 8.0);
  int saturate_differs = 0;
  for (int i = 0; i < 4000; ++i) {
    const double x = dist(rng);
    sc_dt::sc_fix sc(plain.wl, plain.iwl);  // SystemC's default modes
    sc = x;
    const int64_t sc_value = static_cast<int64_t>(std::ldexp(sc.to_double(), plain.frac_bits()));
    ASSERT_EQ(wrap.from_double(x), sc_value) << "x=" << x;
    if (plain.holds(static_cast<int64_t>(std::floor(std::ldexp(x, plain.frac_bits()))))) {
      ASSERT_EQ(plain.from_double(x), sc_value) << "in range, x=" << x;  // truncation agrees
    } else {
      saturate_differs += plain.from_double(x) != sc_value;
    }
  }
  EXPECT_GT(saturate_differs, 1000);  // out of range: saturated here, wrapped by sc_fix
}

TEST(FixedPoint, ParseRejectsMalformedWithFieldName) {
  for (const char* text : {"", "x4.28", "s4", "s4.", "s.28", "s4.28:foo", "s4.2x", "s70.10"}) {
    try {
      parse_fixed_format(text, "--series");
      FAIL() << "accepted '" << text << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--series"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace shadesim
