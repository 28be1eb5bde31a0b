// One Verilated co-simulation executable, as the shared driver (sim/harness/cosim_main.cpp) sees
// it: its backend, the parameters it was Verilated with, and how to run a job on its model.
//
// The driver - options, jobs, reports, replay lines, waveform re-runs - does not depend on the
// Verilated model, so it is compiled once into libshadesim_harness. Each RTL build compiles only
// its Verilated model and sim/harness/cosim_adapter.cpp, which fills this in and calls
// cosim_main. (The driver in every build cost 17 s of compiler time, half of a build.)
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "model/rtl_parameters.h"
#include "sim/harness/cosim.h"

namespace shadesim {

struct CosimExecutable {
  std::string backend;   // "cpp" or "systemc", as reports name it
  std::string command;   // the shadesim command line that runs this build (replay lines, errors)
  bool traced = false;   // Verilated with FST tracing (--waves)
  bool covered = false;  // Verilated with line/toggle/user coverage (--coverage)
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

}  // namespace shadesim
