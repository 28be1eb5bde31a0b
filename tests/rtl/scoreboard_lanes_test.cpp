// The scoreboard with pixel lanes (sim/harness/cosim.h score_beat): an RTL beat is expanded into
// its valid lanes, and a beat whose lanes are not the model's - ending early, running into the
// next span, a hole in the mask, an empty mask - is a mismatch, not a silent pass. The expected
// pixels are written out by hand.
#include <gtest/gtest.h>

#include <vector>

#include "sim/harness/cosim.h"

namespace shadesim {
namespace {

// The pixels of spans (y, x0, len) on one row as the model emits them with `lanes` lanes: pixel
// k of a span on lane k mod lanes, colour x, end of row on the row's last pixel.
std::vector<PixelOut> row(const std::vector<std::pair<int, int>>& spans, int lanes) {
  std::vector<PixelOut> out;
  for (const auto& [x0, len] : spans) {
    for (int k = 0; k < len; ++k) {
      PixelOut p;
      p.x = static_cast<uint16_t>(x0 + k);
      p.y = 4;
      p.colour[0] = static_cast<uint16_t>(x0 + k);
      p.lane = k % lanes;
      out.push_back(p);
    }
  }
  out.back().end_of_row = true;
  return out;
}

UnitConfig four_lanes() {
  UnitConfig c;
  c.lanes = 4;
  return c;
}

struct Beat {
  int x;
  unsigned mask;
  bool eor;
};

// Feeds the beats on cycles 0, 1, ...; lane j's colour is x + j (the model's colour above). The
// cycle model's beats are the expected pixels' own (a beat starts at each lane-0 pixel), one a
// cycle from cycle 0 too.
Scoreboard run(const std::vector<PixelOut>& want, const std::vector<Beat>& beats) {
  const UnitConfig c = four_lanes();
  Scoreboard board(want, c.channels, c.lanes);
  uint64_t cycle = 0;
  for (size_t k = 0; k < want.size(); ++cycle) {
    size_t n = 1;
    while (k + n < want.size() && want[k + n].lane != 0) ++n;
    board.model_beat(cycle, want[k].x, want[k].y, static_cast<int>(n), want[k + n - 1].end_of_row);
    k += n;
  }
  cycle = 0;
  for (const Beat& b : beats) {
    const uint64_t x = static_cast<uint64_t>(b.x);
    score_beat(
        board, x, 4, b.mask, b.eor,
        [x](int lsb, int width) { return ((x + static_cast<uint64_t>(lsb / width)) & 0xff); }, c,
        cycle);
    ++cycle;
  }
  return board;
}

TEST(ScoreboardLanes, TheModelsBeatsPass) {
  // 5 pixels in 4 lanes: [10 11 12 13] [14 eor].
  const Scoreboard b = run(row({{10, 5}}, 4), {{10, 0xF, false}, {14, 0x1, true}});
  EXPECT_FALSE(b.failed()) << b.first_mismatch().expected << " / " << b.first_mismatch().got;
  EXPECT_TRUE(b.complete());
  EXPECT_EQ(b.pixels_checked(), 5u);
}

TEST(ScoreboardLanes, ABeatThatEndsEarlyIsAMismatch) {
  // Same pixels in the same order, but [10 11 12] [13 14]: pixel 13 on lane 0, not 3.
  const Scoreboard b = run(row({{10, 5}}, 4), {{10, 0x7, false}, {13, 0x3, true}});
  ASSERT_TRUE(b.failed());
  EXPECT_EQ(b.first_mismatch().kind, Mismatch::Kind::kPixel);
  EXPECT_EQ(b.first_mismatch().x, 13);
  EXPECT_EQ(b.pixels_checked(), 3u);
}

TEST(ScoreboardLanes, ABeatRunningIntoTheNextSpanIsAMismatch) {
  // Spans [10 11] and [12 13] on one row: one beat [10 11 12 13] puts pixel 12 on lane 2.
  const Scoreboard b = run(row({{10, 2}, {12, 2}}, 4), {{10, 0xF, true}});
  ASSERT_TRUE(b.failed());
  EXPECT_EQ(b.first_mismatch().x, 12);
  EXPECT_EQ(b.pixels_checked(), 2u);
}

TEST(ScoreboardLanes, MasksThatAreNotLanesZeroToNAreMismatches) {
  for (unsigned mask : {0x0u, 0x5u, 0xBu, 0x2u, 0x1Fu}) {
    const Scoreboard b = run(row({{10, 5}}, 4), {{10, mask, false}});
    ASSERT_TRUE(b.failed()) << mask;
    EXPECT_EQ(b.pixels_checked(), 0u) << mask;
    EXPECT_NE(b.first_mismatch().got.find("lane mask"), std::string::npos)
        << b.first_mismatch().got;
  }
}

TEST(ScoreboardLanes, EndOfRowOnTheWrongBeatIsAMismatch) {
  const Scoreboard b = run(row({{10, 5}}, 4), {{10, 0xF, true}, {14, 0x1, false}});
  ASSERT_TRUE(b.failed());
  EXPECT_EQ(b.first_mismatch().x, 13);  // its last lane claimed the end of the row
}

}  // namespace
}  // namespace shadesim
