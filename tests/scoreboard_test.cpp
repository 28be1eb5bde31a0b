// The scoreboard (sim/harness/scoreboard.h) fed synthetic observations, no Verilator: each kind
// of mismatch is reported, with its place (scanline, y, x, cycle) and what was expected and
// seen, and a faithful run passes. The expected pixels and cycles are written out by hand.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sim/harness/cosim.h"

namespace shadesim {
namespace {

using Kind = Mismatch::Kind;

constexpr int kChannels = 3;
constexpr int kOutBits = 8;

PixelOut px(int x, int y, int r, int g, int b, bool eor = false, int lane = 0) {
  PixelOut p;
  p.x = static_cast<uint16_t>(x);
  p.y = static_cast<uint16_t>(y);
  p.colour[0] = static_cast<uint16_t>(r);
  p.colour[1] = static_cast<uint16_t>(g);
  p.colour[2] = static_cast<uint16_t>(b);
  p.end_of_row = eor;
  p.lane = lane;
  return p;
}

// Two scanlines, RGB: row 5 x = 3..5, row 6 x = 4..5.
std::vector<PixelOut> two_rows() {
  return {px(3, 5, 10, 20, 30), px(4, 5, 11, 21, 31), px(5, 5, 12, 22, 32, true),
          px(4, 6, 13, 23, 33), px(5, 6, 14, 24, 34, true)};
}

// The cycles on which the cycle model lets each pixel of two_rows() go (a one-cycle bubble
// between the rows).
const std::vector<uint64_t> kModelCycles = {100, 101, 102, 104, 105};

// Feeds the cycle model's beats (one pixel each) on kModelCycles and the RTL's pixels `rtl` on
// `rtl_cycles`, in cycle order, the RTL's first on a shared cycle.
void feed(Scoreboard& board, const std::vector<PixelOut>& rtl,
          const std::vector<uint64_t>& rtl_cycles,
          const std::vector<PixelOut>& model = two_rows()) {
  size_t r = 0, m = 0;
  while (r < rtl.size() || m < model.size()) {
    const bool rtl_next = r < rtl.size() && (m >= model.size() || rtl_cycles[r] <= kModelCycles[m]);
    if (rtl_next) {
      board.rtl_pixel(rtl[r], rtl_cycles[r]);
      ++r;
    } else {
      board.model_beat(kModelCycles[m], model[m].x, model[m].y, 1, model[m].end_of_row);
      ++m;
    }
  }
}

TEST(Scoreboard, AFaithfulRunPasses) {
  Scoreboard board(two_rows(), kChannels);
  feed(board, two_rows(), kModelCycles);
  EXPECT_FALSE(board.failed()) << board.first_mismatch().expected << " / "
                               << board.first_mismatch().got;
  EXPECT_TRUE(board.complete());
  EXPECT_EQ(board.pixels_checked(), 5u);
  EXPECT_EQ(board.scanlines_checked(), 2u);
  EXPECT_EQ(board.cycles(), 106u);  // the last pixel's cycle + 1
}

TEST(Scoreboard, TheRtlAheadOfTheCycleModelIsPairedLater) {
  // The model's pixels are all fed after the RTL's (a SystemC sink running before the model),
  // on the same cycles: still a pass.
  Scoreboard board(two_rows(), kChannels);
  const std::vector<PixelOut> want = two_rows();
  for (size_t k = 0; k < want.size(); ++k) board.rtl_pixel(want[k], kModelCycles[k]);
  EXPECT_FALSE(board.complete());
  for (size_t k = 0; k < want.size(); ++k) {
    board.model_beat(kModelCycles[k], want[k].x, want[k].y, 1, want[k].end_of_row);
  }
  EXPECT_FALSE(board.failed()) << board.first_mismatch().got;
  EXPECT_TRUE(board.complete());
}

TEST(Scoreboard, AChannelTwoErrorIsAPixelMismatch) {
  std::vector<PixelOut> rtl = two_rows();
  rtl[3].colour[2] = 34;  // row 6, x = 4: blue 33 in the model
  Scoreboard board(two_rows(), kChannels);
  feed(board, rtl, kModelCycles);
  ASSERT_TRUE(board.failed());
  const Mismatch m = board.first_mismatch();
  EXPECT_EQ(m.kind, Kind::kPixel);
  EXPECT_EQ(m.scanline, 1);
  EXPECT_EQ(m.y, 6);
  EXPECT_EQ(m.x, 4);
  EXPECT_EQ(m.cycle, 104u);
  EXPECT_EQ(m.expected, "(x=4 y=6 colour=13,23,33)");
  EXPECT_EQ(m.got, "(x=4 y=6 colour=13,23,34)");
  EXPECT_EQ(board.pixels_checked(), 3u);
}

TEST(Scoreboard, AChannelTwoErrorFromThePortsIsAPixelMismatch) {
  // The same error through the beat path the backends use (colour channels packed 8 bits each).
  const UnitConfig cfg = [] {
    UnitConfig c;
    c.channels = kChannels;
    c.out_bits = kOutBits;
    return c;
  }();
  Scoreboard board(two_rows(), kChannels);
  const std::vector<PixelOut> want = two_rows();
  for (size_t k = 0; k < want.size(); ++k) {
    board.model_beat(kModelCycles[k], want[k].x, want[k].y, 1, want[k].end_of_row);
    const uint64_t blue = k == 1 ? 0 : want[k].colour[2];  // pixel 1's blue is lost
    const uint64_t bus = want[k].colour[0] | uint64_t{want[k].colour[1]} << 8 | blue << 16;
    score_beat(
        board, want[k].x, want[k].y, 1, want[k].end_of_row,
        [bus](int lsb, int width) { return port_bits(bus, lsb, width); }, cfg, kModelCycles[k]);
  }
  ASSERT_TRUE(board.failed());
  EXPECT_EQ(board.first_mismatch().kind, Kind::kPixel);
  EXPECT_EQ(board.first_mismatch().x, 4);
  EXPECT_EQ(board.first_mismatch().y, 5);
  EXPECT_EQ(board.first_mismatch().got, "(x=4 y=5 colour=11,21,0)");
}

TEST(Scoreboard, AFlippedEndOfRowIsAPixelMismatch) {
  // Row 5's last pixel leaves without its end-of-row flag.
  std::vector<PixelOut> rtl = two_rows();
  rtl[2].end_of_row = false;
  Scoreboard board(two_rows(), kChannels);
  feed(board, rtl, kModelCycles);
  ASSERT_TRUE(board.failed());
  const Mismatch m = board.first_mismatch();
  EXPECT_EQ(m.kind, Kind::kPixel);
  EXPECT_EQ(m.scanline, 0);
  EXPECT_EQ(m.y, 5);
  EXPECT_EQ(m.x, 5);
  EXPECT_EQ(m.cycle, 102u);
  EXPECT_EQ(m.expected, "(x=5 y=5 colour=12,22,32 eor)");
  EXPECT_EQ(m.got, "(x=5 y=5 colour=12,22,32)");

  // And the flag on a pixel that does not end the row.
  rtl = two_rows();
  rtl[3].end_of_row = true;
  Scoreboard early(two_rows(), kChannels);
  feed(early, rtl, kModelCycles);
  ASSERT_TRUE(early.failed());
  EXPECT_EQ(early.first_mismatch().kind, Kind::kPixel);
  EXPECT_EQ(early.first_mismatch().x, 4);
  EXPECT_EQ(early.first_mismatch().got, "(x=4 y=6 colour=13,23,33 eor)");
}

TEST(Scoreboard, AnExtraPixelIsReported) {
  std::vector<PixelOut> rtl = two_rows();
  rtl.push_back(px(6, 6, 1, 2, 3));
  Scoreboard board(two_rows(), kChannels);
  feed(board, rtl, {100, 101, 102, 104, 105, 106});
  ASSERT_TRUE(board.failed());
  const Mismatch m = board.first_mismatch();
  EXPECT_EQ(m.kind, Kind::kExtraPixel);
  EXPECT_EQ(m.x, 6);
  EXPECT_EQ(m.y, 6);
  EXPECT_EQ(m.cycle, 106u);
  EXPECT_EQ(m.got, "(x=6 y=6 colour=1,2,3)");
  EXPECT_NE(m.expected.find("no more pixels"), std::string::npos) << m.expected;
}

TEST(Scoreboard, PixValidWhileDrainingIsAnExtraPixel) {
  Scoreboard board(two_rows(), kChannels);
  feed(board, two_rows(), kModelCycles);
  ASSERT_TRUE(board.complete());
  board.rtl_valid_after_end(7, 6, 1, 130);
  ASSERT_TRUE(board.failed());
  const Mismatch m = board.first_mismatch();
  EXPECT_EQ(m.kind, Kind::kExtraPixel);
  EXPECT_EQ(m.x, 7);
  EXPECT_EQ(m.y, 6);
  EXPECT_EQ(m.cycle, 130u);
  EXPECT_NE(m.got.find("pix_valid_o 1"), std::string::npos) << m.got;
}

TEST(Scoreboard, AMissingRowIsAPixelMismatchAtItsFirstPixel) {
  // Three rows expected; the RTL goes from row 5 straight to row 7.
  std::vector<PixelOut> want = two_rows();
  want.push_back(px(2, 7, 15, 25, 35, true));
  std::vector<PixelOut> rtl = {want[0], want[1], want[2], want[5]};
  Scoreboard board(want, kChannels);
  board.rtl_pixel(rtl[0], 100);
  board.rtl_pixel(rtl[1], 101);
  board.rtl_pixel(rtl[2], 102);
  board.rtl_pixel(rtl[3], 104);
  ASSERT_TRUE(board.failed());
  const Mismatch m = board.first_mismatch();
  EXPECT_EQ(m.kind, Kind::kPixel);
  EXPECT_EQ(m.scanline, 1);
  EXPECT_EQ(m.y, 6);
  EXPECT_EQ(m.x, 4);
  EXPECT_EQ(m.expected, "(x=4 y=6 colour=13,23,33)");
  EXPECT_EQ(m.got, "(x=2 y=7 colour=15,25,35 eor)");
}

TEST(Scoreboard, AMissingLastRowLeavesTheRunIncomplete) {
  // The RTL stops after row 5: never complete; the watchdog's hang names the pixel still owed.
  Scoreboard board(two_rows(), kChannels);
  const std::vector<PixelOut> want = two_rows();
  feed(board, {want[0], want[1], want[2]}, {100, 101, 102});
  EXPECT_FALSE(board.failed());
  EXPECT_FALSE(board.complete());
  EXPECT_TRUE(board.pixels_pending());
  board.hang(1200, 103, 1000);
  ASSERT_TRUE(board.failed());
  const Mismatch m = board.first_mismatch();
  EXPECT_EQ(m.kind, Kind::kHang);
  EXPECT_EQ(m.scanline, 1);
  EXPECT_EQ(m.y, 6);
  EXPECT_EQ(m.x, 4);
  EXPECT_EQ(m.got, "no pix_valid_o for 1098 cycles (103..1200; watchdog limit 1000)");
}

TEST(Scoreboard, AWrongRowCycleIsACycleMismatch) {
  // Row 5's end-of-row pixel leaves the RTL one cycle after the cycle model's.
  Scoreboard board(two_rows(), kChannels);
  feed(board, two_rows(), {100, 101, 103, 104, 105});
  ASSERT_TRUE(board.failed());
  const Mismatch m = board.first_mismatch();
  EXPECT_EQ(m.kind, Kind::kCycle);
  EXPECT_EQ(m.scanline, 0);
  EXPECT_EQ(m.y, 5);
  EXPECT_EQ(m.x, 5);
  EXPECT_EQ(m.cycle, 102u);  // the earlier of the two
  EXPECT_EQ(m.expected, "pixel 2 (x=5 y=5 colour=12,22,32 eor) leaves on cycle 102 (cycle model)");
  EXPECT_EQ(m.got, "it left on cycle 103 (RTL)");
  EXPECT_EQ(board.scanlines_checked(), 0u);
}

TEST(Scoreboard, EveryPixelsExitCycleIsCompared) {
  // A pixel inside row 6 leaves early (the row still ends on time): a cycle mismatch on it.
  Scoreboard board(two_rows(), kChannels);
  feed(board, two_rows(), {100, 101, 102, 103, 105});
  ASSERT_TRUE(board.failed());
  const Mismatch m = board.first_mismatch();
  EXPECT_EQ(m.kind, Kind::kCycle);
  EXPECT_EQ(m.scanline, 1);
  EXPECT_EQ(m.y, 6);
  EXPECT_EQ(m.x, 4);
  EXPECT_EQ(m.cycle, 103u);
  EXPECT_EQ(m.got, "it left on cycle 103 (RTL)");
  EXPECT_EQ(board.scanlines_checked(), 1u);
}

TEST(Scoreboard, AReadyMismatchIsReportedWithThePort) {
  Scoreboard board(two_rows(), kChannels);
  const std::vector<PixelOut> want = two_rows();
  feed(board, {want[0]}, {100}, {want[0]});
  CommandPortState port;
  port.valid = true;
  port.beat = 41;
  port.beats = 90;
  port.word0 = 0x0300000000000007ull;
  board.cmd_ready(99, true, true, port);  // agreeing: nothing
  EXPECT_TRUE(board.passed());
  board.cmd_ready(101, false, true, port);
  // It fails the run without stopping it (the pixel side may explain it later).
  EXPECT_FALSE(board.passed());
  EXPECT_FALSE(board.failed());
  const Mismatch m = board.first_mismatch();
  EXPECT_EQ(m.kind, Kind::kReady);
  EXPECT_EQ(m.cycle, 101u);
  // Placed at the pixel the output owes next.
  EXPECT_EQ(m.scanline, 0);
  EXPECT_EQ(m.y, 5);
  EXPECT_EQ(m.x, 4);
  EXPECT_EQ(m.expected,
            "cmd_ready_o 1 (cycle model), beat 41 of 90 on the port (cmd_valid_i 1, word 0 "
            "0x0300000000000007)");
  EXPECT_EQ(m.got, "cmd_ready_o 0 (RTL)");
}

TEST(Scoreboard, AReadyMismatchWhileIdleIsReportedToo) {
  Scoreboard board(two_rows(), kChannels);
  CommandPortState port;
  port.valid = false;
  port.beat = 3;
  port.beats = 90;
  port.word0 = 0xffull;
  board.cmd_ready(7, true, false, port);
  ASSERT_FALSE(board.passed());
  EXPECT_EQ(board.first_mismatch().kind, Kind::kReady);
  EXPECT_EQ(
      board.first_mismatch().expected,
      "cmd_ready_o 0 (cycle model), idle before beat 3 of 90 on the port (cmd_valid_i 0, word 0 "
      "0x00000000000000ff)");
  EXPECT_EQ(board.first_mismatch().got, "cmd_ready_o 1 (RTL)");
}

TEST(Scoreboard, APixelSideMismatchAfterAReadyMismatchIsReportedWithIt) {
  // A stall downstream shows on the command port first (cycle 101), then as a late pixel.
  Scoreboard board(two_rows(), kChannels);
  CommandPortState port;
  port.valid = true;
  port.beat = 12;
  port.beats = 40;
  port.word0 = 0x10;
  board.cmd_ready(101, false, true, port);
  feed(board, two_rows(), {100, 101, 102, 105, 106});
  ASSERT_TRUE(board.failed());
  const Mismatch m = board.first_mismatch();
  EXPECT_EQ(m.kind, Kind::kCycle);
  EXPECT_EQ(m.y, 6);
  EXPECT_EQ(m.x, 4);
  EXPECT_EQ(m.cycle, 104u);
  EXPECT_EQ(m.before,
            "cmd_ready_o differed first, on cycle 101: expected cmd_ready_o 1 (cycle model), beat "
            "12 of 40 "
            "on the port (cmd_valid_i 1, word 0 0x0000000000000010), got cmd_ready_o 0 (RTL)");
}

TEST(Scoreboard, TheFirstMismatchIsKept) {
  std::vector<PixelOut> rtl = two_rows();
  rtl[1].colour[0] = 0;
  Scoreboard board(two_rows(), kChannels);
  feed(board, rtl, kModelCycles);
  board.cmd_ready(200, true, false, CommandPortState{});
  board.timeout(300);
  ASSERT_TRUE(board.failed());
  EXPECT_EQ(board.first_mismatch().kind, Kind::kPixel);
  EXPECT_EQ(board.first_mismatch().cycle, 101u);
}

TEST(Scoreboard, ReferenceModelsThatDisagreeAreReported) {
  // The cycle model lets a pixel go that the bit-accurate model does not have at that place.
  Scoreboard board(two_rows(), kChannels);
  board.model_beat(100, 3, 5, 1, false);
  board.model_beat(101, 9, 5, 1, false);
  ASSERT_TRUE(board.failed());
  EXPECT_EQ(board.first_mismatch().kind, Kind::kCycle);
  EXPECT_EQ(board.first_mismatch().x, 9);
  EXPECT_NE(board.first_mismatch().got.find("the reference models disagree"), std::string::npos);
}

TEST(Scoreboard, AWrongPixelInLaneThreeIsReported) {
  // Four lanes, one 4-pixel span on row 2 in one beat; lane 3's green channel is off by one.
  UnitConfig cfg;
  cfg.channels = kChannels;
  cfg.out_bits = kOutBits;
  cfg.lanes = 4;
  const std::vector<PixelOut> want = {px(8, 2, 1, 2, 3, false, 0), px(9, 2, 4, 5, 6, false, 1),
                                      px(10, 2, 7, 8, 9, false, 2), px(11, 2, 10, 11, 12, true, 3)};
  Scoreboard board(want, kChannels, cfg.lanes);
  board.model_beat(50, 8, 2, 4, true);
  // The bus: lane j at bits [24 j, 24 j + 24), channel c at 8 c within it.
  std::vector<uint64_t> lanes;
  lanes.reserve(want.size());
  for (const PixelOut& p : want)
    lanes.push_back(p.colour[0] | uint64_t{p.colour[1]} << 8 | uint64_t{p.colour[2]} << 16);
  lanes[3] += uint64_t{1} << 8;
  score_beat(
      board, 8, 2, 0xF, true,
      [&lanes](int lsb, int width) {
        return port_bits(lanes[static_cast<size_t>(lsb / 24)], lsb % 24, width);
      },
      cfg, 50);
  ASSERT_TRUE(board.failed());
  const Mismatch m = board.first_mismatch();
  EXPECT_EQ(m.kind, Kind::kPixel);
  EXPECT_EQ(m.x, 11);
  EXPECT_EQ(m.y, 2);
  EXPECT_EQ(m.cycle, 50u);
  EXPECT_EQ(m.expected, "(x=11 y=2 colour=10,11,12 eor lane=3)");
  EXPECT_EQ(m.got, "(x=11 y=2 colour=10,12,12 eor lane=3)");
  EXPECT_EQ(board.pixels_checked(), 3u);
}

TEST(Scoreboard, MismatchKindsHaveNames) {
  EXPECT_EQ(to_string(Kind::kPixel), "pixel");
  EXPECT_EQ(to_string(Kind::kCycle), "cycle");
  EXPECT_EQ(to_string(Kind::kReady), "ready");
  EXPECT_EQ(to_string(Kind::kExtraPixel), "extra-pixel");
  EXPECT_EQ(to_string(Kind::kHang), "hang");
  EXPECT_EQ(to_string(Kind::kTimeout), "timeout");
}

}  // namespace
}  // namespace shadesim
