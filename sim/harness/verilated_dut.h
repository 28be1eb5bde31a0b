// The one part of a co-simulation executable that depends on the Verilated model: shade_unit's
// ports behind a small interface, so the backends' loops (sim/harness/cpp_backend.cpp,
// sc_backend.cpp) and the driver (cosim_main.cpp, cosim_options.cpp, cosim_run.cpp) are compiled
// once, into the harness libraries, whatever the parameters. Each build compiles only its Verilated
// model and the glue (sim/harness/cosim_glue.cpp), which implements this interface for its
// Vshade_unit and whose port types (CData ... VlWide, bool ... sc_bv) follow the parameters.
//
// This header includes neither Verilator's nor the model's headers: a change to the model or
// the harness relinks the cached builds without compiling their Verilated code again.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace shadesim {

// shade_unit's outputs as sampled before a rising edge (pix_colour_o is read through
// colour_bits only when a beat leaves).
struct DutOutputs {
  bool cmd_ready = false;
  bool pix_valid = false;
  uint64_t pix_x = 0, pix_y = 0, pix_mask = 0;
  bool pix_eor = false;
};

// One Verilog parameter as the build was Verilated with it (a packed one as its slots).
struct BuiltParameter {
  const char* name;
  int64_t value;
  const int64_t* slots;  // nullptr for a plain parameter
  int slot_count;
};

// What the glue tells the driver about its build.
struct BuiltModel {
  const BuiltParameter* parameters = nullptr;
  int parameter_count = 0;
  bool traced = false;       // Verilated with --trace-fst
  bool covered = false;      // Verilated with line, toggle and user coverage
  bool fault_hooks = false;  // sim/harness/faults/ bound into shade_unit
};

// The Verilated C++ model with its own VerilatedContext.
class CppDut {
 public:
  virtual ~CppDut() = default;
  // Whether the Verilated cmd_data_i is port_words 64-bit words wide.
  virtual bool port_fits(int port_words) const = 0;
  virtual void set_clock(bool clk) = 0;
  virtual void set_reset_n(bool rst_n) = 0;
  // cmd_valid_i, cmd_data_i (port_words words) and pix_ready_i.
  virtual void set_inputs(bool cmd_valid, const uint64_t* beat, int port_words, bool pix_ready) = 0;
  virtual void eval() = 0;
  virtual DutOutputs outputs() const = 0;
  // One cycle in two calls (the per-cycle path): the inputs set and settled, the outputs
  // sampled; then the rising edge evaluated and the clock low again.
  virtual DutOutputs settle(bool cmd_valid, const uint64_t* beat, int port_words,
                            bool pix_ready) = 0;
  virtual void rising_edge() = 0;
  // Bits [lsb, lsb + width) of pix_colour_o, width <= 64.
  virtual uint64_t colour_bits(int lsb, int width) const = 0;
  // Traced builds: an FST file of the dumps between open and close. Others throw
  // std::invalid_argument from open_trace.
  virtual void open_trace(const std::string& path) = 0;
  virtual void dump(uint64_t time) = 0;
  virtual void close_trace() = 0;
  // Covered builds: the run's coverage counts (no-op in others).
  virtual void write_coverage(const std::string& path) = 0;
  virtual void final() = 0;
};

// Defined by the glue of a C++ build: the model, given Verilated's command line (the deliberate
// fault's plusargs).
std::unique_ptr<CppDut> make_cpp_dut(int argc, const char** argv);

// The executable's main, in the harness library (sim/harness/cpp_backend.cpp).
int cpp_cosim_main(int argc, char** argv, const BuiltModel& model);

}  // namespace shadesim
