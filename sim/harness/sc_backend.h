// SystemC backend: the Verilated shade_unit (verilate(... SYSTEMC)) under an sc_clock, with the
// testbench as one SC_MODULE (ScLockstep) that moves values between its ports and the lockstep
// block (sim/harness/cosim.h, the contract) on every rising edge.
//
// A SystemC kernel elaborates once per process: one run per process.
#pragma once

#include <array>
#include <chrono>
#include <stdexcept>
#include <string>
#include <systemc>
#include <type_traits>
#include <utility>
#include <vector>

#include "sim/harness/cosim.h"
#ifdef SHADESIM_COSIM_COVERAGE
#include "verilated_cov.h"
#endif

namespace shadesim {

constexpr double kScPeriodNs = 10.0;

// Posedge index of the current time; posedge kResetCycles is cycle 0.
inline int64_t sc_cycle_now() {
  return static_cast<int64_t>(sc_core::sc_time_stamp() /
                              sc_core::sc_time(kScPeriodNs, sc_core::SC_NS)) -
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
inline bool port_fits(const sc_dt::sc_bv<W>&, int port_words) {
  return W == 64 * port_words;
}

// Bits [lsb, lsb + width) (width <= 64) of an output port's value: an integer up to 64 bits,
// sc_bv above (pix_colour_o with several lanes).
inline uint64_t out_bits_of(uint64_t port, int lsb, int width) {
  return port_bits(port, lsb, width);
}
template <int W>
inline uint64_t out_bits_of(const sc_dt::sc_bv<W>& port, int lsb, int width) {
  return port.range(lsb + width - 1, lsb).to_uint64();
}

// The testbench as one SC_MODULE around the lockstep block (sim/harness/cosim.h): on each
// rising edge it reads the DUT's outputs as they were just before the edge (signal values
// change only after the edge's evaluation), hands them to Lockstep::edge, and writes the next
// cycle's inputs, so cycle numbers match the C++ backend's exactly. During reset it holds
// every input low.
template <class DT, class XT, class CT, class MT>
struct ScLockstep : sc_core::sc_module {
  sc_core::sc_in<bool> clk;
  sc_core::sc_out<bool> rst_n;
  sc_core::sc_out<bool> cmd_valid;
  sc_core::sc_out<DT> cmd_data;
  sc_core::sc_in<bool> cmd_ready;
  sc_core::sc_in<bool> pix_valid;
  sc_core::sc_in<XT> pix_x, pix_y;
  sc_core::sc_in<CT> pix_colour;
  sc_core::sc_in<MT> pix_mask;
  sc_core::sc_in<bool> pix_eor;
  sc_core::sc_out<bool> pix_ready;

  SC_HAS_PROCESS(ScLockstep);
  ScLockstep(sc_core::sc_module_name name, Lockstep& lockstep)
      : sc_module(name), lockstep_(lockstep) {
    SC_METHOD(tick);
    sensitive << clk.pos();
    dont_initialize();
  }

  void tick() {
    const int64_t cycle = sc_cycle_now();
    if (cycle >= 0) {
      Lockstep::Sample out;
      out.cmd_ready = cmd_ready.read();
      out.pix_valid = pix_valid.read();
      out.pix_x = pix_x.read();
      out.pix_y = pix_y.read();
      out.pix_mask = static_cast<uint64_t>(pix_mask.read());
      out.pix_eor = pix_eor.read();
      const CT& colour = pix_colour.read();
      const auto colour_bits = [&colour](int lsb, int width) {
        return out_bits_of(colour, lsb, width);
      };
      if (!lockstep_.edge(static_cast<uint64_t>(cycle), out, colour_bits)) {
        sc_core::sc_stop();
        return;
      }
    }
    const int64_t next = cycle + 1;
    rst_n.write(next >= 0);
    DT beat{};
    if (next < 0) {
      cmd_valid.write(false);
      pix_ready.write(false);
    } else {
      const Lockstep::Drive& in = lockstep_.drive(static_cast<uint64_t>(next));
      cmd_valid.write(in.cmd_valid);
      to_port(beat, in.cmd_data, lockstep_.unit().port_words);
      pix_ready.write(in.pix_ready);
    }
    cmd_data.write(beat);
  }

 private:
  Lockstep& lockstep_;
};

template <class V>
CosimResult run_verilated_systemc(const CosimJob& job) {
  // Verilator picks bool / uint32_t / uint64_t per port width; follow it.
  using XT = typename std::remove_reference_t<decltype(std::declval<V&>().pix_x_o)>::data_type;
  using CT = typename std::remove_reference_t<decltype(std::declval<V&>().pix_colour_o)>::data_type;
  using DT = typename std::remove_reference_t<decltype(std::declval<V&>().cmd_data_i)>::data_type;
  using MT = typename std::remove_reference_t<decltype(std::declval<V&>().pix_mask_o)>::data_type;
  Lockstep lockstep(job);
  const UnitConfig& cfg = lockstep.unit();

  sc_core::sc_clock clk("clk", kScPeriodNs, sc_core::SC_NS, 0.5, 0, sc_core::SC_NS, true);
  sc_core::sc_signal<bool> rst_n("rst_n"), cmd_valid("cmd_valid"), cmd_ready("cmd_ready");
  sc_core::sc_signal<DT> cmd_data("cmd_data");
  if (!port_fits(DT{}, cfg.port_words)) {
    throw std::invalid_argument("configuration " + job.config.name + ": port_words " +
                                std::to_string(cfg.port_words) +
                                " differs from the Verilated cmd_data_i width");
  }
  sc_core::sc_signal<XT> pix_x("pix_x"), pix_y("pix_y");
  sc_core::sc_signal<CT> pix_colour("pix_colour");
  sc_core::sc_signal<MT> pix_mask("pix_mask");
  sc_core::sc_signal<bool> pix_eor("pix_eor"), pix_valid("pix_valid"), pix_ready("pix_ready");

  // The deliberate fault of a fault run.
  VerilatorCommandLine command_line(job.fault);
  Verilated::commandArgs(command_line.argc(), command_line.argv());
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

  ScLockstep<DT, XT, CT, MT> bench("bench", lockstep);
  bench.clk(clk);
  bench.rst_n(rst_n);
  bench.cmd_valid(cmd_valid);
  bench.cmd_data(cmd_data);
  bench.cmd_ready(cmd_ready);
  bench.pix_valid(pix_valid);
  bench.pix_x(pix_x);
  bench.pix_y(pix_y);
  bench.pix_colour(pix_colour);
  bench.pix_mask(pix_mask);
  bench.pix_eor(pix_eor);
  bench.pix_ready(pix_ready);

  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  const CosimResult r =
      lockstep.result(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
#ifdef SHADESIM_COSIM_COVERAGE
  // The counters live in the model (counted into the thread's context): write them while it exists.
  if (!job.coverage_path.empty())
    Verilated::threadContextp()->coveragep()->write(job.coverage_path.c_str());
#endif
  return r;
}

}  // namespace shadesim
