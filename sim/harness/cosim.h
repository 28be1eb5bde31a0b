// The co-simulation contract (in the manner of ibex's dv/cosim/cosim.h): what the reference
// provides, what a backend must do each cycle, and what a failure means. Both backends -
// sim/harness/cpp_backend.cpp (a plain loop around the Verilated C++ model) and
// sim/harness/sc_backend.cpp (the Verilated SystemC model under an sc_clock) - only move values
// between the DUT's ports and the one lockstep block below, class Lockstep.
//
// The reference, built from a CosimJob before the first clock:
//   - the bit-accurate model (model/shade_unit.h, ShadeUnit::run): every pixel the stream
//     produces, in stream order, each with x, y, end of row, lane and colour channels;
//   - the cycle model (model/cycle_model.h, CycleModel::clock): the unit's control, clocked once
//     per rising edge on the same inputs as the RTL; per edge it says whether cmd_ready_o is
//     high and which pixel beat (if any) leaves;
//   - a command driver for each side (sim/harness/stimulus.h: the stream cut into beats, the job's
//     seeded idle gaps) and the job's seeded pix_ready_i pattern; while cmd_valid_i is low the
//     data lines carry seeded noise (sim/harness/idle_noise.h), which the cycle model sees too.
//
// A backend's obligations, cycle c = 0, 1, 2, ... (after kResetCycles edges with rst_ni low and
// every input low):
//   1. put drive(c)'s values on cmd_valid_i, cmd_data_i and pix_ready_i;
//   2. let the DUT's combinational logic settle, then sample cmd_ready_o and the pix_* outputs
//      (the values the rising edge at the end of cycle c acts on);
//   3. call edge(c, sample, colour_bits) before the DUT's state changes, then clock the DUT;
//   4. stop when edge() returns false, and take result().
// drive(c) must come before edge(c), and edge(c) before drive(c + 1): one call of each per cycle.
//
// What edge(c) checks (sim/harness/scoreboard.h keeps the first mismatch, Mismatch::Kind):
//   pixel        a pixel leaving the RTL (pix_valid_o and pix_ready_i) differs from the
//                bit-accurate model's next one in any field, or its lane mask has a hole;
//   cycle        a pixel left the RTL on another cycle than the same pixel left the cycle model
//                (every pixel, not only each row's last);
//   ready        cmd_ready_o differs from the cycle model's on this cycle (every cycle, valid
//                or not: both see the same data lines). It fails the run but does not stop
//                it: each side's driver follows its own cmd_ready, and a pixel-side mismatch
//                that follows (a downstream stall reaches the port first) is reported instead,
//                naming this one as its Mismatch::before;
//   extra-pixel  a pixel after the last expected one, or any pix_valid_o while the pipeline
//                drains after the run: drain_cycles() cycles past the cycle model's idle end;
//   hang         no pix_valid_o for longer than the watchdog (sim/harness/watchdog.h) allows
//                while pixels are still expected;
//   timeout      the run passed the cycle model's length + kCycleLimitMargin unfinished.
// A run passes when every expected pixel left the RTL with the model's bits on the cycle
// model's cycle, every cycle's cmd_ready_o agreed, and nothing followed. After the first
// pixel-side mismatch (or a hang) edge() returns false at once, unless a wave window is open:
// then the run goes on to the window's last cycle so the waveform shows what followed (later
// mismatches are ignored).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model/command_stream.h"
#include "model/cycle_model.h"
#include "model/shade_unit.h"
#include "sim/harness/fault_site.h"
#include "sim/harness/idle_noise.h"
#include "sim/harness/rtl_config.h"
#include "sim/harness/scoreboard.h"
#include "sim/harness/stimulus.h"
#include "sim/harness/watchdog.h"

namespace shadesim {

struct CosimJob {
  RtlConfig config;
  std::string scenario;  // for reports; "replay" for a loaded stream
  CommandStream stream;
  Stimulus stim;
  uint64_t watchdog_cycles = 0;  // hang limit (sim/harness/watchdog.h); 0: the cycle model's
  std::string coverage_path;     // covered builds: where the run writes its coverage .dat
  FaultInjection fault;          // FAULT_HOOKS builds: the deliberate fault this run injects
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

// Reset cycles before cycle 0 (rst_ni low on these edges).
constexpr int kResetCycles = 4;

// Time stamp of a cycle in waveforms: 10 units per clock, reset cycles first; the rising edge
// of cycle c is at 10 (c + kResetCycles) + 5.
constexpr uint64_t kWaveUnitsPerCycle = 10;

// Cycles a run may take beyond the cycle model's prediction before it is a timeout.
constexpr uint64_t kCycleLimitMargin = 1000;

// Cycles to watch pix_valid_o after the cycle model has gone idle with every pixel out. Any
// state that can still make a pixel - a span in setup, in the span queue or in the engines, a
// pixel in the slot - reaches the empty pix register within the span latency (SPAN header to
// first pixel) plus one slot interval, back-pressure or not (an empty pix register advances).
// Twice that and a margin, so an RTL whose pipeline is deeper than the model's is seen too.
inline uint64_t drain_cycles(const CycleModel& model, const CycleConfig& timing) {
  return 2 * static_cast<uint64_t>(model.span_latency() + timing.slot.interval) + 16;
}

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
  const PixelTiming timing =
      predict_pixel_timing(p.words, job.stim, CycleConfig::of(job.config.unit));
  p.cycle_limit = timing.cycles + kCycleLimitMargin;
  p.watchdog_cycles =
      job.watchdog_cycles > 0 ? job.watchdog_cycles : timing.longest_quiet + kWatchdogMargin;
  return p;
}

// Unpacks one lane of the pix_colour_o bus (channel c in bits [c*out_bits +: out_bits] of it).
inline PixelOut unpack_pixel(uint64_t x, uint64_t y, uint64_t colour, bool eor, int channels,
                             int out_bits, int lane = 0) {
  PixelOut p;
  p.x = static_cast<uint16_t>(x);
  p.y = static_cast<uint16_t>(y);
  p.lane = lane;
  const uint64_t mask = (uint64_t{1} << out_bits) - 1;
  for (int c = 0; c < channels; ++c) {
    p.colour[c] = static_cast<uint16_t>((colour >> (c * out_bits)) & mask);
  }
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

// The lockstep block: the reference (bit-accurate model's pixels, the cycle model), the two
// command drivers, the watchdog and the scoreboard, stepped one cycle at a time by a backend
// as the contract above says.
class Lockstep {
 public:
  // What the backend drives on a cycle.
  struct Drive {
    bool cmd_valid = false;
    const uint64_t* cmd_data = nullptr;  // port_words words: the beat, or noise while not valid
    bool pix_ready = false;
  };
  // What the backend sampled on a cycle, before its rising edge (pix_colour_o is read through
  // edge()'s colour_bits only when a beat leaves).
  struct Sample {
    bool cmd_ready = false;
    bool pix_valid = false;
    uint64_t pix_x = 0, pix_y = 0, pix_mask = 0;
    bool pix_eor = false;
  };

  // Runs the bit-accurate model and the cycle model's prediction (the cycle bound, the
  // watchdog's limit); not part of the simulation's speed. With `waves`, a mismatch does not
  // stop the run before waves->last.
  explicit Lockstep(const CosimJob& job, const WaveWindow* waves = nullptr)
      : Lockstep(job, prepare(job), waves) {}
  // The drivers and drive()'s result point into the block.
  Lockstep(const Lockstep&) = delete;
  Lockstep& operator=(const Lockstep&) = delete;

  const UnitConfig& unit() const { return cfg_; }

  // The inputs of cycle `cycle` (see the contract above for the order of calls).
  const Drive& drive(uint64_t cycle) {
    drive_.pix_ready = stim_.pix_ready(cycle);
    drive_.cmd_valid = rtl_driver_.valid();
    if (drive_.cmd_valid) {
      drive_.cmd_data = rtl_driver_.beat();
    } else {
      noise_ = idle_noise(stim_, cycle);
      drive_.cmd_data = noise_.data();
    }
    return drive_;
  }

  // The rising edge at the end of cycle `cycle`: clocks the cycle model on the inputs of
  // drive(cycle), scores the RTL's outputs `s` against it and the bit-accurate model's pixels
  // (colour_bits(lsb, width): bits [lsb, lsb + width) of pix_colour_o, width <= 64), advances
  // the drivers. Returns whether to clock on.
  template <class ColourBits>
  bool edge(uint64_t cycle, const Sample& s, const ColourBits& colour_bits) {
    // The cycle model's own driver stays in step with the RTL's while cmd_ready agrees, which
    // is checked on every cycle; its idle data lines are the RTL's.
    const bool model_valid = model_driver_.valid();
    const uint64_t* model_data =
        model_valid ? model_driver_.beat() : (drive_.cmd_valid ? zeros_.data() : drive_.cmd_data);
    const CycleModel::Edge e = model_.clock(model_valid, model_data, drive_.pix_ready);
    if (s.cmd_ready != e.cmd_ready) {  // the port's state is gathered only for the report
      board_.cmd_ready(cycle, s.cmd_ready, e.cmd_ready,
                       {drive_.cmd_valid, rtl_driver_.index(), beats_, drive_.cmd_data[0]});
    }
    const bool rtl_beat = !draining_ && s.pix_valid && drive_.pix_ready;
    // The common case first: one pixel leaves both the cycle model and the RTL on this edge,
    // each the bit-accurate model's next one (Scoreboard::pixel_pair_if_expected). Anything
    // else - beats of several lanes, pixels on one side only, a mismatch - takes the general
    // path, which reports it.
    if (e.pix_fire && rtl_beat && e.pix_count == 1 && s.pix_mask == 1 &&
        board_.pixel_pair_if_expected(cycle, e.pix_x, e.pix_y, e.pix_eor, s.pix_x, s.pix_y,
                                      colour_bits(0, cfg_.channels * cfg_.out_bits), s.pix_eor,
                                      cfg_.out_bits)) {
      model_driver_.clock(e.cmd_fire);
      rtl_driver_.clock(drive_.cmd_valid && s.cmd_ready);
      return keep_going(cycle, s.pix_valid);
    }
    if (e.pix_fire) board_.model_beat(cycle, e.pix_x, e.pix_y, e.pix_count, e.pix_eor);
    if (draining_) {
      if (s.pix_valid) board_.rtl_valid_after_end(s.pix_x, s.pix_y, s.pix_mask, cycle);
    } else if (rtl_beat) {
      score_beat(board_, s.pix_x, s.pix_y, s.pix_mask, s.pix_eor, colour_bits, cfg_, cycle);
    }
    model_driver_.clock(e.cmd_fire);
    rtl_driver_.clock(drive_.cmd_valid && s.cmd_ready);
    return keep_going(cycle, s.pix_valid);
  }

  // The outcome so far; `seconds` is the caller's wall time of the simulation.
  CosimResult result(double seconds) const {
    CosimResult r;
    r.first = board_.first_mismatch();
    // A whole run: until the stream is consumed and the unit idle, as `shadesim cycles` and the
    // closed form count it (the last pixel may leave before the END_FRAME word is taken);
    // otherwise, until the last pixel that left.
    r.cycles = idle_end_ > 0 ? idle_end_ : board_.cycles();
    r.pixels = board_.pixels_checked();
    r.scanlines = board_.scanlines_checked();
    r.seconds = seconds;
    return r;
  }

 private:
  Lockstep(const CosimJob& job, Prepared prep, const WaveWindow* waves)
      : cfg_(job.config.unit),
        stim_(job.stim),
        words_(std::move(prep.words)),
        beats_((words_.size() + static_cast<size_t>(cfg_.port_words) - 1) /
               static_cast<size_t>(cfg_.port_words)),
        board_(std::move(prep.expected), cfg_.channels, cfg_.lanes),
        rtl_driver_(words_, stim_, cfg_.port_words),
        model_driver_(words_, stim_, cfg_.port_words),
        timing_(CycleConfig::of(cfg_)),
        model_(timing_),
        watchdog_(prep.watchdog_cycles),
        cycle_limit_(prep.cycle_limit),
        drain_cycles_(drain_cycles(model_, timing_)),
        waves_(waves) {
    model_.track_categories(false);  // the breakdown of `cycles`, not needed here
  }

  bool keep_going(uint64_t cycle, bool pix_valid) {
    const bool window_open = waves_ != nullptr && cycle < waves_->last;
    if (!draining_ && board_.complete() && model_driver_.done() && model_.idle()) {
      draining_ = true;
      drain_end_ = cycle + drain_cycles_;
      idle_end_ = cycle + 1;
    }
    if (board_.failed() && !window_open) return false;
    if (draining_) return cycle < drain_end_ || window_open;
    if (cycle > cycle_limit_) {
      board_.timeout(cycle);
      return false;
    }
    if (watchdog_.expired(cycle, pix_valid, board_)) {
      board_.hang(cycle, watchdog_.quiet_since(), watchdog_.limit());
      return window_open;
    }
    return true;
  }

  UnitConfig cfg_;
  Stimulus stim_;
  std::vector<uint64_t> words_;  // the drivers point into it: never resized
  size_t beats_;
  Scoreboard board_;
  CommandDriver rtl_driver_, model_driver_;
  CycleConfig timing_;
  CycleModel model_;
  PixelWatchdog watchdog_;
  uint64_t cycle_limit_;
  uint64_t drain_cycles_;
  const WaveWindow* waves_;
  bool draining_ = false;
  uint64_t drain_end_ = 0;
  uint64_t idle_end_ = 0;  // the cycle after the one the stream was consumed and the unit idle
  Drive drive_;
  std::array<uint64_t, 8> noise_{};
  std::array<uint64_t, 8> zeros_{};
};

}  // namespace shadesim
