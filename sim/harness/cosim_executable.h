// One Verilated co-simulation executable, as the shared driver (sim/harness/cosim_main.cpp, with
// cosim_options.cpp and cosim_run.cpp) sees it: its backend, the parameters it was Verilated
// with, and how to run a job on its model.
//
// The driver - options, jobs, reports, replay lines, waveform re-runs - and the backends' loops
// do not depend on the Verilated model, so they are compiled once into the harness libraries.
// Each RTL build compiles only its Verilated model and the glue (sim/harness/cosim_glue.cpp),
// whose main hands the model to cpp_cosim_main or sc_cosim_main (sim/harness/verilated_dut.h),
// which fill this in and call cosim_main.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "model/rtl_parameters.h"
#include "sim/harness/cosim.h"
#include "sim/harness/verilated_dut.h"

namespace shadesim {

struct CosimExecutable {
  std::string backend;   // "cpp" or "systemc", as reports name it
  std::string command;   // the shadesim command line that runs this build (replay lines, errors)
  bool traced = false;   // Verilated with FST tracing (--waves)
  bool covered = false;  // Verilated with line/toggle/user coverage (--coverage)
  bool fault_hooks = false;  // can inject the deliberate faults (--fault)
  // The SystemC kernel elaborates once per process: one job per run.
  bool one_job_per_process = false;
  std::vector<VerilogParameter> parameters;  // as Verilated (cosim_build.h)
  // Runs one job on the Verilated model; waves: dump that window (traced builds only, else null).
  // Throws std::invalid_argument when the job cannot run on this build.
  std::function<CosimResult(const CosimJob&, const WaveWindow*)> run;
};

// The executable's main: parses argv, runs the jobs, reports. Exit status: 0 every run passed (or
// the expected mismatch was found), 1 a mismatch, 2 bad input.
int cosim_main(int argc, char** argv, const CosimExecutable& exe);
// cosim_main, with anything it throws printed as "<command>: error: ..." and exit status 2.
int cosim_main_or_error(int argc, char** argv, const CosimExecutable& exe);

// The parameters a build's glue lists, as the driver compares them.
std::vector<VerilogParameter> built_parameters(const BuiltModel& model);
// What every executable of a backend shares: the parameters and coverage from its glue, its
// name and the shadesim command that runs it. The caller adds `run` (and what else differs).
CosimExecutable executable_of(const BuiltModel& model, const std::string& backend,
                              const std::string& command);

// The outputs a backend sampled, as the lockstep block takes them.
inline Lockstep::Sample sample_of(const DutOutputs& o) {
  Lockstep::Sample s;
  s.cmd_ready = o.cmd_ready;
  s.pix_valid = o.pix_valid;
  s.pix_x = o.pix_x;
  s.pix_y = o.pix_y;
  s.pix_mask = o.pix_mask;
  s.pix_eor = o.pix_eor;
  return s;
}

}  // namespace shadesim
