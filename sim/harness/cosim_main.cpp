// The co-simulation executable of one RTL build: the Verilated shade_unit (C++, SystemC, or C++
// with FST tracing) against the bit-accurate model (every pixel) and the cycle model (every
// pixel's exit cycle and cmd_ready_o on every cycle); sim/harness/cosim.h states the contract.
// shadesim builds one per parameter set into its cache (sim/eda/verilator/rtl_build.h) and runs it
// through `shadesim cosim`, which passes the unit as a file. This file is the executable's shared
// driver: it hands the command line to the parser (sim/harness/cosim_options.cpp, the only file
// that reads it) and the options to the engine (sim/harness/cosim_run.cpp), all three compiled
// once into libshadesim_harness; each build adds its Verilated model through
// sim/harness/cosim_glue.cpp (sim/harness/cosim_executable.h):
//
//   <exe> --unit unit.json --config grey_s428w --scenario all --seed 1 --runs 3
//   <exe> --stream failing.cmds --seed 5 --gap-pct 30 ...   (replay: the stream names its unit)
//   <exe> --unit unit.json --stream s.cmds --json result.json
//   <exe> --unit unit.json --config fault_lsb --scenario mixed --waves fail.fst   (traced build)
//   <exe> --list [--json]
//
// The unit must map (model/rtl_parameters.h) to exactly the parameters this executable was
// Verilated with; whether it can inject the deliberate faults is compiled in beside them.
//
// Exit status: 0 every run passed (or the expected mismatch was found), 1 a mismatch, 2 bad
// input (unit of another build, unreadable or incompatible stream, bad option).
//
// --json FILE: one object per run (an array when there is more than one run):
//   {config, backend, traced, scenario, seed, stimulus: {gap_pct, max_gap, stall_pct}, passed,
//    cycles, pixels, scanlines, seconds, cycles_per_second,
//    first_mismatch: null | {kind, scanline, y, x, expected, got, cycle, message},
//      kind: pixel | cycle | ready | extra-pixel | hang | timeout (sim/harness/cosim.h says each),
//      before: null | an earlier ready mismatch this one follows from,
//    saved_stream: null | path, replay: null | command line, waves: null | {path, first_cycle,
//    last_cycle}}
// On bad input (exit 2) the file holds {"passed": false, "error": message} when it can be written.
#include <iostream>
#include <string>
#include <vector>

#include "sim/harness/cosim_executable.h"
#include "sim/harness/cosim_options.h"
#include "sim/harness/cosim_run.h"

namespace shadesim {

int cosim_main(int argc, char** argv, const CosimExecutable& exe) {
  const cosim_exe::CommandLine line = cosim_exe::parse_command_line(argc, argv, exe);
  if (line.exit_status) return *line.exit_status;
  if (line.options.list) {
    cosim_exe::print_list(line.options.list_json, exe);
    return 0;
  }
  return cosim_exe::run(line.options, exe);
}

std::vector<VerilogParameter> built_parameters(const BuiltModel& model) {
  std::vector<VerilogParameter> out;
  for (int i = 0; i < model.parameter_count; ++i) {
    const BuiltParameter& p = model.parameters[i];
    if (p.slots) {
      out.emplace_back(p.name, std::vector<int64_t>(p.slots, p.slots + p.slot_count));
    } else {
      out.emplace_back(p.name, p.value);
    }
  }
  return out;
}

CosimExecutable executable_of(const BuiltModel& model, const std::string& backend,
                              const std::string& command) {
  CosimExecutable exe;
  exe.parameters = built_parameters(model);
  exe.covered = model.covered;
  exe.fault_hooks = model.fault_hooks;
  exe.traced = model.traced;
  exe.backend = backend;
  exe.command = command;
  return exe;
}

int cosim_main_or_error(int argc, char** argv, const CosimExecutable& exe) {
  try {
    return cosim_main(argc, argv, exe);
  } catch (const std::exception& e) {
    std::cerr << exe.command << ": error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace shadesim
