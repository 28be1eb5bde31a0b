// Verilator C++ backend: the Verilated shade_unit clocked by a plain loop, the cycle model
// stepped in lockstep on the same stimulus, both feeding the scoreboard.
#pragma once

#include <chrono>
#include <memory>
#include <stdexcept>
#include <utility>

#include "sim/harness/cosim.h"
#include "sim/harness/idle_noise.h"
#include "verilated.h"
#ifdef SHADESIM_COSIM_TRACE
#include "verilated_fst_c.h"
#endif
#ifdef SHADESIM_COSIM_COVERAGE
#include "verilated_cov.h"
#endif

namespace shadesim {

// Puts a beat (port_words 64-bit words, model/command_stream.h) on the Verilated cmd_data_i:
// a 64-bit port for one word, a VlWide of 32-bit words for more.
inline void put_beat(QData& port, const uint64_t* beat, int /*port_words*/) { port = beat[0]; }
template <std::size_t N>
inline void put_beat(VlWide<N>& port, const uint64_t* beat, int port_words) {
  for (int k = 0; k < port_words; ++k) {
    port[2 * k] = static_cast<EData>(beat[k]);
    port[2 * k + 1] = static_cast<EData>(beat[k] >> 32);
  }
}
// The configuration's port width must be the Verilated one.
inline bool port_fits(const QData&, int port_words) { return port_words == 1; }
template <std::size_t N>
inline bool port_fits(const VlWide<N>&, int port_words) { return N == 2 * static_cast<std::size_t>(port_words); }

// Bits [lsb, lsb + width) (width <= 64) of a Verilated output: a plain integer up to 64 bits, a
// VlWide of 32-bit words above (pix_colour_o with several lanes).
inline uint64_t out_bits_of(QData port, int lsb, int width) { return port_bits(port, lsb, width); }
template <std::size_t N>
inline uint64_t out_bits_of(const VlWide<N>& port, int lsb, int width) {
  uint64_t v = 0;
  for (int b = 0; b < width; ++b) {
    const int i = lsb + b;
    v |= static_cast<uint64_t>((port[static_cast<std::size_t>(i / 32)] >> (i % 32)) & 1U) << b;
  }
  return v;
}

// With `waves`, only a trace-enabled build (SHADESIM_COSIM_TRACE, verilate(... TRACE_FST))
// dumps the window into an FST file; other builds throw std::invalid_argument.
template <class V>
CosimResult run_verilated_cpp(const CosimJob& job, const WaveWindow* waves = nullptr) {
  Prepared prep = prepare(job);
  const auto t0 = std::chrono::steady_clock::now();  // simulation speed excludes preparation
  const UnitConfig& cfg = job.config.unit;
  Scoreboard board(std::move(prep.expected), cfg.channels, cfg.lanes);  // not needed after this: no copy

  VerilatedContext context;
#ifdef SHADESIM_COSIM_TRACE
  std::unique_ptr<VerilatedFstC> fst;
  if (waves) context.traceEverOn(true);
#else
  if (waves) {
    throw std::invalid_argument("waveforms need the trace-enabled build (shadesim cosim --waves picks it); this one has no tracing");
  }
#endif
  V top(&context);
  if (!port_fits(top.cmd_data_i, cfg.port_words)) {
    throw std::invalid_argument("configuration " + job.config.name + ": port_words " + std::to_string(cfg.port_words) +
                                " differs from the Verilated cmd_data_i width");
  }
#ifdef SHADESIM_COSIM_TRACE
  if (waves) {
    fst = std::make_unique<VerilatedFstC>();
    top.trace(fst.get(), 99);
    fst->open(waves->path.c_str());
    if (!fst->isOpen()) throw std::runtime_error(waves->path + ": cannot open for writing the waveform");
  }
  // Dumps the state at `units` (time stamp) when `cycle` is inside the window.
  auto dump = [&](uint64_t cycle, uint64_t units) {
    if (fst && cycle >= waves->first && cycle <= waves->last) fst->dump(units);
  };
#else
  auto dump = [](uint64_t, uint64_t) {};
#endif
  top.clk_i = 0;
  top.rst_ni = 0;
  top.cmd_valid_i = 0;
  top.pix_ready_i = 0;
  top.eval();
  for (int i = 0; i < kResetCycles; ++i) {
    top.clk_i = 1;
    top.eval();
    top.clk_i = 0;
    top.eval();
  }
  top.rst_ni = 1;

  CommandDriver rtl_driver(prep.words, job.stim, cfg.port_words);
  CommandDriver model_driver(prep.words, job.stim, cfg.port_words);
  CycleModel model(CycleConfig::of(cfg));
  PixelWatchdog watchdog(prep.watchdog_cycles);
  uint64_t cycle = 0;
  for (;; ++cycle) {
    const bool ready = job.stim.pix_ready(cycle);
    const bool valid = rtl_driver.valid();
    top.cmd_valid_i = valid;
    // Valid low: noise on the data lines (sim/harness/idle_noise.h), not the next beat.
    put_beat(top.cmd_data_i, valid ? rtl_driver.beat() : idle_noise(job.stim, cycle).data(),
             cfg.port_words);
    top.pix_ready_i = ready;
    top.eval();
    const uint64_t t = (cycle + kResetCycles) * kWaveUnitsPerCycle;
    dump(cycle, t);
    const bool cmd_fire = valid && top.cmd_ready_o;
    const bool pix_valid = top.pix_valid_o;
    if (top.pix_valid_o && ready) {
      score_beat(board, top.pix_x_o, top.pix_y_o, top.pix_mask_o, top.pix_eor_o,
                 [&top](int lsb, int width) { return out_bits_of(top.pix_colour_o, lsb, width); }, cfg, cycle);
    }
    const CycleModel::Edge e = model.clock(model_driver.valid(), model_driver.beat(), ready);
    model_driver.clock(e.cmd_fire);
    if (e.pix_fire && e.pix_eor) board.model_scanline({e.pix_y, cycle, e.pix_x + e.pix_count - 1});
    top.clk_i = 1;
    top.eval();
    dump(cycle, t + kWaveUnitsPerCycle / 2);
    top.clk_i = 0;
    rtl_driver.clock(cmd_fire);
    // With a wave window, run on to its end (or to the natural end of the stream).
    const bool window_open = waves && cycle < waves->last && !board.complete();
    if ((board.failed() && !window_open) || board.complete()) break;
    if (cycle > prep.cycle_limit) {
      board.timeout(cycle);
      break;
    }
    if (watchdog.expired(cycle, pix_valid, board)) {
      board.hang(cycle, watchdog.quiet_since(), watchdog.limit());
      if (!window_open) break;
    }
  }
  top.final();
#ifdef SHADESIM_COSIM_TRACE
  if (fst) fst->close();
#endif
  CosimResult r;
  r.first = board.first_mismatch();
  r.cycles = board.cycles();
  r.pixels = board.pixels_checked();
  r.scanlines = board.scanlines_checked();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
#ifdef SHADESIM_COSIM_COVERAGE
  // The counts live in this run's context: write them before it goes, pass or fail.
  if (!job.coverage_path.empty()) context.coveragep()->write(job.coverage_path.c_str());
#endif
  return r;
}

}  // namespace shadesim
