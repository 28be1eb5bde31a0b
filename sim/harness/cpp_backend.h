// Verilator C++ backend: the Verilated shade_unit clocked by a plain loop that moves values
// between its ports and the lockstep block (sim/harness/cosim.h, the contract).
#pragma once

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sim/harness/cosim.h"
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
inline bool port_fits(const VlWide<N>&, int port_words) {
  return N == 2 * static_cast<std::size_t>(port_words);
}

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
  Lockstep lockstep(job, waves);
  const auto t0 = std::chrono::steady_clock::now();  // simulation speed excludes preparation
  const UnitConfig& cfg = lockstep.unit();

  VerilatedContext context;
#ifdef SHADESIM_COSIM_TRACE
  std::unique_ptr<VerilatedFstC> fst;
  if (waves) context.traceEverOn(true);
#else
  if (waves) {
    throw std::invalid_argument(
        "waveforms need the trace-enabled build (shadesim cosim --waves picks it); this one has no "
        "tracing");
  }
#endif
  // The deliberate fault of a fault run.
  VerilatorCommandLine command_line(job.fault);
  context.commandArgs(command_line.argc(), command_line.argv());
  V top(&context);
  if (!port_fits(top.cmd_data_i, cfg.port_words)) {
    throw std::invalid_argument("configuration " + job.config.name + ": port_words " +
                                std::to_string(cfg.port_words) +
                                " differs from the Verilated cmd_data_i width");
  }
#ifdef SHADESIM_COSIM_TRACE
  if (waves) {
    fst = std::make_unique<VerilatedFstC>();
    top.trace(fst.get(), 99);
    fst->open(waves->path.c_str());
    if (!fst->isOpen())
      throw std::runtime_error(waves->path + ": cannot open for writing the waveform");
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

  const auto colour_bits = [&top](int lsb, int width) {
    return out_bits_of(top.pix_colour_o, lsb, width);
  };
  for (uint64_t cycle = 0;; ++cycle) {
    const Lockstep::Drive& in = lockstep.drive(cycle);
    top.cmd_valid_i = in.cmd_valid;
    put_beat(top.cmd_data_i, in.cmd_data, cfg.port_words);
    top.pix_ready_i = in.pix_ready;
    top.eval();
    const uint64_t t = (cycle + kResetCycles) * kWaveUnitsPerCycle;
    dump(cycle, t);
    Lockstep::Sample out;
    out.cmd_ready = top.cmd_ready_o;
    out.pix_valid = top.pix_valid_o;
    out.pix_x = top.pix_x_o;
    out.pix_y = top.pix_y_o;
    out.pix_mask = top.pix_mask_o;
    out.pix_eor = top.pix_eor_o;
    const bool go_on = lockstep.edge(cycle, out, colour_bits);
    top.clk_i = 1;
    top.eval();
    dump(cycle, t + kWaveUnitsPerCycle / 2);
    top.clk_i = 0;
    if (!go_on) break;
  }
  top.final();
#ifdef SHADESIM_COSIM_TRACE
  if (fst) fst->close();
#endif
  const CosimResult r =
      lockstep.result(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
#ifdef SHADESIM_COSIM_COVERAGE
  // The counts live in this run's context: write them before it goes, pass or fail.
  if (!job.coverage_path.empty()) context.coveragep()->write(job.coverage_path.c_str());
#endif
  return r;
}

}  // namespace shadesim
