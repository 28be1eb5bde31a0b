// Pixel lanes (UnitConfig::lanes, model/lane_fanout.h): the fan-out of one span setup into K
// lanes of K-step forward differences, against the one-lane engine's own recurrence run in
// exact (unbounded) arithmetic, and whole shipped scenes shaded with 2 and 4 lanes against one.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <variant>
#include <vector>

#include "host/frame.h"
#include "model/lane_fanout.h"
#include "model/series_engine.h"
#include "model/shade_unit.h"

namespace shadesim {
namespace {

// The one-lane recurrence v += d; d += d2 in 128-bit integers (no overflow rule): p(0..n-1).
std::vector<Int128> exact_values(const SeriesStart& s, int n) {
  std::vector<Int128> p;
  Int128 v = s.v, d = s.d;
  for (int i = 0; i < n; ++i) {
    p.push_back(v);
    v += d;
    d += s.d2;
  }
  return p;
}

// The series format's overflow rule written out here: clamp, or two's complement modulo 2^wl.
int64_t fit(Int128 x, const FixedFormat& f) {
  if (f.overflow == Overflow::kSaturate) {
    if (x > f.raw_max()) return f.raw_max();
    if (x < f.raw_min()) return f.raw_min();
    return static_cast<int64_t>(x);
  }
  const Int128 m = Int128{1} << f.wl;
  Int128 r = x % m;
  if (r < 0) r += m;
  if (r > f.raw_max()) r -= m;
  return static_cast<int64_t>(r);
}

SeriesStart random_start(std::mt19937_64& rng, const FixedFormat& f) {
  // Anywhere in the format, with the differences often small (as in a real span) and sometimes
  // at full range (so that every sum overflows the format).
  std::uniform_int_distribution<int64_t> any(f.raw_min(), f.raw_max());
  const int64_t small = f.raw_max() >> 6;
  std::uniform_int_distribution<int64_t> near(-small, small);
  const bool wide = rng() % 3 == 0;
  return {any(rng), wide ? any(rng) : near(rng), wide ? any(rng) : near(rng) / 64};
}

// Each lane's start is the exact value of pixel j and the exact K-step differences there,
// brought into the series format once by its overflow rule.
TEST(LaneFanout, StartsAreTheExactKStepDifferencesFittedOnce) {
  std::mt19937_64 rng(8);
  for (const char* fmt : {"s3.20:rnd:sat", "s2.10:sat", "s4.28:wrap", "s2.12"}) {
    const FixedFormat f = parse_fixed_format(fmt, "test");
    for (int k : {1, 2, 4}) {
      const LaneFanout fanout(f, k);
      for (int trial = 0; trial < 2000; ++trial) {
        const SeriesStart s = random_start(rng, f);
        const std::vector<Int128> p = exact_values(s, 3 * k);
        for (int j = 0; j < k; ++j) {
          const SeriesStart got = fanout(s, j);
          EXPECT_EQ(got.v, fit(p[j], f)) << fmt << " K=" << k << " j=" << j;
          EXPECT_EQ(got.d, fit(p[j + k] - p[j], f)) << fmt << " K=" << k << " j=" << j;
          EXPECT_EQ(got.d2, fit(p[j + 2 * k] - 2 * p[j + k] + p[j], f))
              << fmt << " K=" << k << " j=" << j;
        }
      }
    }
  }
}

// Wrapping: lane j stepped by its engine gives the one-lane engine's values at pixels
// j, j + K, ... bit for bit, however often the sums wrap.
TEST(LaneFanout, WrappingLanesEqualTheOneLaneEngine) {
  std::mt19937_64 rng(9);
  for (const char* fmt : {"s2.10:wrap", "s4.28:wrap"}) {
    const FixedFormat f = parse_fixed_format(fmt, "test");
    for (int k : {2, 4}) {
      const LaneFanout fanout(f, k);
      for (int trial = 0; trial < 300; ++trial) {
        const SeriesStart s = random_start(rng, f);
        const int len = 1 + static_cast<int>(rng() % 300);
        SeriesEngine one(f);
        one.load(s);
        std::vector<int64_t> want;
        for (int i = 0; i < len; ++i, one.step()) want.push_back(one.value());
        for (int j = 0; j < k; ++j) {
          SeriesEngine lane(f);
          lane.load(fanout(s, j));
          for (int i = j; i < len; i += k, lane.step()) {
            ASSERT_EQ(lane.value(), want[static_cast<size_t>(i)])
                << fmt << " K=" << k << " lane " << j << " pixel " << i;
          }
        }
      }
    }
  }
}

std::vector<PixelOut> shade(const PreparedFrame& f, int lanes) {
  UnitConfig c = f.config;
  c.lanes = lanes;
  return ShadeUnit(c).run(f.encoded.stream);
}

// Each pixel's lane from the stream's spans: pixel k of a span is on lane k mod K.
std::vector<int> lanes_of(const CommandStream& stream, int lanes) {
  std::vector<int> out;
  for (const Command& c : stream.commands) {
    if (const auto* s = std::get_if<SpanCmd>(&c)) {
      for (int k = 0; k < s->length; ++k) out.push_back(k % lanes);
    }
  }
  return out;
}

void expect_same_pixels(const PreparedFrame& f, const std::string& what) {
  const std::vector<PixelOut> one = shade(f, 1);
  for (int k : {2, 4}) {
    const std::vector<PixelOut> many = shade(f, k);
    const std::vector<int> lane = lanes_of(f.encoded.stream, k);
    ASSERT_EQ(one.size(), many.size()) << what;
    ASSERT_EQ(lane.size(), many.size()) << what;
    for (size_t i = 0; i < one.size(); ++i) {
      const PixelOut &a = one[i], &b = many[i];
      ASSERT_TRUE(a.x == b.x && a.y == b.y && a.colour == b.colour && a.end_of_row == b.end_of_row)
          << what << ": pixel " << i << " (x=" << a.x << " y=" << a.y << ") differs with " << k
          << " lanes";
      ASSERT_EQ(a.lane, 0) << what;
      ASSERT_EQ(b.lane, lane[i]) << what << ": pixel " << i;
    }
  }
}

// The shipped scenes at the default widths (series s4.28, wrapping): 2 and 4 lanes give the
// one-lane unit's pixels bit for bit, every lane index within its span.
TEST(PixelLanes, WrapLanesEqualOneLaneOnShippedScenes) {
  for (const char* name : {"sphere", "torus", "multi", "specular", "suzanne"}) {
    const std::string path = std::string(SHADESIM_SOURCE_DIR) + "/scenes/" + name + ".json";
    const PreparedFrame f = prepare_frame(path, FrameOptions{});
    ASSERT_EQ(f.config.series.overflow, Overflow::kWrap);
    expect_same_pixels(f, name);
  }
}

// The long-span hard scene (2048-pixel spans: the drift case) on a narrow wrapping series.
TEST(PixelLanes, WrapLanesEqualOneLaneOnLongSpans) {
  FrameOptions o;
  o.base.series = parse_fixed_format("s2.20:wrap", "test");
  o.base.coef = parse_fixed_format("s2.28:rnd:wrap", "test");
  const PreparedFrame f =
      prepare_frame(std::string(SHADESIM_SOURCE_DIR) + "/scenes/hard/long_span.json", o);
  expect_same_pixels(f, "long_span");
}

TEST(PixelLanes, RejectsOtherLaneCounts) {
  UnitConfig c;
  for (int k : {0, 3, 8, -1}) {
    c.lanes = k;
    EXPECT_THROW(ShadeUnit{c}, std::invalid_argument) << k;
  }
}

}  // namespace
}  // namespace shadesim
