// SystemC backend: the Verilated shade_unit (verilate(... SYSTEMC)) under an sc_clock, fed by a
// Driver and drained by a Sink (SC_MODULEs), with the cycle model wrapped as a third module that
// steps in lockstep. Every module acts on the rising edge: it samples the handshake signals as
// they were just before the edge (what the RTL saw) and drives the next cycle's inputs, so
// cycle numbers match the C++ backend's exactly.
//
// A SystemC kernel elaborates once per process: one run per process.
#pragma once

#include <array>
#include <chrono>
#include <stdexcept>
#include <systemc>
#include <type_traits>
#include <utility>

#include "sim/harness/cosim.h"
#include "sim/harness/idle_noise.h"
#ifdef SHADESIM_COSIM_COVERAGE
#include "verilated_cov.h"
#endif

namespace shadesim {

constexpr double kScPeriodNs = 10.0;

// Posedge index of the current time; posedge kResetCycles is cycle 0.
inline int64_t sc_cycle_now() {
  return static_cast<int64_t>(sc_core::sc_time_stamp() / sc_core::sc_time(kScPeriodNs, sc_core::SC_NS)) -
         kResetCycles;
}

// A beat (port_words 64-bit words, model/command_stream.h) as the Verilated cmd_data_i's type:
// uint64_t for one word, sc_bv<64 * port_words> for more.
inline void to_port(uint64_t& port, const uint64_t* beat, int /*port_words*/) { port = beat[0]; }
template <int W>
inline void to_port(sc_dt::sc_bv<W>& port, const uint64_t* beat, int port_words) {
  static_assert(W % 64 == 0, "cmd_data_i is a whole number of 64-bit words");
  for (int k = 0; k < port_words && 64 * k < W; ++k) {
    port.set_word(2 * k, static_cast<sc_dt::sc_digit>(beat[k]));
    port.set_word(2 * k + 1, static_cast<sc_dt::sc_digit>(beat[k] >> 32));
  }
}
inline bool port_fits(const uint64_t&, int port_words) { return port_words == 1; }
template <int W>
inline bool port_fits(const sc_dt::sc_bv<W>&, int port_words) { return W == 64 * port_words; }

// Bits [lsb, lsb + width) (width <= 64) of an output port's value: an integer up to 64 bits,
// sc_bv above (pix_colour_o with several lanes).
inline uint64_t out_bits_of(uint64_t port, int lsb, int width) { return port_bits(port, lsb, width); }
template <int W>
inline uint64_t out_bits_of(const sc_dt::sc_bv<W>& port, int lsb, int width) {
  return port.range(lsb + width - 1, lsb).to_uint64();
}

template <class DT>
struct ScDriver : sc_core::sc_module {
  sc_core::sc_in<bool> clk;
  sc_core::sc_in<bool> cmd_ready;
  sc_core::sc_out<bool> rst_n;
  sc_core::sc_out<bool> cmd_valid;
  sc_core::sc_out<DT> cmd_data;

  SC_HAS_PROCESS(ScDriver);
  ScDriver(sc_core::sc_module_name name, const std::vector<uint64_t>& words, const Stimulus& stim, int port_words)
      : sc_module(name), driver_(words, stim, port_words), stim_(stim) {
    SC_METHOD(tick);
    sensitive << clk.pos();
    dont_initialize();
  }

  void tick() {
    const int64_t cycle = sc_cycle_now();
    if (cycle >= 0) {
      const bool fire = driver_.valid() && cmd_ready.read();
      driver_.clock(fire);
    }
    rst_n.write(cycle >= -1);
    const bool run = cycle >= -1;
    const bool valid = run && driver_.valid();
    cmd_valid.write(valid);
    DT beat{};
    // Valid low: noise on the data lines (sim/harness/idle_noise.h), not the next beat.
    const std::array<uint64_t, 8> noise = idle_noise(stim_, static_cast<uint64_t>(cycle + 1));
    to_port(beat, valid ? driver_.beat() : noise.data(), driver_.port_words());
    cmd_data.write(beat);
  }

 private:
  CommandDriver driver_;
  Stimulus stim_;
};

template <class XT, class CT, class MT>
struct ScSink : sc_core::sc_module {
  sc_core::sc_in<bool> clk;
  sc_core::sc_in<bool> pix_valid;
  sc_core::sc_in<XT> pix_x, pix_y;
  sc_core::sc_in<CT> pix_colour;
  sc_core::sc_in<MT> pix_mask;
  sc_core::sc_in<bool> pix_eor;
  sc_core::sc_out<bool> pix_ready;

  SC_HAS_PROCESS(ScSink);
  ScSink(sc_core::sc_module_name name, const Stimulus& stim, const UnitConfig& cfg, Scoreboard& board)
      : sc_module(name), stim_(stim), cfg_(cfg), board_(board) {
    SC_METHOD(tick);
    sensitive << clk.pos();
    dont_initialize();
  }

  void tick() {
    const int64_t cycle = sc_cycle_now();
    if (cycle >= 0 && pix_valid.read() && stim_.pix_ready(static_cast<uint64_t>(cycle))) {
      const CT& colour = pix_colour.read();
      score_beat(board_, pix_x.read(), pix_y.read(), static_cast<uint64_t>(pix_mask.read()), pix_eor.read(),
                 [&colour](int lsb, int width) { return out_bits_of(colour, lsb, width); }, cfg_,
                 static_cast<uint64_t>(cycle));
    }
    const int64_t next = cycle + 1;
    pix_ready.write(next >= 0 && stim_.pix_ready(static_cast<uint64_t>(next)));
  }

 private:
  Stimulus stim_;
  UnitConfig cfg_;
  Scoreboard& board_;
};

// The cycle model as a SystemC module: same stimulus, own driver, lockstep with the RTL; it
// also ends the simulation when the scoreboard is complete, failed or the run hangs.
SC_MODULE(ScCycleModel) {
  sc_core::sc_in<bool> clk;

  SC_HAS_PROCESS(ScCycleModel);
  ScCycleModel(sc_core::sc_module_name name, const std::vector<uint64_t>& words, const Stimulus& stim,
               CycleConfig timing, Scoreboard& board, uint64_t cycle_limit,
               const sc_core::sc_signal<bool>& pix_valid, uint64_t watchdog_cycles)
      : sc_module(name), driver_(words, stim, timing.port_words), stim_(stim), model_(timing), board_(board),
        limit_(cycle_limit), pix_valid_(pix_valid), watchdog_(watchdog_cycles) {
    SC_METHOD(tick);
    sensitive << clk.pos();
    dont_initialize();
  }

  void tick() {
    const int64_t cycle = sc_cycle_now();
    if (cycle < 0) return;
    const auto c = static_cast<uint64_t>(cycle);
    const CycleModel::Edge e = model_.clock(driver_.valid(), driver_.beat(), stim_.pix_ready(c));
    driver_.clock(e.cmd_fire);
    if (e.pix_fire && e.pix_eor) board_.model_scanline({e.pix_y, c, e.pix_x + e.pix_count - 1});
    // The sink may record this edge's pixel after this check: completion is seen one edge
    // later, which changes nothing that is compared.
    if (board_.failed() || board_.complete()) {
      sc_core::sc_stop();
    } else if (c > limit_) {
      board_.timeout(c);
      sc_core::sc_stop();
    } else if (watchdog_.expired(c, pix_valid_.read(), board_)) {  // the value before this edge
      board_.hang(c, watchdog_.quiet_since(), watchdog_.limit());
      sc_core::sc_stop();
    }
  }

 private:
  CommandDriver driver_;
  Stimulus stim_;
  CycleModel model_;
  Scoreboard& board_;
  uint64_t limit_;
  const sc_core::sc_signal<bool>& pix_valid_;
  PixelWatchdog watchdog_;
};

template <class V>
CosimResult run_verilated_systemc(const CosimJob& job) {
  // Verilator picks bool / uint32_t / uint64_t per port width; follow it.
  using XT = typename std::remove_reference_t<decltype(std::declval<V&>().pix_x_o)>::data_type;
  using CT = typename std::remove_reference_t<decltype(std::declval<V&>().pix_colour_o)>::data_type;
  using DT = typename std::remove_reference_t<decltype(std::declval<V&>().cmd_data_i)>::data_type;
  using MT = typename std::remove_reference_t<decltype(std::declval<V&>().pix_mask_o)>::data_type;
  Prepared prep = prepare(job);
  const UnitConfig& cfg = job.config.unit;
  Scoreboard board(std::move(prep.expected), cfg.channels, cfg.lanes);  // not needed after this: no copy

  sc_core::sc_clock clk("clk", kScPeriodNs, sc_core::SC_NS, 0.5, 0, sc_core::SC_NS, true);
  sc_core::sc_signal<bool> rst_n("rst_n"), cmd_valid("cmd_valid"), cmd_ready("cmd_ready");
  sc_core::sc_signal<DT> cmd_data("cmd_data");
  if (!port_fits(DT{}, cfg.port_words)) {
    throw std::invalid_argument("configuration " + job.config.name + ": port_words " + std::to_string(cfg.port_words) +
                                " differs from the Verilated cmd_data_i width");
  }
  sc_core::sc_signal<XT> pix_x("pix_x"), pix_y("pix_y");
  sc_core::sc_signal<CT> pix_colour("pix_colour");
  sc_core::sc_signal<MT> pix_mask("pix_mask");
  sc_core::sc_signal<bool> pix_eor("pix_eor"), pix_valid("pix_valid"), pix_ready("pix_ready");

  V dut("dut");
  dut.clk_i(clk);
  dut.rst_ni(rst_n);
  dut.cmd_data_i(cmd_data);
  dut.cmd_valid_i(cmd_valid);
  dut.cmd_ready_o(cmd_ready);
  dut.pix_x_o(pix_x);
  dut.pix_y_o(pix_y);
  dut.pix_colour_o(pix_colour);
  dut.pix_mask_o(pix_mask);
  dut.pix_eor_o(pix_eor);
  dut.pix_valid_o(pix_valid);
  dut.pix_ready_i(pix_ready);

  ScDriver<DT> driver("driver", prep.words, job.stim, cfg.port_words);
  driver.clk(clk);
  driver.cmd_ready(cmd_ready);
  driver.rst_n(rst_n);
  driver.cmd_valid(cmd_valid);
  driver.cmd_data(cmd_data);

  ScSink<XT, CT, MT> sink("sink", job.stim, cfg, board);
  sink.clk(clk);
  sink.pix_valid(pix_valid);
  sink.pix_x(pix_x);
  sink.pix_y(pix_y);
  sink.pix_colour(pix_colour);
  sink.pix_mask(pix_mask);
  sink.pix_eor(pix_eor);
  sink.pix_ready(pix_ready);

  ScCycleModel model("cycle_model", prep.words, job.stim, CycleConfig::of(cfg), board, prep.cycle_limit, pix_valid,
                       prep.watchdog_cycles);
  model.clk(clk);

  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  CosimResult r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.first = board.first_mismatch();
  r.cycles = board.cycles();
  r.pixels = board.pixels_checked();
  r.scanlines = board.scanlines_checked();
#ifdef SHADESIM_COSIM_COVERAGE
  // The counters live in the model (counted into the thread's context): write them while it exists.
  if (!job.coverage_path.empty()) Verilated::threadContextp()->coveragep()->write(job.coverage_path.c_str());
#endif
  return r;
}

}  // namespace shadesim
