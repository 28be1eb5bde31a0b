// Verilator C++ backend: the Verilated shade_unit clocked by a plain loop, the cycle model
// stepped in lockstep on the same stimulus, both feeding the scoreboard.
#pragma once

#include <chrono>

#include "sim/harness/cosim.h"
#include "verilated.h"

namespace shadesim {

template <class V>
CosimResult run_verilated_cpp(const CosimJob& job) {
  const Prepared prep = prepare(job);
  const auto t0 = std::chrono::steady_clock::now();  // simulation speed excludes preparation
  const UnitConfig& cfg = job.config.unit;
  Scoreboard board(prep.expected, cfg.channels);

  VerilatedContext context;
  V top(&context);
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

  CommandDriver rtl_driver(prep.words, job.stim);
  CommandDriver model_driver(prep.words, job.stim);
  CycleModel model;
  uint64_t cycle = 0;
  for (;; ++cycle) {
    const bool ready = job.stim.pix_ready(cycle);
    const bool valid = rtl_driver.valid();
    top.cmd_valid_i = valid;
    top.cmd_data_i = rtl_driver.word();
    top.pix_ready_i = ready;
    top.eval();
    const bool cmd_fire = valid && top.cmd_ready_o;
    if (top.pix_valid_o && ready) {
      board.rtl_pixel(unpack_pixel(top.pix_x_o, top.pix_y_o, top.pix_colour_o, top.pix_eor_o,
                                   cfg.channels, cfg.out_bits),
                      cycle);
    }
    const CycleModel::Edge e = model.clock(model_driver.valid(), model_driver.word(), ready);
    model_driver.clock(e.cmd_fire);
    if (e.pix_fire && e.pix_eor) board.model_scanline({e.pix_y, cycle, e.pix_x});
    top.clk_i = 1;
    top.eval();
    top.clk_i = 0;
    rtl_driver.clock(cmd_fire);
    if (board.failed() || board.complete()) break;
    if (cycle > prep.cycle_limit) {
      board.timeout(cycle);
      break;
    }
  }
  top.final();
  CosimResult r;
  r.first = board.first_mismatch();
  r.cycles = board.cycles();
  r.pixels = board.pixels_checked();
  r.scanlines = board.scanlines_checked();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace shadesim
