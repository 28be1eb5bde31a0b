// Watchdog for an RTL that stops producing pixels: no pix_valid_o for more than a limit of
// cycles while the bit-accurate model still expects pixels is reported as a hang at once,
// instead of simulating on to the run's overall cycle bound (which, on a long stream, is
// millions of cycles after the hang).
//
// The default limit comes from the cycle model under the same stimulus: its longest stretch
// of cycles without a pixel leaving, plus a margin. A cycle-exact RTL holds pix_valid_o high
// whenever a pixel waits (valid/ready), so its pix_valid_o is never low longer than the cycle
// model goes without a pixel leaving; the margin keeps a merely late RTL (a cycle mismatch,
// which the scoreboard reports better) from being called hung.
#pragma once

#include <cstdint>
#include <vector>

#include "model/cycle_model.h"
#include "sim/harness/scoreboard.h"
#include "sim/harness/stimulus.h"

namespace shadesim {

// Cycles the default watchdog allows beyond the cycle model's longest pixel-less stretch.
constexpr uint64_t kWatchdogMargin = 1000;

// What the cycle model predicts for a stream: its length in cycles and the longest run of
// cycles without a pixel leaving (from cycle 0 to the first pixel, and between pixels).
struct PixelTiming {
  uint64_t cycles = 0;
  uint64_t longest_quiet = 0;
};

inline PixelTiming predict_pixel_timing(const std::vector<uint64_t>& words, const Stimulus& stim,
                                        const CycleConfig& timing) {
  CycleModel model(timing);
  model.track_categories(false);
  CommandDriver driver(words, stim, timing.port_words);
  PixelTiming t;
  uint64_t quiet = 0;
  for (uint64_t cycle = 0; !driver.done() || !model.idle(); ++cycle) {
    const CycleModel::Edge e = model.clock(driver.valid(), driver.beat(), stim.pix_ready(cycle));
    driver.clock(e.cmd_fire);
    quiet = e.pix_fire ? 0 : quiet + 1;
    if (quiet > t.longest_quiet) t.longest_quiet = quiet;
    t.cycles = cycle + 1;
  }
  return t;
}

class PixelWatchdog {
 public:
  // `limit`: cycles without pix_valid_o allowed while pixels are pending; 0 disables it.
  explicit PixelWatchdog(uint64_t limit) : limit_(limit) {}

  // Called once per cycle with pix_valid_o as sampled just before that cycle's edge. True when
  // the RTL has shown no pixel for more than the limit while the scoreboard still expects one:
  // the caller then reports the hang (Scoreboard::hang) and stops.
  bool expired(uint64_t cycle, bool pix_valid, const Scoreboard& board) {
    if (pix_valid) {
      last_valid_ = cycle;
      seen_valid_ = true;
      return false;
    }
    const uint64_t since = seen_valid_ ? last_valid_ + 1 : 0;
    return limit_ > 0 && board.pixels_pending() && cycle >= since && cycle - since >= limit_;
  }

  uint64_t limit() const { return limit_; }
  // First cycle of the current stretch without pix_valid_o.
  uint64_t quiet_since() const { return seen_valid_ ? last_valid_ + 1 : 0; }

 private:
  uint64_t limit_;
  uint64_t last_valid_ = 0;
  bool seen_valid_ = false;
};

}  // namespace shadesim
