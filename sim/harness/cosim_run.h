// The co-simulation executable's engine (sim/harness/cosim_main.cpp states its contract): the runs
// its options name, and --list. It reads no command line: cosim_options.h parses that.
#pragma once

#include "sim/harness/cosim_executable.h"
#include "sim/harness/cosim_options.h"

namespace shadesim::cosim_exe {

// Runs the jobs the options name, printing a line per run. Exit status: 0 every run passed (or
// the expected mismatch was found), 1 a mismatch, 2 bad input, printed as "<command>: error: ..."
// and, with --json FILE, written there as {"passed": false, "error": ...} when it can be.
int run(const Options& o, const CosimExecutable& exe);

// --list: the parameters this executable was Verilated with (json: with backend, traced, covered
// and fault_hooks, as JSON).
void print_list(bool json, const CosimExecutable& exe);

}  // namespace shadesim::cosim_exe
