// The lockstep block (sim/harness/cosim.h) driven the way a backend drives it, against a stand-in
// DUT written here (no Verilator): a second CycleModel for the control and ShadeUnit's pixels
// for the values, so it behaves as a correct RTL would. A faithful stand-in passes; one that
// sends an extra pixel after its last, or inverts cmd_ready_o on one idle cycle, fails with that
// kind of mismatch on that cycle.
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sim/harness/cosim.h"
#include "sim/harness/random_stream.h"

namespace shadesim {
namespace {

CosimJob short_job() {
  CosimJob job;
  job.config.name = "stand-in";
  job.scenario = "short";
  Scenario sc = scenario_by_name("short");
  sc.shape.rows = 12;
  job.stream = random_stream(job.config.unit, sc.shape, 4);
  job.stim = sc.stim;
  job.stim.seed = 4;
  job.stim.stall_pct = 0;  // the stand-in shows pix_valid_o only when it fires
  return job;
}

struct Faults {
  std::optional<uint64_t> extra_pixel_after;  // cycles after the stand-in's last pixel
  std::optional<uint64_t> ready_flipped_on;   // a cycle on which cmd_ready_o is inverted
};

struct Outcome {
  CosimResult result;
  uint64_t last_pixel_cycle = 0;
  uint64_t idle_cycle = 0;  // the first cycle > 0 with cmd_valid_i low (0: none seen)
  bool idle_ready = false;  // cmd_ready_o on it
  uint64_t cycles_clocked = 0;
};

Outcome run(const CosimJob& job, const Faults& faults = {}) {
  Lockstep lockstep(job);
  CycleModel dut(CycleConfig::of(job.config.unit));
  const std::vector<PixelOut> pixels = ShadeUnit(job.config.unit).run(job.stream);
  size_t next = 0;
  Outcome r;
  std::optional<uint64_t> extra_on;
  for (uint64_t cycle = 0; cycle < 1000000; ++cycle) {
    const Lockstep::Drive& in = lockstep.drive(cycle);
    const CycleModel::Edge e = dut.clock(in.cmd_valid, in.cmd_data, in.pix_ready);
    Lockstep::Sample s;
    s.cmd_ready = e.cmd_ready != (faults.ready_flipped_on && *faults.ready_flipped_on == cycle);
    s.pix_valid = e.pix_fire;
    s.pix_x = static_cast<uint64_t>(e.pix_x);
    s.pix_y = static_cast<uint64_t>(e.pix_y);
    s.pix_mask = (uint64_t{1} << e.pix_count) - 1;
    s.pix_eor = e.pix_eor;
    uint64_t colour = 0;
    if (e.pix_fire) {
      colour = pixels[next].colour[0];
      next += static_cast<size_t>(e.pix_count);
      r.last_pixel_cycle = cycle;
      if (next == pixels.size() && faults.extra_pixel_after)
        extra_on = cycle + *faults.extra_pixel_after;
    } else if (extra_on && cycle == *extra_on) {
      s.pix_valid = true;
      s.pix_x = 1;
      s.pix_y = 1;
      s.pix_mask = 1;
    }
    if (!in.cmd_valid && cycle > 0 && r.idle_cycle == 0) {
      r.idle_cycle = cycle;
      r.idle_ready = e.cmd_ready;
    }
    const auto colour_bits = [colour](int lsb, int width) { return port_bits(colour, lsb, width); };
    r.cycles_clocked = cycle + 1;
    if (!lockstep.edge(cycle, s, colour_bits)) break;
  }
  r.result = lockstep.result(0);
  return r;
}

TEST(Lockstep, AFaithfulDutPassesAndThePipelineIsDrained) {
  const CosimJob job = short_job();
  const Outcome r = run(job);
  ASSERT_TRUE(r.result.passed()) << to_string(r.result.first.kind) << ": "
                                 << r.result.first.expected << " / " << r.result.first.got;
  const std::vector<PixelOut> pixels = ShadeUnit(job.config.unit).run(job.stream);
  EXPECT_EQ(r.result.pixels, pixels.size());
  EXPECT_EQ(r.result.scanlines, 12u);
  EXPECT_EQ(r.result.cycles, r.last_pixel_cycle + 1);
  // Clocked on past the last pixel: at least the drain (the grey ideal unit's span latency is 5
  // cycles, its slot interval 1: 2 (5 + 1) + 16 = 28 cycles).
  EXPECT_GE(r.cycles_clocked, r.last_pixel_cycle + 1 + 28);
}

TEST(Lockstep, AnExtraPixelAfterTheLastIsCaughtWhileDraining) {
  const CosimJob job = short_job();
  Faults f;
  f.extra_pixel_after = 20;
  const Outcome r = run(job, f);
  ASSERT_FALSE(r.result.passed());
  EXPECT_EQ(r.result.first.kind, Mismatch::Kind::kExtraPixel);
  EXPECT_EQ(r.result.first.cycle, r.last_pixel_cycle + 20);
  EXPECT_EQ(r.result.first.x, 1);
  EXPECT_EQ(r.result.first.y, 1);
}

TEST(Lockstep, CmdReadyIsComparedOnIdleCyclesToo) {
  const CosimJob job = short_job();
  const Outcome faithful = run(job);
  ASSERT_GT(faithful.idle_cycle, 0u) << "no cycle with cmd_valid_i low";
  Faults f;
  f.ready_flipped_on = faithful.idle_cycle;
  const Outcome r = run(job, f);
  ASSERT_FALSE(r.result.passed());
  EXPECT_EQ(r.result.first.kind, Mismatch::Kind::kReady);
  EXPECT_EQ(r.result.first.cycle, faithful.idle_cycle);
  EXPECT_EQ(r.result.first.got,
            std::string("cmd_ready_o ") + (faithful.idle_ready ? "0" : "1") + " (RTL)");
  EXPECT_NE(r.result.first.expected.find("cmd_valid_i 0"), std::string::npos)
      << r.result.first.expected;
}

}  // namespace
}  // namespace shadesim
