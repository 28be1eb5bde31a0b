// CycleEstimate (closed form) against run_cycle_model (the clocked CycleModel, the spec) with no
// gaps and no back-pressure: cycles, pixels, words, beats and every scanline's completion cycle
// equal, on every shipped and hard scene (each on its own configuration, then on a grid of port
// widths, queue depths and slot timings) and on random streams with MATERIAL and TABLE commands.
#include "model/cycle_estimate.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "derive/derive_config.h"
#include "host/frame.h"
#include "model/cycle_model.h"
#include "sim/harness/cycle_run.h"
#include "sim/harness/random_stream.h"

namespace shadesim {
namespace {

// Pipelined slots of latency 0, 2 and 5; iterative units of 2, 5 and 17 cycles per pixel.
const std::vector<SlotTiming> kSlots = {{0, 1}, {2, 1}, {5, 1}, {2, 2}, {5, 5}, {17, 17}};

std::string describe(const CycleConfig& u) {
  return "port_words " + std::to_string(u.port_words) + ", tri_queue " +
         std::to_string(u.tri_queue) + ", lanes " + std::to_string(u.lanes) +
         ", material_buffers " + std::to_string(u.material_buffers) + ", slot latency " +
         std::to_string(u.slot.latency) + " interval " + std::to_string(u.slot.interval) +
         ", combine_stages " + std::to_string(u.combine_stages);
}

// The unit with this many combine stages (UnitConfig::combine_stages).
CycleConfig combined(CycleConfig u, int stages) {
  u.combine_stages = stages;
  return u;
}

// The unit with this many material buffers.
CycleConfig buffered(CycleConfig u, int material_buffers) {
  u.material_buffers = material_buffers;
  return u;
}

// Every figure the two share; returns the number of scanlines compared.
size_t expect_same(const std::vector<uint64_t>& words, const CycleConfig& unit,
                   const std::string& what) {
  const CycleRun clocked = run_cycle_model(words, Stimulus{}, unit);
  const CycleEstimateRun fast = CycleEstimate(unit).run(words, true);
  const std::string where = what + " on " + describe(unit);
  EXPECT_EQ(fast.cycles, clocked.cycles) << where;
  EXPECT_EQ(fast.pixels, clocked.pixels) << where;
  EXPECT_EQ(fast.words, clocked.words) << where;
  EXPECT_EQ(fast.beats, clocked.beats) << where;
  EXPECT_EQ(fast.scanlines.size(), clocked.scanlines.size()) << where;
  if (fast.breakdown) {
    const auto a = fast.breakdown->rows(), b = clocked.breakdown.rows();
    for (size_t i = 0; i < a.size(); ++i)
      EXPECT_EQ(a[i].cycles, b[i].cycles) << where << ": breakdown " << a[i].name;
  } else {
    ADD_FAILURE() << where << ": no breakdown";
  }
  const size_t n = std::min(fast.scanlines.size(), clocked.scanlines.size());
  for (size_t i = 0; i < n; ++i) {
    const ScanlineDone& a = fast.scanlines[i];
    const ScanlineDone& b = clocked.scanlines[i];
    if (a.y != b.y || a.cycle != b.cycle || a.x != b.x) {
      ADD_FAILURE() << where << ": scanline #" << i << " estimate y " << a.y << " x " << a.x
                    << " cycle " << a.cycle << ", clocked y " << b.y << " x " << b.x << " cycle "
                    << b.cycle;
      break;
    }
  }
  return n;
}

std::vector<std::string> scenes() {
  std::vector<std::string> paths;
  for (const char* dir : {"/scenes", "/scenes/hard"}) {
    for (const auto& e :
         std::filesystem::directory_iterator(std::string(SHADESIM_SOURCE_DIR) + dir)) {
      if (e.path().extension() == ".json") paths.push_back(e.path().string());
    }
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

class SceneStreams : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneStreams, EqualsClockedModelOnOwnConfigAndKnobGrid) {
  const std::string scene = GetParam();
  FrameOptions o;
  // Unit span setup: the grid below varies the unit-setup structure (a host-setup stream, with
  // its start values after each SPAN, is another stream; tests/host_setup_test.cpp has its grid).
  DeriveOptions unit_setup;
  unit_setup.span_setup = SpanSetupSite::kUnit;
  o.base = derive_config({scene}, unit_setup).config;
  o.fixed_unit = true;
  const PreparedFrame f = prepare_frame(scene, o);
  const std::vector<uint64_t> words = f.encoded.stream.encode();
  ASSERT_GT(f.encoded.stats.spans, 0u) << scene;
  // The same unit with host span setup, on its own stream.
  o.base.span_setup = SpanSetupSite::kHost;
  o.base.tri_queue = 1;
  const PreparedFrame h = prepare_frame(scene, o);
  for (int mb : {1, 2}) {
    for (int stages : {0, 1, 2}) {
      EXPECT_GT(expect_same(h.encoded.stream.encode(),
                            combined(buffered(CycleConfig::of(h.config), mb), stages),
                            scene + " (host span setup)"),
                0u);
    }
  }

  // Its own configuration as derived (port 4, queue 2, its specular unit's timing).
  for (int mb : {1, 2}) {
    EXPECT_GT(
        expect_same(words, buffered(CycleConfig::of(f.config), mb), scene + " (own configuration)"),
        0u);
    for (int port : {1, 2, 4, 8}) {
      for (int queue : {1, 2, 3}) {
        for (const SlotTiming& slot : kSlots)
          expect_same(words, buffered(CycleConfig(slot, port, queue), mb), scene);
      }
    }
    for (int lanes : {2, 4}) {
      for (int port : {1, 4}) {
        for (int queue : {1, 2}) {
          for (const SlotTiming& slot : kSlots)
            expect_same(words, buffered(CycleConfig(slot, port, queue, lanes), mb), scene);
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedAndHard, SceneStreams, ::testing::ValuesIn(scenes()),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                           std::string n = std::filesystem::path(p.param).stem().string();
                           if (p.param.find("/hard/") != std::string::npos) n = "hard_" + n;
                           for (char& ch : n) {
                             if (!isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           }
                           return n;
                         });

// Random streams: every scenario shape (material switches with TABLE loads, 1-pixel spans,
// full rows, ...) on units whose streams carry MATERIAL payloads of their specular unit.
TEST(CycleEstimate, EqualsClockedModelOnRandomStreams) {
  std::vector<UnitConfig> units(3);
  units[1].specular.kind = SpecularUnitKind::kLut;
  units[2].specular.kind = SpecularUnitKind::kSchlick;
  units[2].channels = 3;
  units[2].lights = 2;
  size_t materials = 0, tables = 0;
  uint64_t cycles_one_buffer = 0, cycles_two_buffers = 0;  // "switch" streams, P=4 Q=2
  for (const std::string& name : scenario_names()) {
    const Scenario sc = scenario_by_name(name);
    for (size_t u = 0; u < units.size(); ++u) {
      for (uint64_t seed = 1; seed <= 3; ++seed) {
        const CommandStream s = random_stream(units[u], sc.shape, seed * 7919 + u);
        for (const Command& c : s.commands) {
          materials += std::holds_alternative<MaterialCmd>(c);
          tables += std::holds_alternative<TableCmd>(c);
        }
        const std::vector<uint64_t> words = s.encode();
        const std::string what =
            "random " + name + " seed " + std::to_string(seed) + " unit " + std::to_string(u);
        if (name == "switch") {
          const CycleConfig unit(SlotTiming{2, 1}, 4, 2);
          cycles_one_buffer += CycleEstimate(buffered(unit, 1)).run(words).cycles;
          cycles_two_buffers += CycleEstimate(buffered(unit, 2)).run(words).cycles;
        }
        for (int mb : {1, 2}) {
          for (int port : {1, 2, 4, 8}) {
            for (int queue : {1, 2, 3}) {
              for (const SlotTiming& slot : kSlots)
                expect_same(words, buffered(CycleConfig(slot, port, queue), mb), what);
            }
          }
          for (int lanes : {2, 4}) {
            for (const SlotTiming& slot : kSlots)
              expect_same(words, buffered(CycleConfig(slot, 4, 2, lanes), mb), what);
          }
          // A combine stage, on every slot timing and a one- and a four-word port.
          for (int port : {1, 4}) {
            for (int lanes : {1, 2}) {
              for (const SlotTiming& slot : kSlots)
                expect_same(words, combined(buffered(CycleConfig(slot, port, 2, lanes), mb), 1),
                            what);
            }
          }
        }
      }
    }
  }
  // The streams did exercise the MATERIAL / TABLE drain.
  EXPECT_GT(materials, 50u);
  EXPECT_GT(tables, 10u);
  // Their MATERIALs come while spans are in flight: a second buffer saves cycles, so the banks
  // were exercised.
  EXPECT_LT(cycles_two_buffers, cycles_one_buffer);
}

// Hand-made cases whose figures follow from the recurrences by hand (not from either model).
std::vector<uint64_t> words_of(const std::vector<CommandWord>& ws) {
  std::vector<uint64_t> out;
  out.reserve(ws.size());
  for (const CommandWord& w : ws) out.push_back(w.bits);
  return out;
}

TEST(CycleEstimate, OneSpanTakesSpanLatencyPlusItsPixels) {
  // A SPAN taken on cycle 0 enters s1..s3 on 0..2, loads the engines on 3, emits on 4..4+len-1;
  // each pixel leaves latency + 1 later; the run ends the cycle after the last one.
  for (int latency : {0, 2, 5}) {
    for (int len : {1, 7}) {
      const CycleEstimateRun r = CycleEstimate(SlotTiming{latency, 1})
                                     .run(words_of({CommandWord::span(3, 10, len, true)}));
      ASSERT_EQ(r.scanlines.size(), 1u);
      EXPECT_EQ(r.scanlines[0].cycle, static_cast<uint64_t>(4 + len - 1 + latency + 1));
      EXPECT_EQ(r.scanlines[0].x, 10 + len - 1);
      EXPECT_EQ(r.cycles, r.scanlines[0].cycle + 1);
      // The first pixel leaves span_latency() cycles after its SPAN header (taken on cycle 0).
      EXPECT_EQ(r.scanlines[0].cycle - static_cast<uint64_t>(len - 1),
                static_cast<uint64_t>(CycleModel(SlotTiming{latency, 1}).span_latency()));
    }
  }
}

TEST(CycleEstimate, EachCombineStageDelaysEveryPixelOneCycle) {
  // The same span as above with a combine stage: every pixel waits one more advance between
  // the slot and the pix register, so the scanline ends one cycle later and nothing else moves.
  for (int stages : {1, 2}) {
    for (int latency : {0, 2}) {
      for (int len : {1, 7}) {
        const std::vector<uint64_t> w = words_of({CommandWord::span(3, 10, len, true)});
        CycleConfig piped(SlotTiming{latency, 1});
        piped.combine_stages = stages;
        const CycleEstimateRun r = CycleEstimate(piped).run(w);
        ASSERT_EQ(r.scanlines.size(), 1u);
        EXPECT_EQ(r.scanlines[0].cycle, static_cast<uint64_t>(4 + len - 1 + latency + 1 + stages));
        EXPECT_EQ(r.cycles, r.scanlines[0].cycle + 1);
        EXPECT_EQ(CycleModel(piped).span_latency(),
                  CycleModel(SlotTiming{latency, 1}).span_latency() + stages);
      }
    }
  }
}

TEST(CycleEstimate, IterativeSlotEmitsOnePixelPerInterval) {
  // Interval q: the len pixels are emitted q cycles apart from cycle 4; the last leaves q + 1
  // after its emit.
  const int q = 5, len = 4;
  const CycleEstimateRun r =
      CycleEstimate(SlotTiming{q, q}).run(words_of({CommandWord::span(0, 0, len, true)}));
  ASSERT_EQ(r.scanlines.size(), 1u);
  EXPECT_EQ(r.scanlines[0].cycle, static_cast<uint64_t>(4 + (len - 1) * q + q + 1));
}

TEST(CycleEstimate, MaterialWaitsForTheLastPixel) {
  // SPAN (pixel leaves on 5), MATERIAL header on 5 (datapath empty), its 2 payload words on 6
  // and 7, the next SPAN on 8: its pixel leaves on 13.
  const std::vector<uint64_t> w =
      words_of({CommandWord::span(0, 0, 1, true), CommandWord::material(2), CommandWord{0},
                CommandWord{0}, CommandWord::span(1, 0, 1, true)});
  const CycleEstimateRun r = CycleEstimate(CycleConfig{}).run(w);
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[0].cycle, 5u);
  EXPECT_EQ(r.scanlines[1].cycle, 13u);
}

TEST(CycleEstimate, HeaderGoesWithTheTailOnTheCycleItBecomesReady) {
  // Four-word port. Cycle 0: the SPAN (its pixel leaves on 5, so the datapath is empty from 5).
  // Cycle 1: the TRIANGLE header with 2 of its 15 coefficient words; 2, 3, 4: a beat of them
  // each; 5: the last one, and the MATERIAL behind it in the beat, ready on exactly that cycle;
  // 6: the SPAN after it (its pixel leaves on 11); 7: the padding. The run ends on cycle 12.
  std::vector<CommandWord> ws = {CommandWord::span(0, 0, 1, true), CommandWord::triangle(0, 0, 15)};
  for (int i = 0; i < 15; ++i) ws.push_back(CommandWord{0});
  ws.push_back(CommandWord::material(0));
  ws.push_back(CommandWord::span(1, 0, 1, true));
  const CycleConfig unit(SlotTiming{}, 4, 1);
  const CycleEstimateRun r = CycleEstimate(unit).run(words_of(ws));
  ASSERT_EQ(r.scanlines.size(), 2u);
  EXPECT_EQ(r.scanlines[0].cycle, 5u);
  EXPECT_EQ(r.scanlines[1].cycle, 11u);
  EXPECT_EQ(r.cycles, 12u);
  EXPECT_EQ(r.beats, 5u);
  expect_same(words_of(ws), unit, "material with the tail");
}

TEST(CycleEstimate, ClassifiesTrianglesBySetupAndFill) {
  // One-word port: a triangle of 6 coefficient words and one 2-pixel span takes 8 decoder
  // cycles for 2 engine cycles (setup-bound); one with a 40-pixel span takes 8 for 40.
  std::vector<CommandWord> ws;
  ws.push_back(CommandWord::triangle(0, 0, 6));
  for (int i = 0; i < 6; ++i) ws.push_back(CommandWord{0});
  ws.push_back(CommandWord::span(0, 0, 2, true));
  ws.push_back(CommandWord::triangle(0, 1, 6));
  for (int i = 0; i < 6; ++i) ws.push_back(CommandWord{0});
  ws.push_back(CommandWord::span(1, 0, 40, true));
  const CycleEstimateRun r = CycleEstimate(CycleConfig{}).run(words_of(ws));
  ASSERT_EQ(r.triangles.size(), 2u);
  EXPECT_EQ(r.triangles[0].decoder_cycles, 8u);
  EXPECT_EQ(r.triangles[0].engine_cycles, 2u);
  EXPECT_TRUE(r.triangles[0].setup_bound());
  EXPECT_EQ(r.triangles[1].decoder_cycles, 8u);
  EXPECT_EQ(r.triangles[1].engine_cycles, 40u);
  EXPECT_FALSE(r.triangles[1].setup_bound());
  EXPECT_EQ(r.triangles[1].yo, 1);
  EXPECT_EQ(r.triangles[1].pixels, 40u);
}

TEST(CycleEstimate, RejectsStreamsTheClockedModelCouldNotFinish) {
  EXPECT_THROW(
      CycleEstimate(CycleConfig{}).run(words_of({CommandWord::triangle(0, 0, 6), CommandWord{0}})),
      std::invalid_argument);
  EXPECT_THROW(CycleEstimate(CycleConfig{}).run(words_of({CommandWord::span(0, 0, 0, true)})),
               std::invalid_argument);
  EXPECT_THROW(CycleEstimate(CycleConfig(SlotTiming{}, 3, 1)), std::invalid_argument);
}

}  // namespace
}  // namespace shadesim
