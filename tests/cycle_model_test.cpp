// CycleModel on its own, against closed forms derived from the documented pipeline
// (README, "RTL and co-simulation"): a SPAN header accepted on cycle t has its pixel k leave on
// cycle t + 5 + k (so a span of length L ends on t + 4 + L) when nothing stalls; back-to-back spans
// leave no bubble; MATERIAL waits for an empty datapath; pixels leave only on cycles where
// pix_ready is high. A pipelined specular slot of latency L adds L to every pixel; an iterative one
// of interval Q has pixel k leave on t + 5 + Q (k + 1). The cycle breakdown is checked against
// hand-counted schedules.
#include "model/cycle_model.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "model/command_stream.h"
#include "sim/harness/cycle_run.h"

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

// A MATERIAL of one channel and one light: header count 3 (ambient, spec_colour, exponent).
MaterialCmd small_material() {
  MaterialCmd m;
  m.ambient = {0};
  m.spec_colour = {0};
  m.exponent = 1;
  return m;
}

// The words of `cmds`; a TRIANGLE takes one payload word per coefficient given, whatever the
// unit's coefficient layout (the cycle model reads only its header's count).
std::vector<uint64_t> words(std::vector<Command> cmds) {
  std::vector<uint64_t> out;
  for (Command& c : cmds) {
    if (const auto* t = std::get_if<TriangleCmd>(&c)) {
      out.push_back(CommandWord::triangle(t->xo, t->yo, t->coef.size()).bits);
      out.insert(out.end(), t->coef.size(), 0);
      continue;
    }
    CommandStream cs;
    cs.commands = {std::move(c)};
    const auto w = cs.encode();
    out.insert(out.end(), w.begin(), w.end());
  }
  return out;
}

TEST(CycleModel, SingleSpanLatencyIsFiveCycles) {
  for (int len : {1, 2, 7, 2048}) {
    const CycleRun r = run_cycle_model(words({span(3, 0, len, true)}), Stimulus{});
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
      const CycleRun r =
          run_cycle_model(words({span(0, 0, l1, true), span(1, 0, l2, true)}), Stimulus{});
      ASSERT_EQ(r.scanlines.size(), 2u);
      EXPECT_EQ(r.scanlines[0].cycle, static_cast<uint64_t>(l1 + 4));
      EXPECT_EQ(r.scanlines[1].cycle, static_cast<uint64_t>(l1 + l2 + 4)) << l1 << "," << l2;
    }
  }
}

TEST(CycleModel, MaterialWaitsForEmptyDatapath) {
  const MaterialCmd m = small_material();
  const CycleRun r =
      run_cycle_model(words({span(0, 0, 10, true), m, span(1, 0, 1, true)}), Stimulus{});
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[0].cycle, 14u);
  // Last pixel handed over on cycle 13; MATERIAL accepted on 14, payload 15..17, SPAN on 18.
  EXPECT_EQ(r.scanlines[1].cycle, 18u + 4u + 1u);
}

// Two material buffers: the MATERIAL switches to the bank no span reads, so the drain is gone;
// switching back waits for the first bank's span, and a TABLE that is not per-material still
// waits for the empty datapath.
TEST(CycleModel, TwoMaterialBuffersRemoveTheDrain) {
  const MaterialCmd m = small_material();
  CycleConfig two;
  two.material_buffers = 2;
  // SPAN 0 (bank 0) on 0, its pixels leave on 5..14. MATERIAL (to bank 1) on 1, payload 2..4,
  // SPAN 1 on 5: its pixel right behind span 0's, on 15.
  CycleRun r =
      run_cycle_model(words({span(0, 0, 10, true), m, span(1, 0, 1, true)}), Stimulus{}, two);
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[0].cycle, 14u);
  EXPECT_EQ(r.scanlines[1].cycle, 15u);
  EXPECT_EQ(r.cycles, 16u);
  // A second MATERIAL (back to bank 0) waits 6..13: span 0's last pixel leaves the slot on the
  // edge of 13. Accepted on 14, payload 15..17, SPAN 2 on 18, its pixel on 23 (as one buffer).
  r = run_cycle_model(words({span(0, 0, 10, true), m, span(1, 0, 1, true), m, span(2, 0, 1, true)}),
                      Stimulus{}, two);
  ASSERT_EQ(r.scanlines.size(), 3u);
  EXPECT_EQ(r.scanlines[1].cycle, 15u);
  EXPECT_EQ(r.scanlines[2].cycle, 23u);
  // MATERIAL on 1 (payload 2..4); the TABLE header waits 5..13 for the empty datapath, is
  // accepted on 14, its 2 words take 15, 16; SPAN 1 on 17, its pixel on 22.
  TableCmd t;
  t.base = 0;
  t.entries.assign(2, 0);
  r = run_cycle_model(words({span(0, 0, 10, true), m, t, span(1, 0, 1, true)}), Stimulus{}, two);
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[1].cycle, 22u);
  // With a slot of latency 3 the first case's pixel still follows span 0's without a bubble.
  CycleConfig slow(SlotTiming{3, 1});
  slow.material_buffers = 2;
  r = run_cycle_model(words({span(0, 0, 10, true), m, span(1, 0, 1, true)}), Stimulus{}, slow);
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[1].cycle, r.scanlines[0].cycle + 1);
  CycleConfig three;
  three.material_buffers = 3;
  EXPECT_THROW(CycleModel{three}, std::invalid_argument);
}

// A per-material TABLE (a per-exponent reload) writes the bank of the latest MATERIAL: with two
// buffers it waits only for that bank's spans, not for the empty datapath.
TEST(CycleModel, PerMaterialTableLoadsTheNewBankWithoutADrain) {
  const MaterialCmd m = small_material();
  TableCmd t;
  t.base = 0;
  t.entries.assign(2, 0);
  t.per_material = true;
  CycleConfig one, two;
  two.material_buffers = 2;
  // Two buffers: SPAN 0 (bank 0) on 0, pixels leave on 5..14. MATERIAL (to bank 1) on 1,
  // payload 2..4; the TABLE header on 5 (no span of bank 1 in flight), words 6, 7; SPAN 1 on 8,
  // its pixel right behind span 0's, on 15.
  CycleRun r =
      run_cycle_model(words({span(0, 0, 10, true), m, t, span(1, 0, 1, true)}), Stimulus{}, two);
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[1].cycle, 15u);
  // One buffer: MATERIAL waits for the empty datapath (accepted on 14, payload 15..17), the
  // TABLE header goes on 18, words 19, 20; SPAN 1 on 21, its pixel on 26.
  r = run_cycle_model(words({span(0, 0, 10, true), m, t, span(1, 0, 1, true)}), Stimulus{}, one);
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[1].cycle, 26u);
  // Two buffers, a span of bank 1 already in flight: SPAN 1 on 5, its pixel on 15 (it leaves
  // the slot on the edge of 14); the TABLE header waits 6..14, goes on 15, words 16, 17; SPAN 2
  // on 18, its pixel on 23.
  r = run_cycle_model(words({span(0, 0, 10, true), m, span(1, 0, 1, true), t, span(2, 0, 1, true)}),
                      Stimulus{}, two);
  ASSERT_EQ(r.scanlines.size(), 3u);
  EXPECT_EQ(r.scanlines[1].cycle, 15u);
  EXPECT_EQ(r.scanlines[2].cycle, 23u);
}

TEST(CycleModel, TrianglePayloadTakesOneCyclePerWord) {
  TriangleCmd t;
  t.coef.assign(12, 0);
  const CycleRun r = run_cycle_model(words({t, span(0, 0, 6, true)}), Stimulus{});
  ASSERT_EQ(r.scanlines.size(), 1u);
  EXPECT_EQ(r.scanlines[0].cycle, 13u + 6u + 4u);
}

TEST(CycleModel, IdleGapsDelayAcceptance) {
  Stimulus s;
  s.gap_pct = 100;
  s.max_gap = 1;  // exactly one idle cycle before every word
  const CycleRun r = run_cycle_model(words({span(0, 0, 1, true), span(1, 0, 1, true)}), s);
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
  const CycleRun r = run_cycle_model(
      words({span(0, 0, 5, false), span(0, 9, 3, true), span(1, 0, 1, true), EndFrameCmd{}}), s);
  EXPECT_EQ(r.pixels, 9u);
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[0].y, 0);
  EXPECT_EQ(r.scanlines[1].y, 1);
  EXPECT_LT(r.scanlines[0].cycle, r.scanlines[1].cycle);
  EXPECT_GE(r.cycles, 9u + 5u);
}

// ---- specular slot timing ---------------------------------------------------------------

TEST(CycleModel, PipelinedSlotAddsItsLatencyToEveryPixel) {
  for (int lat : {1, 3, 6}) {
    for (int len : {1, 4}) {
      const CycleRun r = run_cycle_model(words({span(0, 0, len, true), span(1, 0, 3, true)}),
                                         Stimulus{}, SlotTiming{lat, 1});
      ASSERT_EQ(r.scanlines.size(), 2u);
      EXPECT_EQ(r.scanlines[0].cycle, static_cast<uint64_t>(len + 4 + lat)) << lat << "," << len;
      EXPECT_EQ(r.scanlines[1].cycle, static_cast<uint64_t>(len + 3 + 4 + lat))
          << lat << "," << len;
    }
  }
}

TEST(CycleModel, IterativeSlotTakesItsIntervalPerPixel) {
  for (int q : {2, 5, 16}) {
    for (int a : {1, 3}) {
      const int b = 2;
      const CycleRun r = run_cycle_model(words({span(0, 0, a, true), span(1, 0, b, true)}),
                                         Stimulus{}, SlotTiming{q, q});
      ASSERT_EQ(r.scanlines.size(), 2u);
      EXPECT_EQ(r.scanlines[0].cycle, static_cast<uint64_t>(5 + q * a)) << q << "," << a;
      EXPECT_EQ(r.scanlines[1].cycle, static_cast<uint64_t>(5 + q * (a + b))) << q << "," << a;
    }
  }
}

TEST(CycleModel, MaterialDrainIncludesTheSlot) {
  const MaterialCmd m = small_material();
  for (int lat : {0, 2, 7}) {
    const CycleRun r = run_cycle_model(words({span(0, 0, 10, true), m, span(1, 0, 1, true)}),
                                       Stimulus{}, SlotTiming{lat, 1});
    ASSERT_EQ(r.scanlines.size(), 2u);
    // Last pixel leaves on 14 + lat; MATERIAL accepted then, payload 3 words, SPAN 4 cycles
    // after it, its pixel 5 + lat cycles later.
    EXPECT_EQ(r.scanlines[0].cycle, static_cast<uint64_t>(14 + lat)) << lat;
    EXPECT_EQ(r.scanlines[1].cycle, static_cast<uint64_t>(14 + lat + 4 + 5 + lat)) << lat;
  }
}

// The units' timing as the README's RTL timing table gives it for the slot.
TEST(CycleModel, SlotTimingPerUnit) {
  SpecularConfig c;
  EXPECT_EQ(SlotTiming::of(c).latency, 0);
  EXPECT_EQ(SlotTiming::of(c).interval, 1);
  c.kind = SpecularUnitKind::kLut;
  c.lut.interp_bits = 0;
  EXPECT_EQ(SlotTiming::of(c).latency, 2);
  EXPECT_EQ(SlotTiming::of(c).interval, 1);
  c.lut.interp_bits = 4;
  EXPECT_EQ(SlotTiming::of(c).latency, 3);
  c.kind = SpecularUnitKind::kSchlick;
  c.schlick.quotient_bits = 12;
  c.schlick.timing = UnitTiming::kIterative;
  EXPECT_EQ(SlotTiming::of(c).latency, 12);
  EXPECT_EQ(SlotTiming::of(c).interval, 12);
  c.schlick.timing = UnitTiming::kPipelined;
  EXPECT_EQ(SlotTiming::of(c).latency, 12);
  EXPECT_EQ(SlotTiming::of(c).interval, 1);
  c.kind = SpecularUnitKind::kWpow;
  c.wpow.max_m = 16;
  c.wpow.timing = UnitTiming::kPipelined;
  EXPECT_EQ(SlotTiming::of(c).latency, 5);
  EXPECT_EQ(SlotTiming::of(c).interval, 1);
  c.wpow.timing = UnitTiming::kIterative;
  c.wpow.max_m = 8;
  EXPECT_EQ(SlotTiming::of(c).latency, 4);
  EXPECT_EQ(SlotTiming::of(c).interval, 4);
}

TEST(CycleModel, RejectsImpossibleSlotTimings) {
  EXPECT_THROW(CycleModel(SlotTiming{-1, 1}), std::invalid_argument);
  EXPECT_THROW(CycleModel(SlotTiming{0, 0}), std::invalid_argument);
  EXPECT_THROW(CycleModel(SlotTiming{3, 4}), std::invalid_argument);
}

// ---- command port width (model/command_stream.h: how a beat is taken apart) -------------------
// Expected cycles are counted by hand from the documented item rule, not from the model.

CycleConfig port(int words) { return CycleConfig(SlotTiming{}, words); }

TEST(CommandPort, TriangleHeaderTakesTheCoefficientsInItsBeat) {
  // P = 4: [TRI c0 c1 c2 | c3 c4 c5 SPAN]: cycle 0 header + 3 words, cycle 1 three words,
  // cycle 2 the SPAN (accepted on t = 2, so the span of 6 ends on 2 + 4 + 6).
  TriangleCmd t;
  t.coef.assign(6, 0);
  const CycleRun r = run_cycle_model(words({t, span(0, 0, 6, true)}), Stimulus{}, port(4));
  ASSERT_EQ(r.scanlines.size(), 1u);
  EXPECT_EQ(r.scanlines[0].cycle, 12u);
  EXPECT_EQ(r.beats, 2u);
}

TEST(CommandPort, ANextHeaderGoesWithTheTail) {
  // P = 4, two 6-word triangles then a 3-pixel span: [T1 a b c | d e f T2 | g h i j | k l S 0].
  // Cycle 0: T1 + a b c; 1: d e f + T2; 2: g h i j; 3: k l (the SPAN may not go with its
  // triangle's tail without a span queue); 4: the SPAN; 5: the padding. The span ends on
  // 4 + 4 + 3. With tri_queue 2 the SPAN goes on 3 into the queue: 3 + 5 + 3.
  TriangleCmd t;
  t.coef.assign(6, 0);
  const std::vector<uint64_t> w = words({t, t, span(0, 0, 3, true)});
  const CycleRun r = run_cycle_model(w, Stimulus{}, port(4));
  ASSERT_EQ(r.scanlines.size(), 1u);
  EXPECT_EQ(r.scanlines[0].cycle, 11u);
  const CycleRun q = run_cycle_model(w, Stimulus{}, CycleConfig(SlotTiming{}, 4, 2));
  ASSERT_EQ(q.scanlines.size(), 1u);
  EXPECT_EQ(q.scanlines[0].cycle, 11u);
}

TEST(CommandPort, TwoWordPortTakesTwoCoefficientsPerCycle) {
  // P = 2: [TRI c0 | c1 c2 | ... | c9 c10 | c11 SPAN]: cycles 0..5 take the header and c0..c10,
  // cycle 6 c11, cycle 7 the SPAN.
  TriangleCmd t;
  t.coef.assign(12, 0);
  const CycleRun r = run_cycle_model(words({t, span(0, 0, 3, true)}), Stimulus{}, port(2));
  ASSERT_EQ(r.scanlines.size(), 1u);
  EXPECT_EQ(r.scanlines[0].cycle, 7u + 4u + 3u);
}

TEST(CommandPort, OneSpanPerCycleAndPaddingInOneCycle) {
  // P = 8: five one-pixel spans then three padding words: spans accepted on cycles 0..4, the
  // NOP on 5 (the beat then), span k ends on k + 5.
  std::vector<Command> cmds;
  cmds.reserve(5);
  for (int y = 0; y < 5; ++y) cmds.push_back(span(y, 0, 1, true));
  const CycleRun r = run_cycle_model(words(cmds), Stimulus{}, port(8));
  ASSERT_EQ(r.scanlines.size(), 5u);
  for (int y = 0; y < 5; ++y)
    EXPECT_EQ(r.scanlines[static_cast<size_t>(y)].cycle, static_cast<uint64_t>(y + 5));
  EXPECT_EQ(r.beats, 1u);
  EXPECT_EQ(r.cycles, 10u);
}

TEST(CommandPort, ASpanQueueTakesARunOfSpansInOneCycle) {
  // P = 8, five one-pixel spans and three padding words. Without a span queue the spans go one
  // per cycle (0..4) and the padding on 5, so the beat is accepted on cycle 5. With tri_queue 2
  // (8 queue entries) all five go on cycle 0 and the padding on 1.
  std::vector<Command> cmds;
  cmds.reserve(5);
  for (int y = 0; y < 5; ++y) cmds.push_back(span(y, 0, 1, true));
  std::vector<uint64_t> beat = words(cmds);
  beat.resize(8, 0);
  for (const auto& [queue, accepted_on] : {std::pair{1, 5}, std::pair{2, 1}}) {
    CycleModel m(CycleConfig(SlotTiming{}, 8, queue));
    int fired = -1;
    for (int c = 0; c < 10 && fired < 0; ++c) {
      if (m.clock(true, beat.data(), true).cmd_fire) fired = c;
    }
    EXPECT_EQ(fired, accepted_on) << "tri_queue " << queue;
  }
  // A run longer than the queue's room: 8 spans of 100 pixels, P = 8, tri_queue 2. Cycle 0 takes
  // all 8 (the queue is empty: 8 entries of room); nothing pops before the edge.
  std::vector<Command> long_spans;
  long_spans.reserve(8);
  for (int y = 0; y < 8; ++y) long_spans.push_back(span(y, 0, 100, true));
  const std::vector<uint64_t> full = words(long_spans);
  CycleModel m(CycleConfig(SlotTiming{}, 8, 2));
  EXPECT_TRUE(m.clock(true, full.data(), true).cmd_fire);
}

TEST(CommandPort, MaterialPayloadIsOneWordPerCycle) {
  // P = 4: [MAT a s e | SPAN]: the header on 0, its three words on 1..3, the SPAN on 4.
  const MaterialCmd m = small_material();
  const CycleRun r = run_cycle_model(words({m, span(0, 0, 2, true)}), Stimulus{}, port(4));
  ASSERT_EQ(r.scanlines.size(), 1u);
  EXPECT_EQ(r.scanlines[0].cycle, 4u + 4u + 2u);
}

TEST(CommandPort, GapsComeBeforeBeats) {
  // One idle cycle before every beat: P = 2, [SPAN SPAN | SPAN pad]: beat 0 offered on cycle 1
  // (spans on 1, 2), beat 1 on 4 (SPAN on 4, padding on 5).
  Stimulus s;
  s.gap_pct = 100;
  s.max_gap = 1;
  const CycleRun r = run_cycle_model(
      words({span(0, 0, 1, true), span(1, 0, 1, true), span(2, 0, 1, true)}), s, port(2));
  ASSERT_EQ(r.scanlines.size(), 3u);
  EXPECT_EQ(r.scanlines[0].cycle, 1u + 5u);
  EXPECT_EQ(r.scanlines[1].cycle, 2u + 5u);
  EXPECT_EQ(r.scanlines[2].cycle, 4u + 5u);
}

// ---- triangle queue ------------------------------------------------------------------------

TEST(TriangleQueue, SpanQueueAddsOneRegister) {
  // tri_queue 2: a SPAN accepted on t enters setup stage 1 from the queue on t + 1, so a span
  // of len ends on t + 5 + len (one more than without a queue).
  for (int len : {1, 5}) {
    const CycleRun r = run_cycle_model(words({span(0, 0, len, true)}), Stimulus{},
                                       CycleConfig(SlotTiming{}, 1, 2));
    ASSERT_EQ(r.scanlines.size(), 1u);
    EXPECT_EQ(r.scanlines[0].cycle, static_cast<uint64_t>(5 + len)) << len;
  }
}

TEST(TriangleQueue, PortRunsAheadOfTheEngines) {
  // A 40-pixel span, then ten one-pixel spans, then END_FRAME. Without a queue, four spans fit
  // past the decoder (three setup stages and the engines), so the fifth header waits for the
  // 40 pixels; with tri_queue 2 the span queue (8 entries) takes the other seven, and END_FRAME
  // goes on cycle 11, one word per cycle.
  std::vector<Command> cmds = {span(0, 0, 40, true)};
  for (int y = 1; y <= 10; ++y) cmds.push_back(span(y, 0, 1, true));
  cmds.push_back(EndFrameCmd{});
  const std::vector<uint64_t> w = words(cmds);
  for (int queue : {1, 2}) {
    CycleModel m(CycleConfig(SlotTiming{}, 1, queue));
    CommandDriver d(w, Stimulus{});
    uint64_t end_frame_taken = 0;
    for (uint64_t c = 0; c < 200 && !d.done(); ++c) {
      const auto e = m.clock(d.valid(), d.word(), true);
      if (e.cmd_fire && d.index() == w.size() - 1) end_frame_taken = c;
      d.clock(e.cmd_fire);
    }
    if (queue == 1) {
      EXPECT_GT(end_frame_taken, 40u);  // behind the 40-pixel span
    } else {
      EXPECT_EQ(end_frame_taken, 11u);
    }
  }
}

TEST(TriangleQueue, RejectsOtherDepths) {
  for (int q : {0, 9})
    EXPECT_THROW(CycleModel(CycleConfig(SlotTiming{}, 1, q)), std::invalid_argument) << q;
}

TEST(CommandPort, RejectsOtherWidths) {
  for (int w : {0, 3, 5, 16}) EXPECT_THROW(CycleModel(port(w)), std::invalid_argument) << w;
}

// ---- cycle breakdown -------------------------------------------------------------------------

TEST(CycleBreakdown, SingleSpanIsFillThenPixels) {
  for (int lat : {0, 3}) {
    const int len = 9;
    const CycleRun r =
        run_cycle_model(words({span(0, 0, len, true)}), Stimulus{}, SlotTiming{lat, 1});
    const CycleBreakdown& b = r.breakdown;
    EXPECT_EQ(b.pixel, static_cast<uint64_t>(len));
    EXPECT_EQ(b.setup_load, static_cast<uint64_t>(5 + lat));
    EXPECT_EQ(b.total(), r.cycles);
    EXPECT_EQ(
        b.back_pressure + b.unit_stall + b.command_gap + b.material + b.table + b.command_words,
        0u);
  }
}

TEST(CycleBreakdown, MaterialSwitchCostsItsWordsAndARefill) {
  const MaterialCmd m = small_material();
  const CycleRun r =
      run_cycle_model(words({span(0, 0, 10, true), m, span(1, 0, 1, true)}), Stimulus{});
  const CycleBreakdown& b = r.breakdown;
  EXPECT_EQ(r.cycles, 24u);
  EXPECT_EQ(b.pixel, 11u);
  EXPECT_EQ(b.setup_load, 5u);  // the first span's fill
  // The header is accepted with the last pixel; then 3 payload words, the SPAN header and
  // 4 more cycles of its latency pass without a pixel.
  EXPECT_EQ(b.material, 3u + 5u);
  EXPECT_EQ(b.total(), r.cycles);
}

TEST(CycleBreakdown, GapsBeforeEveryWordAreChargedToTheInput) {
  Stimulus s;
  s.gap_pct = 100;
  s.max_gap = 1;  // one idle cycle before every word: one span per 2 cycles
  const int n = 20;
  std::vector<Command> cmds;
  cmds.reserve(n);
  for (int i = 0; i < n; ++i) cmds.push_back(span(i, 0, 1, true));
  const CycleRun r = run_cycle_model(words(cmds), s);
  const CycleBreakdown& b = r.breakdown;
  // SPAN i accepted on 2i + 1, its pixel leaves on 2i + 6.
  EXPECT_EQ(r.cycles, static_cast<uint64_t>(2 * n + 5));
  EXPECT_EQ(b.pixel, static_cast<uint64_t>(n));
  EXPECT_EQ(b.setup_load, 5u);
  EXPECT_EQ(b.command_gap, static_cast<uint64_t>(n));  // cycle 5 and every cycle between pixels
  EXPECT_EQ(b.total(), r.cycles);
}

TEST(CycleBreakdown, SmallTrianglesAreCommandBound) {
  const int k = 30;
  std::vector<Command> cmds;
  for (int i = 0; i < k; ++i) {
    TriangleCmd t;
    t.coef.assign(12, 0);  // grey, 1 light: 2 series x 6 coefficients
    cmds.push_back(t);
    cmds.push_back(span(i, 0, 2, true));
  }
  const CycleRun r = run_cycle_model(words(cmds), Stimulus{});
  const CycleBreakdown& b = r.breakdown;
  // 14 words per triangle at one per clock; its 2 pixels leave 5 and 6 cycles after its SPAN.
  EXPECT_EQ(r.cycles, static_cast<uint64_t>(14 * (k - 1) + 20));
  EXPECT_EQ(b.pixel, static_cast<uint64_t>(2 * k));
  EXPECT_EQ(b.setup_load, 5u);
  EXPECT_EQ(b.command_words, static_cast<uint64_t>(13 + 12 * (k - 1)));
  EXPECT_EQ(b.total(), r.cycles);
}

TEST(CycleBreakdown, TableWaitsForTheDatapathAndIsCharged) {
  TableCmd t;
  t.base = 0;
  t.entries.assign(20, 0);
  const CycleRun r =
      run_cycle_model(words({span(0, 0, 2, true), t, span(1, 0, 2, true)}), Stimulus{});
  const CycleBreakdown& b = r.breakdown;
  // SPAN 0 on 0 (pixels 5, 6; engines empty from 6); the TABLE header waits 1..5, is accepted
  // on 6, its 20 words take 7..26; SPAN 1 on 27 (pixels 32, 33).
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[1].cycle, 33u);
  EXPECT_EQ(r.cycles, 34u);
  EXPECT_EQ(b.pixel, 4u);
  EXPECT_EQ(b.setup_load, 5u);
  EXPECT_EQ(b.table, 34u - 4u - 5u);  // 7..31 look back to 2..26: TABLE waiting or its words
  EXPECT_EQ(b.total(), r.cycles);
}

TEST(CycleBreakdown, BackPressureCountsCyclesAPixelWaited) {
  // Ready on every third cycle (see PixelsLeaveOnlyWhenReady): pixels leave on 6, 9, 12, 15
  // and one waits on 5, 7, 8, 10, 11, 13, 14.
  const auto w = words({span(0, 0, 4, true)});
  CycleModel m;
  CommandDriver d(w, Stimulus{});
  int pixel = 0, bp = 0, fill = 0, other = 0;
  for (uint64_t c = 0; c < 16; ++c) {
    const auto e = m.clock(d.valid(), d.word(), c % 3 == 0);
    d.clock(e.cmd_fire);
    switch (e.category) {
      case CycleModel::Category::kPixel:
        ++pixel;
        break;
      case CycleModel::Category::kBackPressure:
        ++bp;
        break;
      case CycleModel::Category::kSetupLoad:
        ++fill;
        break;
      default:
        ++other;
        break;
    }
  }
  EXPECT_TRUE(m.idle());
  EXPECT_EQ(pixel, 4);
  EXPECT_EQ(bp, 7);
  EXPECT_EQ(fill, 5);
  EXPECT_EQ(other, 0);
}

TEST(CycleBreakdown, IterativeUnitStallsAreItsIntervalAndLatency) {
  for (int q : {2, 8}) {
    const int n = 6;
    const CycleRun r = run_cycle_model(words({span(0, 0, n, true)}), Stimulus{}, SlotTiming{q, q});
    const CycleBreakdown& b = r.breakdown;
    EXPECT_EQ(r.cycles, static_cast<uint64_t>(6 + q * n));
    EXPECT_EQ(b.pixel, static_cast<uint64_t>(n));
    EXPECT_EQ(b.setup_load, 5u);
    EXPECT_EQ(b.unit_stall, static_cast<uint64_t>(q + (n - 1) * (q - 1)));
    EXPECT_EQ(b.total(), r.cycles);
  }
}

// On random streams and stimuli the categories still partition the run and the pixel count.
TEST(CycleBreakdown, PartitionsRandomRuns) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<Command> cmds;
    int y = 0;
    for (int i = 0; i < 60; ++i) {
      const int kind = static_cast<int>(rng() % 6);
      if (kind == 0) {
        const MaterialCmd m = small_material();
        cmds.push_back(m);
      } else if (kind == 1) {
        TableCmd t;
        t.entries.assign(1 + rng() % 9, 0);
        cmds.push_back(t);
      } else if (kind == 2) {
        TriangleCmd t;
        t.coef.assign(12, 0);
        cmds.push_back(t);
      } else {
        const bool last = rng() % 2 == 0;
        cmds.push_back(span(y, 0, 1 + static_cast<int>(rng() % 12), last));
        if (last) ++y;
      }
    }
    Stimulus s;
    s.seed = static_cast<uint64_t>(trial);
    s.gap_pct = static_cast<int>(rng() % 60);
    s.max_gap = 1 + static_cast<int>(rng() % 8);
    s.stall_pct = static_cast<int>(rng() % 60);
    const int q = static_cast<int>(rng() % 4);
    const SlotTiming timing =
        q >= 2 ? SlotTiming{q, q} : SlotTiming{static_cast<int>(rng() % 5), 1};
    const int port_words = 1 << (rng() % 4);
    const int tri_queue = 1 + static_cast<int>(rng() % 3);
    const CycleRun r = run_cycle_model(words(cmds), s, CycleConfig(timing, port_words, tri_queue));
    EXPECT_EQ(r.breakdown.total(), r.cycles) << "trial " << trial;
    EXPECT_EQ(r.breakdown.pixel, r.pixels) << "trial " << trial;
    if (timing.interval == 1) {
      EXPECT_EQ(r.breakdown.unit_stall, 0u) << "trial " << trial;
    }
    if (s.stall_pct == 0) {
      EXPECT_EQ(r.breakdown.back_pressure, 0u) << "trial " << trial;
    }
    if (s.gap_pct == 0) {
      EXPECT_EQ(r.breakdown.command_gap, 0u) << "trial " << trial;
    }
  }
}

// ---- pixel lanes -------------------------------------------------------------------------------
// A span of len pixels leaves in ceil(len / K) beats of up to K pixels, one beat per cycle: a
// SPAN header accepted on t has beat b leave on t + 5 + b (lane 0's pixel k of a one-lane unit
// is its beat k). Counted by hand from that rule.

CycleConfig lanes(int k, SlotTiming slot = SlotTiming{}) { return CycleConfig(slot, 1, 1, k); }

TEST(PixelLanes, OneSpanOfFiveInFourLanesIsTwoBeats) {
  // Beats [0 1 2 3] on cycle 5 and [4] on cycle 6; the run ends after cycle 6.
  const CycleRun r = run_cycle_model(words({span(3, 10, 5, true)}), Stimulus{}, lanes(4));
  ASSERT_EQ(r.scanlines.size(), 1u);
  EXPECT_EQ(r.scanlines[0].y, 3);
  EXPECT_EQ(r.scanlines[0].cycle, 6u);
  EXPECT_EQ(r.scanlines[0].x, 14);  // the end-of-row pixel: lane 0 of the second beat
  EXPECT_EQ(r.pixels, 5u);
  EXPECT_EQ(r.breakdown.pixel, 2u);  // beats
  EXPECT_EQ(r.breakdown.setup_load, 5u);
  EXPECT_EQ(r.cycles, 7u);
  EXPECT_EQ(r.breakdown.total(), r.cycles);
}

TEST(PixelLanes, SpanEndsAfterCeilLenOverLanesBeats) {
  for (int k : {1, 2, 4}) {
    for (int len : {1, 2, 3, 4, 5, 7, 8, 9, 2048}) {
      const int beats = (len + k - 1) / k;
      const CycleRun r = run_cycle_model(words({span(0, 0, len, true)}), Stimulus{}, lanes(k));
      ASSERT_EQ(r.scanlines.size(), 1u);
      EXPECT_EQ(r.scanlines[0].cycle, static_cast<uint64_t>(4 + beats)) << k << "," << len;
      EXPECT_EQ(r.scanlines[0].x, len - 1) << k << "," << len;
      EXPECT_EQ(r.pixels, static_cast<uint64_t>(len));
      EXPECT_EQ(r.breakdown.pixel, static_cast<uint64_t>(beats));
      EXPECT_EQ(r.cycles, static_cast<uint64_t>(5 + beats));
    }
  }
}

TEST(PixelLanes, BackToBackSpansLeaveNoBubbleAndNeverShareABeat) {
  // Spans of 3 and 6 in 2 lanes: beats 2 + 3; the second span's last beat leaves on 4 + 5.
  // In 4 lanes: 1 + 2 beats (a span's tail beat is not filled from the next span).
  const std::vector<uint64_t> w = words({span(0, 0, 3, true), span(1, 0, 6, true)});
  const CycleRun two = run_cycle_model(w, Stimulus{}, lanes(2));
  ASSERT_EQ(two.scanlines.size(), 2u);
  EXPECT_EQ(two.scanlines[0].cycle, 6u);
  EXPECT_EQ(two.scanlines[1].cycle, 9u);
  const CycleRun four = run_cycle_model(w, Stimulus{}, lanes(4));
  ASSERT_EQ(four.scanlines.size(), 2u);
  EXPECT_EQ(four.scanlines[0].cycle, 5u);
  EXPECT_EQ(four.scanlines[1].cycle, 7u);
  EXPECT_EQ(four.breakdown.pixel, 3u);
}

TEST(PixelLanes, SlotTimingIsPerBeat) {
  // Pipelined latency 3: every beat 3 later. Iterative Q: beat b leaves on t + 5 + Q (b + 1),
  // all lanes' units in lockstep.
  const std::vector<uint64_t> w = words({span(0, 0, 7, true)});  // 2 beats in 4 lanes
  const CycleRun pipe = run_cycle_model(w, Stimulus{}, lanes(4, SlotTiming{3, 1}));
  ASSERT_EQ(pipe.scanlines.size(), 1u);
  EXPECT_EQ(pipe.scanlines[0].cycle, 4u + 2u + 3u);
  for (int q : {2, 5}) {
    const CycleRun it = run_cycle_model(w, Stimulus{}, lanes(4, SlotTiming{q, q}));
    ASSERT_EQ(it.scanlines.size(), 1u);
    EXPECT_EQ(it.scanlines[0].cycle, static_cast<uint64_t>(5 + q * 2)) << q;
    EXPECT_EQ(it.breakdown.unit_stall, static_cast<uint64_t>(q + (q - 1))) << q;
    EXPECT_EQ(it.breakdown.total(), it.cycles);
  }
}

TEST(PixelLanes, BeatsLeaveOnlyWhenReady) {
  // 8 pixels in 4 lanes, ready on every third cycle: beat 0 valid from 5, leaves on 6; beat 1
  // loaded on 6, leaves on 9.
  const auto w = words({span(0, 0, 8, true)});
  CycleModel m(lanes(4));
  CommandDriver d(w, Stimulus{});
  std::vector<uint64_t> left;
  std::vector<int> counts;
  for (uint64_t c = 0; c < 30; ++c) {
    const auto e = m.clock(d.valid(), d.word(), c % 3 == 0);
    d.clock(e.cmd_fire);
    if (e.pix_fire) {
      left.push_back(c);
      counts.push_back(e.pix_count);
      EXPECT_EQ(e.pix_x, 4 * static_cast<int>(left.size() - 1));
      EXPECT_EQ(e.pix_eor, left.size() == 2);
    }
  }
  EXPECT_EQ(left, (std::vector<uint64_t>{6, 9}));
  EXPECT_EQ(counts, (std::vector<int>{4, 4}));
  EXPECT_TRUE(m.idle());
}

TEST(PixelLanes, RejectsOtherLaneCounts) {
  for (int k : {0, 3, 8}) EXPECT_THROW(CycleModel(lanes(k)), std::invalid_argument) << k;
}

// On random streams and stimuli the rows still sum to the cycles, the pixel row counts beats,
// and the pixels are the spans' pixels.
TEST(PixelLanes, BreakdownPartitionsRandomRuns) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 40; ++trial) {
    const int k = 1 << (rng() % 3);
    std::vector<Command> cmds;
    uint64_t pixels = 0, beats = 0;
    int y = 0;
    for (int i = 0; i < 50; ++i) {
      if (rng() % 4 == 0) {
        TriangleCmd t;
        t.coef.assign(12, 0);
        cmds.push_back(t);
      } else {
        const bool last = rng() % 2 == 0;
        const int len = 1 + static_cast<int>(rng() % 13);
        cmds.push_back(span(y, 0, len, last));
        pixels += static_cast<uint64_t>(len);
        beats += static_cast<uint64_t>((len + k - 1) / k);
        if (last) ++y;
      }
    }
    Stimulus s;
    s.seed = static_cast<uint64_t>(trial);
    s.gap_pct = static_cast<int>(rng() % 50);
    s.max_gap = 1 + static_cast<int>(rng() % 6);
    s.stall_pct = static_cast<int>(rng() % 50);
    const int q = static_cast<int>(rng() % 4);
    const SlotTiming timing =
        q >= 2 ? SlotTiming{q, q} : SlotTiming{static_cast<int>(rng() % 5), 1};
    const CycleRun r = run_cycle_model(
        words(cmds), s, CycleConfig(timing, 1 << (rng() % 4), 1 + static_cast<int>(rng() % 3), k));
    EXPECT_EQ(r.breakdown.total(), r.cycles) << "trial " << trial;
    EXPECT_EQ(r.breakdown.pixel, beats) << "trial " << trial;
    EXPECT_EQ(r.pixels, pixels) << "trial " << trial;
    EXPECT_EQ(r.scanlines.size(), static_cast<size_t>(y)) << "trial " << trial;
  }
}

}  // namespace
}  // namespace shadesim
