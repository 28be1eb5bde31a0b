// SystemC backend: the Verilated shade_unit (behind ScDut, sim/harness/sc_dut.h) under an
// sc_clock, with the testbench as one SC_MODULE (ScBench) that moves values between its ports
// and the lockstep block (sim/harness/cosim.h, the contract) on every rising edge. Compiled once
// into libshadesim_cosim_sc; each SystemC build's glue supplies only the model.
//
// A SystemC kernel elaborates once per process: one run per process.
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <systemc>

#include "sim/harness/cosim.h"
#include "sim/harness/cosim_executable.h"
#include "sim/harness/sc_dut.h"

namespace shadesim {
namespace {

constexpr double kScPeriodNs = 10.0;

// Posedge index of the current time; posedge kResetCycles is cycle 0.
int64_t sc_cycle_now() {
  return static_cast<int64_t>(sc_core::sc_time_stamp() /
                              sc_core::sc_time(kScPeriodNs, sc_core::SC_NS)) -
         kResetCycles;
}

// The testbench around the lockstep block: on each rising edge it reads the DUT's outputs as
// they were just before the edge (signal values change only after the edge's evaluation), hands
// them to Lockstep::edge, and writes the next cycle's inputs, so cycle numbers match the C++
// backend's exactly. During reset it holds every input low.
struct ScBench : sc_core::sc_module {
  sc_core::sc_in<bool> clk;

  SC_HAS_PROCESS(ScBench);
  // SystemC's module-name stack needs sc_module_name by value.
  // NOLINTNEXTLINE(performance-unnecessary-value-param): see above
  ScBench(sc_core::sc_module_name name, Lockstep& lockstep, ScDut& dut)
      : sc_module(name), lockstep_(lockstep), dut_(dut) {
    SC_METHOD(tick);
    sensitive << clk.pos();
    dont_initialize();
  }

  void tick() {
    static constexpr uint64_t kZeros[8] = {};  // port_words is at most 8
    const int port_words = lockstep_.unit().port_words;
    const int64_t cycle = sc_cycle_now();
    if (cycle >= 0) {
      const auto colour_bits = [this](int lsb, int width) { return dut_.colour_bits(lsb, width); };
      if (!lockstep_.edge(static_cast<uint64_t>(cycle), sample_of(dut_.read_outputs()),
                          colour_bits)) {
        sc_core::sc_stop();
        return;
      }
    }
    const int64_t next = cycle + 1;
    if (next < 0) {
      dut_.write_inputs(false, false, kZeros, port_words, false);
    } else {
      const Lockstep::Drive& in = lockstep_.drive(static_cast<uint64_t>(next));
      dut_.write_inputs(true, in.cmd_valid, in.cmd_data, port_words, in.pix_ready);
    }
  }

 private:
  Lockstep& lockstep_;
  ScDut& dut_;
};

CosimResult run_systemc(const CosimJob& job) {
  Lockstep lockstep(job);
  const UnitConfig& cfg = lockstep.unit();
  sc_core::sc_clock clk("clk", kScPeriodNs, sc_core::SC_NS, 0.5, 0, sc_core::SC_NS, true);
  // The deliberate fault of a fault run.
  VerilatorCommandLine command_line(job.fault);
  const std::unique_ptr<ScDut> dut = make_sc_dut(clk, command_line.argc(), command_line.argv());
  if (!dut->port_fits(cfg.port_words)) {
    throw std::invalid_argument("configuration " + job.config.name + ": port_words " +
                                std::to_string(cfg.port_words) +
                                " differs from the Verilated cmd_data_i width");
  }
  ScBench bench("bench", lockstep, *dut);
  bench.clk(clk);

  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  CosimResult r =  // returned: moved
      lockstep.result(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  // The counters live in the model: write them while it exists.
  if (!job.coverage_path.empty()) dut->write_coverage(job.coverage_path);
  return r;
}

}  // namespace

int sc_cosim_main(int argc, char** argv, const BuiltModel& model) {
  CosimExecutable exe = executable_of(model, "systemc", "shadesim cosim --backend systemc");
  exe.one_job_per_process = true;
  exe.run = [](const CosimJob& job, const WaveWindow* waves) {
    if (waves) {
      throw std::invalid_argument(
          "waveforms need the trace-enabled C++ build (shadesim cosim --waves)");
    }
    return run_systemc(job);
  };
  return cosim_main_or_error(argc, argv, exe);
}

}  // namespace shadesim
