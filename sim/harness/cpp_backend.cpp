// Verilator C++ backend: the Verilated shade_unit (behind CppDut, sim/harness/verilated_dut.h)
// clocked by a plain loop that moves values between its ports and the lockstep block
// (sim/harness/cosim.h, the contract). Compiled once into the harness library; each build's glue
// (sim/harness/cosim_glue.cpp) supplies only the model.
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>

#include "sim/harness/cosim.h"
#include "sim/harness/cosim_executable.h"
#include "sim/harness/verilated_dut.h"

namespace shadesim {
namespace {

// Holds every input low for kResetCycles edges with rst_ni low, then releases reset.
void reset(CppDut& dut, int port_words) {
  static constexpr uint64_t kZeros[8] = {};  // port_words is at most 8
  dut.set_clock(false);
  dut.set_reset_n(false);
  dut.set_inputs(false, kZeros, port_words, false);
  dut.eval();
  for (int i = 0; i < kResetCycles; ++i) {
    dut.set_clock(true);
    dut.eval();
    dut.set_clock(false);
    dut.eval();
  }
  dut.set_reset_n(true);
}

// With `waves`, only a traced build dumps the window into an FST file; others throw
// std::invalid_argument.
CosimResult run_cpp(const CosimJob& job, const WaveWindow* waves, const BuiltModel& model) {
  Lockstep lockstep(job, waves);
  const auto t0 = std::chrono::steady_clock::now();  // simulation speed excludes preparation
  const UnitConfig& cfg = lockstep.unit();
  if (waves && !model.traced) {
    throw std::invalid_argument(
        "waveforms need the trace-enabled build (shadesim cosim --waves picks it); this one has no "
        "tracing");
  }
  // The deliberate fault of a fault run.
  VerilatorCommandLine command_line(job.fault);
  const std::unique_ptr<CppDut> dut = make_cpp_dut(command_line.argc(), command_line.argv());
  if (!dut->port_fits(cfg.port_words)) {
    throw std::invalid_argument("configuration " + job.config.name + ": port_words " +
                                std::to_string(cfg.port_words) +
                                " differs from the Verilated cmd_data_i width");
  }
  if (waves) dut->open_trace(waves->path);
  // Dumps the state at `units` (time stamp) when `cycle` is inside the window.
  const auto dump = [&](uint64_t cycle, uint64_t units) {
    if (waves && cycle >= waves->first && cycle <= waves->last) dut->dump(units);
  };
  reset(*dut, cfg.port_words);
  const auto colour_bits = [&dut](int lsb, int width) { return dut->colour_bits(lsb, width); };
  for (uint64_t cycle = 0;; ++cycle) {
    const Lockstep::Drive& in = lockstep.drive(cycle);
    const DutOutputs o = dut->settle(in.cmd_valid, in.cmd_data, cfg.port_words, in.pix_ready);
    const uint64_t t = (cycle + kResetCycles) * kWaveUnitsPerCycle;
    dump(cycle, t);
    const bool go_on = lockstep.edge(cycle, sample_of(o), colour_bits);
    if (waves) {  // the dump after the edge sees the clock high, as before
      dut->set_clock(true);
      dut->eval();
      dump(cycle, t + kWaveUnitsPerCycle / 2);
      dut->set_clock(false);
    } else {
      dut->rising_edge();
    }
    if (!go_on) break;
  }
  dut->final();
  if (waves) dut->close_trace();
  CosimResult r =  // returned: moved
      lockstep.result(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  // The counts live in this run's context: write them before it goes, pass or fail.
  if (!job.coverage_path.empty()) dut->write_coverage(job.coverage_path);
  return r;
}

}  // namespace

int cpp_cosim_main(int argc, char** argv, const BuiltModel& model) {
  CosimExecutable exe = executable_of(model, "cpp", "shadesim cosim --backend cpp");
  exe.run = [&model](const CosimJob& job, const WaveWindow* waves) {
    return run_cpp(job, waves, model);
  };
  return cosim_main_or_error(argc, argv, exe);
}

}  // namespace shadesim
