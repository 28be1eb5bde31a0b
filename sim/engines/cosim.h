// The engines of shadesim cosim, rtl-build and rtl-params: co-simulation of any unit
// configuration, with the RTL Verilated on demand into the build cache
// (sim/eda/verilator/rtl_build.h); sim/engines/cosim.cpp. The command lines that fill their
// options: sim/cli/cosim.cpp.
#pragma once

#include <string>
#include <vector>

namespace shadesim {

struct CosimOptions {
  std::string backend = "cpp";
  std::string config;  // a named build or a UnitConfig FILE.json
  std::string stream;
  std::string waves;
  std::string cache;
  std::string coverage;       // FILE.dat: run the covered build, write its coverage there
  std::string optimization;   // quick | fast; empty: by the run's length (cosim_optimization)
  bool netlist = false;       // Yosys's gate-level netlist in place of the RTL
  std::string netlist_cache;  // empty: <build>/netlist-cache
  bool list = false;
  bool list_json = false;
  std::vector<std::string> passthrough;  // the options the co-simulation itself reads
};

// --list, or builds (or finds) the unit's executable and execs it with the passthrough options:
// returns only for --list or by throwing (after writing a --json among the passthrough options
// that says why).
int run_cosim(const CosimOptions& o);

struct RtlBuildCommandOptions {
  std::vector<std::string> configs;
  bool all = false;
  bool runtime = false;
  std::string optimization = "fast";
  std::vector<std::string> backends;
  std::string cache;
  int jobs = 0;
  bool print_key = false;
  bool coverage = false;
  bool print_source_dir = false;
  bool print_rtl_sources = false;
  // The named builds' fault-hook variants, as runs that inject a fault use them (build_for_run);
  // without it, every build as the other runs use it.
  bool fault_hooks = false;
};

// Builds the executables asked for (or prints their keys, the checkout, the RTL sources);
// returns the exit code (1 when a build failed).
int run_rtl_build(const RtlBuildCommandOptions& o);

struct RtlParamsOptions {
  std::string config;              // a named build or a UnitConfig FILE.json
  std::string tool = "verilator";  // verilator, iverilog or yosys
};

// Prints shade_unit's Verilog parameters for the configuration in the tool's syntax; returns 0.
int run_rtl_params(const RtlParamsOptions& o);

}  // namespace shadesim
