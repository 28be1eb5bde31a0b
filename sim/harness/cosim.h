// One co-simulation run and its result, shared by the Verilator C++ and SystemC backends.
#pragma once

#include <algorithm>
#include <cstdint>
#include <variant>
#include <string>
#include <vector>

#include "model/command_stream.h"
#include "model/shade_unit.h"
#include "model/cycle_model.h"
#include "sim/harness/rtl_config.h"
#include "sim/harness/scoreboard.h"
#include "model/stimulus.h"
#include "sim/harness/watchdog.h"

namespace shadesim {

struct CosimJob {
  RtlConfig config;
  std::string scenario;  // for reports; "replay" for a loaded stream
  CommandStream stream;
  Stimulus stim;
  uint64_t watchdog_cycles = 0;  // hang limit (sim/harness/watchdog.h); 0: the cycle model's
  std::string coverage_path;     // covered builds: where the run writes its coverage .dat
};

// Cycles to dump into an FST file (trace-enabled builds only), inclusive. The run goes on past
// a mismatch until `last` so the window shows what followed it.
struct WaveWindow {
  std::string path;
  uint64_t first = 0, last = 0;
};

struct CosimResult {
  Mismatch first;  // kind kNone when the run passed
  uint64_t cycles = 0, pixels = 0, scanlines = 0;
  double seconds = 0;
  bool passed() const { return first.kind == Mismatch::Kind::kNone; }
};

// Time stamp of a cycle in waveforms: 10 units per clock, reset cycles first; the rising edge
// of cycle c is at 10 (c + kResetCycles) + 5.
constexpr uint64_t kWaveUnitsPerCycle = 10;

// Everything both backends need before the first clock: the words on the cmd port, the
// bit-accurate model's pixels, a cycle bound past which the run counts as hung, and the
// watchdog's limit of cycles without pix_valid_o.
struct Prepared {
  std::vector<uint64_t> words;
  std::vector<PixelOut> expected;
  uint64_t cycle_limit = 0;
  uint64_t watchdog_cycles = 0;
};

inline Prepared prepare(const CosimJob& job) {
  Prepared p;
  p.words = job.stream.encode();
  ShadeUnit unit(job.config.unit);
  p.expected = unit.run(job.stream);
  const PixelTiming timing = predict_pixel_timing(p.words, job.stim, CycleConfig::of(job.config.unit));
  p.cycle_limit = timing.cycles + 1000;
  p.watchdog_cycles = job.watchdog_cycles > 0 ? job.watchdog_cycles : timing.longest_quiet + kWatchdogMargin;
  return p;
}

// How many of the model's pixels the specular term changes: the same stream with every
// spec_colour set to 0, pixel by pixel. A run checks the specular units' bits only where this
// is non-zero.
inline uint64_t specular_affected_pixels(const CosimJob& job, const std::vector<PixelOut>& expected) {
  CommandStream dark = job.stream;
  for (auto& cmd : dark.commands) {
    if (auto* m = std::get_if<MaterialCmd>(&cmd)) std::fill(m->spec_colour.begin(), m->spec_colour.end(), 0);
  }
  const std::vector<PixelOut> plain = ShadeUnit(job.config.unit).run(dark);
  uint64_t n = 0;
  for (size_t i = 0; i < expected.size() && i < plain.size(); ++i) {
    for (int c = 0; c < job.config.unit.channels; ++c) {
      if (expected[i].colour[c] != plain[i].colour[c]) {
        ++n;
        break;
      }
    }
  }
  return n;
}

// Reset cycles before cycle 0 (rst_ni low on these edges).
constexpr int kResetCycles = 4;

// Unpacks one lane of the pix_colour_o bus (channel c in bits [c*out_bits +: out_bits] of it).
inline PixelOut unpack_pixel(uint64_t x, uint64_t y, uint64_t colour, bool eor, int channels,
                             int out_bits, int lane = 0) {
  PixelOut p;
  p.x = static_cast<uint16_t>(x);
  p.y = static_cast<uint16_t>(y);
  p.lane = lane;
  const uint64_t mask = (uint64_t{1} << out_bits) - 1;
  for (int c = 0; c < channels; ++c) p.colour[c] = static_cast<uint16_t>((colour >> (c * out_bits)) & mask);
  p.end_of_row = eor;
  return p;
}

// Bits [lsb, lsb + width) of an output port of up to 64 bits (width <= 64).
inline uint64_t port_bits(uint64_t port, int lsb, int width) {
  const uint64_t v = port >> lsb;
  return width >= 64 ? v : v & ((uint64_t{1} << width) - 1);
}

// A beat that left the RTL on `cycle` (pix_valid_o and pix_ready_i): lane 0's x and y, the lane
// mask, pix_eor_o, and the colour bus as colour_bits(lsb, width) -> bits [lsb, lsb + width) (each
// backend reads its own port types). Hands the valid lanes to the scoreboard in lane order,
// each as pixel x + j; pix_eor_o belongs to the last of them. A mask that is not lanes
// 0 .. n-1 is a mismatch of its own.
template <class ColourBits>
inline void score_beat(Scoreboard& board, uint64_t x, uint64_t y, uint64_t mask, bool eor,
                       const ColourBits& colour_bits, const UnitConfig& cfg, uint64_t cycle) {
  const uint64_t all = (uint64_t{1} << cfg.lanes) - 1;
  if (mask == 0 || (mask & ~all) != 0 || (mask & (mask + 1)) != 0) {
    board.rtl_bad_mask(x, y, mask, cycle);
    return;
  }
  const int width = cfg.channels * cfg.out_bits;
  for (int j = 0; (mask >> j) & 1; ++j) {
    const uint64_t c = colour_bits(j * width, width);
    const bool last = eor && ((mask >> (j + 1)) & 1) == 0;
    const uint64_t xj = x + static_cast<uint64_t>(j);
    if (!board.rtl_pixel_if_expected(xj, y, c, last, cfg.out_bits, cycle, j)) {
      board.rtl_pixel(unpack_pixel(xj, y, c, last, cfg.channels, cfg.out_bits, j), cycle);
    }
  }
}

}  // namespace shadesim
