// CycleModel on its own, against closed forms derived from the documented pipeline
// (notes/rtl.md): a SPAN header accepted on cycle t has its pixel k leave on cycle t + 5 + k
// (so a span of length L ends on t + 4 + L)
// when nothing stalls; back-to-back spans leave no bubble; MATERIAL waits for an empty
// datapath; pixels leave only on cycles where pix_ready is high.
#include <gtest/gtest.h>

#include "model/command_stream.h"
#include "sim/harness/cycle_model.h"

namespace shadesim {
namespace {

SpanCmd span(int y, int x0, int len, bool last) {
  SpanCmd s;
  s.y = y;
  s.x0 = x0;
  s.length = len;
  s.last_in_row = last;
  return s;
}

std::vector<uint64_t> words(std::vector<Command> cmds) {
  CommandStream cs;
  cs.commands = std::move(cmds);
  return cs.encode();
}

TEST(CycleModel, SingleSpanLatencyIsFiveCycles) {
  for (int len : {1, 2, 7, 2048}) {
    const CycleRun r = CycleModel::run(words({span(3, 0, len, true)}), Stimulus{});
    ASSERT_EQ(r.scanlines.size(), 1u);
    EXPECT_EQ(r.scanlines[0].y, 3);
    EXPECT_EQ(r.scanlines[0].cycle, static_cast<uint64_t>(len + 4)) << "len " << len;
    EXPECT_EQ(r.pixels, static_cast<uint64_t>(len));
    EXPECT_EQ(r.cycles, static_cast<uint64_t>(len + 5));
  }
}

TEST(CycleModel, BackToBackSpansLeaveNoBubble) {
  for (int l1 : {1, 2, 5}) {
    for (int l2 : {1, 3}) {
      const CycleRun r = CycleModel::run(words({span(0, 0, l1, true), span(1, 0, l2, true)}), Stimulus{});
      ASSERT_EQ(r.scanlines.size(), 2u);
      EXPECT_EQ(r.scanlines[0].cycle, static_cast<uint64_t>(l1 + 4));
      EXPECT_EQ(r.scanlines[1].cycle, static_cast<uint64_t>(l1 + l2 + 4)) << l1 << "," << l2;
    }
  }
}

TEST(CycleModel, MaterialWaitsForEmptyDatapath) {
  MaterialCmd m;
  m.ambient = {0};
  m.spec_colour = {0};
  m.exponent = 1;  // header count 3
  const CycleRun r = CycleModel::run(words({span(0, 0, 10, true), m, span(1, 0, 1, true)}), Stimulus{});
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[0].cycle, 14u);
  // Last pixel handed over on cycle 13; MATERIAL accepted on 14, payload 15..17, SPAN on 18.
  EXPECT_EQ(r.scanlines[1].cycle, 18u + 4u + 1u);
}

TEST(CycleModel, TrianglePayloadTakesOneCyclePerWord) {
  TriangleCmd t;
  t.coef.assign(12, 0);
  const CycleRun r = CycleModel::run(words({t, span(0, 0, 6, true)}), Stimulus{});
  ASSERT_EQ(r.scanlines.size(), 1u);
  EXPECT_EQ(r.scanlines[0].cycle, 13u + 6u + 4u);
}

TEST(CycleModel, IdleGapsDelayAcceptance) {
  Stimulus s;
  s.gap_pct = 100;
  s.max_gap = 1;  // exactly one idle cycle before every word
  const CycleRun r = CycleModel::run(words({span(0, 0, 1, true), span(1, 0, 1, true)}), s);
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[0].cycle, 1u + 4u + 1u);  // accepted on cycle 1
  EXPECT_EQ(r.scanlines[1].cycle, 3u + 4u + 1u);  // accepted on cycle 3
}

TEST(CycleModel, PixelsLeaveOnlyWhenReady) {
  // Ready on every third cycle: pixel 0 is valid from cycle 5 and leaves on 6; each later
  // pixel is loaded on the cycle its predecessor leaves and leaves three cycles later.
  const auto w = words({span(0, 0, 4, true)});
  CycleModel m;
  CommandDriver d(w, Stimulus{});
  std::vector<uint64_t> left;
  for (uint64_t c = 0; c < 40; ++c) {
    const auto e = m.clock(d.valid(), d.word(), c % 3 == 0);
    d.clock(e.cmd_fire);
    if (e.pix_fire) left.push_back(c);
  }
  EXPECT_EQ(left, (std::vector<uint64_t>{6, 9, 12, 15}));
  EXPECT_TRUE(m.idle());
}

TEST(CycleModel, CountsPixelsAndScanlines) {
  Stimulus s;
  s.seed = 9;
  s.gap_pct = 40;
  s.max_gap = 5;
  s.stall_pct = 50;
  const CycleRun r = CycleModel::run(
      words({span(0, 0, 5, false), span(0, 9, 3, true), span(1, 0, 1, true), EndFrameCmd{}}), s);
  EXPECT_EQ(r.pixels, 9u);
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[0].y, 0);
  EXPECT_EQ(r.scanlines[1].y, 1);
  EXPECT_LT(r.scanlines[0].cycle, r.scanlines[1].cycle);
  EXPECT_GE(r.cycles, 9u + 5u);
}

}  // namespace
}  // namespace shadesim
