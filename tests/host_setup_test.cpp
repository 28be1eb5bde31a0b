// Host span setup (UnitConfig::span_setup kHost): the host sends every span's start
// values instead of the triangle's coefficients. What each check is, and is not:
//   pixels      the same frame shaded with unit setup must come out bit for bit the same. The
//               host computes its start values with the model's own SpanSetup, so this is a
//               consistency check of the two routes through one span setup (the packing, the
//               stream, the start bank), not an independent check of SpanSetup's arithmetic:
//               that is the golden model's (tests/golden/) and the RTL co-simulation's.
//   cycles      the clocked cycle model against the closed form.
//   layout      the start values' words against values placed by hand.
#include "model/host_setup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "derive/derive_config.h"
#include "explore/explore.h"
#include "host/frame.h"
#include "model/cycle_estimate.h"
#include "model/rtl_parameters.h"
#include "model/shade_unit.h"
#include "model/start_packing.h"
#include "sim/harness/cycle_run.h"
#include "sim/harness/random_stream.h"

namespace shadesim {
namespace {

std::vector<std::string> shipped_and_hard_scenes() {
  std::vector<std::string> out;
  for (const char* dir : {"/scenes", "/scenes/hard"}) {
    for (const auto& e :
         std::filesystem::directory_iterator(std::string(SHADESIM_SOURCE_DIR) + dir)) {
      if (e.path().extension() == ".json") out.push_back(e.path().string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

UnitConfig host_unit(UnitConfig c) {
  c.span_setup = SpanSetupSite::kHost;
  c.tri_queue = 1;
  return c;
}

TEST(HostSetup, StartValuesPackDenselyAcrossWords) {
  UnitConfig c;
  c.specular.kind = SpecularUnitKind::kNone;
  c.series = FixedFormat{24, 4, true, Quantization::kTruncate, Overflow::kWrap};
  c.channels = 3;  // three series of 24 bits: 9 values, 216 bits, 4 words
  const StartLayout l = StartLayout::of(c);
  EXPECT_EQ(l.values, 9);
  EXPECT_EQ(l.words, 4);
  std::vector<int64_t> v = {1, -1, 0x7FFFFF, -0x800000, 5, 6, 7, 8, -9};
  const std::vector<uint64_t> w = l.pack(v);
  // Value 0 at bits 0..23, value 1 (all ones) at 24..47, value 2 at 48..71: straddles word 0/1.
  EXPECT_EQ(w[0] & 0xFFFFFF, 1u);
  EXPECT_EQ((w[0] >> 24) & 0xFFFFFF, 0xFFFFFFu);
  EXPECT_EQ(w[0] >> 48, 0xFFFFu);  // value 2's low 16 bits
  EXPECT_EQ(w[1] & 0xFF, 0x7Fu);   // ... and its high 8
  EXPECT_EQ(l.unpack(w.data()), v);
}

TEST(HostSetup, EveryShippedAndHardSceneShadesBitIdenticalToUnitSetup) {
  // Each scene on its own unit, with unit and with host span setup: the host stream has no
  // TRIANGLE, one start value triple per series on every SPAN, and every pixel the same.
  for (const std::string& path : shipped_and_hard_scenes()) {
    DeriveOptions d;
    d.span_setup = SpanSetupSite::kUnit;
    const UnitConfig unit = derive_config({path}, d).config;
    FrameOptions o;
    o.fixed_unit = true;
    o.base = unit;
    const PreparedFrame a = prepare_frame(path, o);
    o.base = host_unit(unit);
    const PreparedFrame b = prepare_frame(path, o);
    size_t triangles = 0, spans = 0;
    for (const Command& c : b.encoded.stream.commands) {
      triangles += std::holds_alternative<TriangleCmd>(c);
      if (const auto* s = std::get_if<SpanCmd>(&c)) {
        ++spans;
        EXPECT_EQ(s->starts.size(), static_cast<size_t>(3 * unit.series_per_triangle()));
      }
    }
    EXPECT_EQ(triangles, 0u) << path;
    EXPECT_EQ(spans, a.encoded.stats.spans) << path;
    const auto pa = ShadeUnit(a.config).run(a.encoded.stream);
    const auto pb = ShadeUnit(b.config).run(b.encoded.stream);
    ASSERT_EQ(pa.size(), pb.size()) << path;
    ASSERT_GT(pa.size(), 0u) << path;
    size_t differ = 0;
    for (size_t i = 0; i < pa.size(); ++i) {
      differ += pa[i].x != pb[i].x || pa[i].y != pb[i].y || pa[i].colour != pb[i].colour ||
                pa[i].end_of_row != pb[i].end_of_row;
    }
    EXPECT_EQ(differ, 0u) << path;
    // And the binary form decodes to the same commands (start values through the packing).
    const std::vector<uint64_t> words = b.encoded.stream.encode();
    const CommandStream back = CommandStream::decode(words, b.config, "test");
    EXPECT_EQ(back.encode(), words) << path;
  }
}

TEST(HostSetup, ConfigChoosesHostSetupWhereTheSceneStaysWithinTheCycleTarget) {
  // The rule: host setup exactly where the host-setup unit's frame runs at <= the target cycles
  // per pixel (the closed-form cycle model, no gaps), checked against the cycle model run here.
  for (const std::string name : {"sphere", "multi"}) {
    const std::string path = std::string(SHADESIM_SOURCE_DIR) + "/scenes/" + name + ".json";
    for (const double target : {1.10, 1.25}) {
      DeriveOptions d;
      d.max_cycles_per_pixel = target;
      const DerivedConfig derived = derive_config({path}, d);
      FrameOptions o;
      o.fixed_unit = true;
      o.base = host_unit(derived.config);
      const PreparedFrame f = prepare_frame(path, o);
      const CycleRun run =
          run_cycle_model(f.encoded.stream.encode(), Stimulus{}, CycleConfig::of(f.config));
      const double cpp = static_cast<double>(run.cycles) / static_cast<double>(run.pixels);
      EXPECT_EQ(derived.config.host_setup(), cpp <= target) << name << " at " << cpp;
      EXPECT_EQ(derived.config.tri_queue, derived.config.host_setup() ? 1 : 2) << name;
      bool reason = false;
      for (const FieldReason& r : derived.reasons) {
        if (r.field != "span_setup") continue;
        reason = true;
        EXPECT_EQ(r.value, derived.config.host_setup() ? "host" : "unit");
        EXPECT_NE(r.reason.find("cycles/px"), std::string::npos) << r.reason;
      }
      EXPECT_TRUE(reason) << name;
    }
  }
}

TEST(HostSetup, ExploreSweepsTheKnobForTheFrontNotTheErrorSearch) {
  // The knob changes area and cycles, never a pixel: swept, not searched; host takes queue 1.
  for (const bool host : {false, true}) {
    UnitConfig start;
    start.tri_queue = 2;
    if (host) start = host_unit(start);
    size_t found = 0;
    for (const Knob& k : knobs_for(start)) {
      if (k.name != "span_setup") continue;
      ++found;
      EXPECT_FALSE(k.searched);
      EXPECT_EQ(k.read(start), host ? 1 : 0);
      UnitConfig c = start;
      k.apply(c, 1);
      EXPECT_TRUE(c.host_setup());
      EXPECT_EQ(c.tri_queue, 1);
      c.validate();
      k.apply(c, 0);
      EXPECT_FALSE(c.host_setup());
      EXPECT_EQ(c.tri_queue, 2);
    }
    EXPECT_EQ(found, 1u);
  }
}

TEST(HostSetup, TextFormRoundTrips) {
  UnitConfig c = host_unit(UnitConfig{});
  CommandStream s;
  s.config = c;
  MaterialCmd m;
  m.ambient = {3};
  m.spec_colour = {5};
  m.exponent = 1 << 16;
  m.unit_params = {};
  s.commands.emplace_back(m);
  const int values = StartLayout::of(c).values;
  SpanCmd span{4, 7, 9, true, {}};
  for (int j = 0; j < values; ++j) span.starts.push_back(j % 2 ? -j : j);
  s.commands.emplace_back(span);
  s.commands.emplace_back(EndFrameCmd{});
  s.validate("test");
  std::stringstream text;
  s.write_text(text);
  EXPECT_NE(text.str().find("span 4 7 9 last |"), std::string::npos) << text.str();
  const CommandStream back = CommandStream::read_text(text, "text");
  EXPECT_EQ(back.encode(), s.encode());
  EXPECT_TRUE(back.config.host_setup());
}

TEST(HostSetup, InvalidCombinationsAreRejectedWithTheirReason) {
  UnitConfig c = host_unit(UnitConfig{});
  c.tri_queue = 2;
  try {
    c.validate();
    ADD_FAILURE() << "tri_queue 2 with host setup accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tri_queue must be 1 with span_setup host"),
              std::string::npos)
        << e.what();
  }
  // A TRIANGLE in a host-setup stream, and a SPAN without its start values.
  CommandStream s;
  s.config = host_unit(UnitConfig{});
  s.commands.emplace_back(TriangleCmd{0, 0, std::vector<int64_t>(size_t{6} * 2, 0)});
  EXPECT_THROW(s.validate("test"), CommandStreamError);
  s.commands = {SpanCmd{1, 1, 1, false, {}}};
  EXPECT_THROW(s.validate("test"), CommandStreamError);
  // The JSON name, and the RTL parameter only for host setup (unit units keep their builds).
  EXPECT_NE(config_to_json(s.config).find("\"span_setup\":\"host\""), std::string::npos);
  EXPECT_EQ(config_from_json(config_to_json(s.config), "test").span_setup, SpanSetupSite::kHost);
  EXPECT_EQ(config_to_json(UnitConfig{}).find("span_setup"), std::string::npos);
  bool host_param = false;
  for (const auto& p : shade_unit_parameters(s.config)) host_param |= p.name == "SPAN_SETUP";
  EXPECT_TRUE(host_param);
  for (const auto& p : shade_unit_parameters(UnitConfig{})) EXPECT_NE(p.name, "SPAN_SETUP");
}

// The closed form against the clocked model, as tests/cycle_estimate_test.cpp does for unit
// setup: cycles, pixels, beats and every scanline's cycle, over ports, lanes, start bank depths,
// material buffers and slot timings.
void expect_estimate_equals_clocked(const std::vector<uint64_t>& words, const CycleConfig& u,
                                    const std::string& what) {
  const CycleRun clocked = run_cycle_model(words, Stimulus{}, u);
  const CycleEstimateRun fast = CycleEstimate(u).run(words, true);
  const std::string where = what + " port " + std::to_string(u.port_words) + " lanes " +
                            std::to_string(u.lanes) + " depth " + std::to_string(u.start_depth) +
                            " matbuf " + std::to_string(u.material_buffers) + " latency " +
                            std::to_string(u.slot.latency) + "/" + std::to_string(u.slot.interval);
  ASSERT_EQ(fast.cycles, clocked.cycles) << where;
  EXPECT_EQ(fast.pixels, clocked.pixels) << where;
  EXPECT_EQ(fast.beats, clocked.beats) << where;
  ASSERT_EQ(fast.scanlines.size(), clocked.scanlines.size()) << where;
  for (size_t i = 0; i < fast.scanlines.size(); ++i) {
    ASSERT_EQ(fast.scanlines[i].cycle, clocked.scanlines[i].cycle) << where << " scanline " << i;
  }
  ASSERT_TRUE(fast.breakdown.has_value()) << where;
  const auto a = fast.breakdown->rows(), b = clocked.breakdown.rows();
  for (size_t i = 0; i < a.size(); ++i)
    EXPECT_EQ(a[i].cycles, b[i].cycles) << where << ": breakdown " << a[i].name;
}

void expect_estimate_on_grid(const CommandStream& host, const std::string& what) {
  const std::vector<uint64_t> words = host.encode();
  for (int port : {1, 2, 4, 8}) {
    for (int lanes : {1, 2}) {
      for (int depth : {1, 2}) {
        for (int mb : {1, 2}) {
          for (const SlotTiming slot : {SlotTiming{0, 1}, SlotTiming{3, 1}, SlotTiming{5, 5}}) {
            CycleConfig u = CycleConfig::of(host.config);
            u.slot = slot;
            u.port_words = port;
            u.lanes = lanes;
            u.start_depth = depth;
            u.material_buffers = mb;
            expect_estimate_equals_clocked(words, u, what);
          }
        }
      }
    }
  }
}

TEST(HostSetup, CycleEstimateEqualsTheClockedModel) {
  for (const std::string& path : {std::string(SHADESIM_SOURCE_DIR) + "/scenes/sphere.json",
                                  std::string(SHADESIM_SOURCE_DIR) + "/scenes/multi.json"}) {
    FrameOptions o;
    o.fixed_unit = true;
    DeriveOptions d;
    d.span_setup = SpanSetupSite::kHost;
    o.base = derive_config({path}, d).config;
    expect_estimate_on_grid(prepare_frame(path, o).encoded.stream, path);
  }
  // Random streams with MATERIAL and TABLE commands between the spans.
  UnitConfig lut;
  lut.specular.kind = SpecularUnitKind::kLut;
  lut.channels = 3;
  for (const std::string& name : scenario_names()) {
    for (uint64_t seed = 1; seed <= 2; ++seed) {
      const CommandStream s = random_stream(lut, scenario_by_name(name).shape, seed * 7919);
      expect_estimate_on_grid(with_host_setup(s), "random " + name);
    }
  }
}

TEST(HostSetup, OneSpanTakesTheStartBankLatencyPlusItsPixels) {
  // A SPAN whose start values come in its header's beat is taken on cycle 0, complete in the
  // start bank on cycle 1, loaded by the engines on edge 1, emitted from edge 2: its first
  // pixel leaves on cycle 3 + latency = span_latency(), two cycles before unit setup's.
  UnitConfig c = host_unit(UnitConfig{});
  c.port_words = 8;
  c.specular.kind = SpecularUnitKind::kNone;  // one series: 3 values, 2 words
  CycleConfig u = CycleConfig::of(c);
  ASSERT_EQ(u.start_words, 2);
  std::vector<uint64_t> words = {CommandWord::span(3, 10, 4, true).bits, 0, 0};
  for (int latency : {0, 2}) {
    u.slot = SlotTiming{latency, 1};
    const CycleEstimateRun r = CycleEstimate(u).run(words);
    ASSERT_EQ(r.scanlines.size(), 1u);
    EXPECT_EQ(r.scanlines[0].cycle - 3, static_cast<uint64_t>(3 + latency));
    EXPECT_EQ(CycleModel(u).span_latency(), 3 + latency);
    expect_estimate_equals_clocked(words, u, "one span");
  }
}

}  // namespace
}  // namespace shadesim
