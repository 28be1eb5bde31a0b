// The Verilated SystemC model behind a small interface (the SystemC twin of CppDut,
// sim/harness/verilated_dut.h): the bench module (sim/harness/sc_backend.cpp) is compiled once
// into libshadesim_cosim_sc, and each SystemC build's glue (sim/harness/cosim_glue.cpp) owns
// its Vshade_unit and the signals of its port types.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <systemc>

#include "sim/harness/verilated_dut.h"

namespace shadesim {

class ScDut {
 public:
  virtual ~ScDut() = default;
  // Whether the Verilated cmd_data_i is port_words 64-bit words wide.
  virtual bool port_fits(int port_words) const = 0;
  // Writes rst_ni, cmd_valid_i, cmd_data_i (port_words words) and pix_ready_i; they take effect
  // after this delta cycle, as signal writes do.
  virtual void write_inputs(bool rst_n, bool cmd_valid, const uint64_t* beat, int port_words,
                            bool pix_ready) = 0;
  virtual DutOutputs read_outputs() const = 0;
  // Bits [lsb, lsb + width) of pix_colour_o, width <= 64.
  virtual uint64_t colour_bits(int lsb, int width) const = 0;
  // Covered builds: the run's coverage counts (no-op in others).
  virtual void write_coverage(const std::string& path) = 0;
};

// Defined by the glue of a SystemC build: the model with clk_i on `clk`, given Verilated's
// command line (the deliberate fault's plusargs).
std::unique_ptr<ScDut> make_sc_dut(sc_core::sc_clock& clk, int argc, const char** argv);

// The executable's main, in libshadesim_cosim_sc (sim/harness/sc_backend.cpp).
int sc_cosim_main(int argc, char** argv, const BuiltModel& model);

}  // namespace shadesim
