// shadesim spec-error's engine: speed against error of the specular units, with the reproduced
// paper figures (sim/engines/spec_error.cpp). The command line that fills SpecErrorOptions:
// sim/cli/spec_error.cpp.
#pragma once

#include <string>

namespace shadesim {

struct SpecErrorOptions {
  std::string exponents = "1-1000";  // numbers, ranges a-b, a-b:step, comma-separated
  std::string units = "all";         // all, or a comma list of unit names
  int points = 256;                  // sample points per zone per exponent (16..1000000)
  std::string json, csv, plot;       // output files; empty: not written
  bool no_papers = false;            // skip the Bishop and Romanyuk reproductions
};

// Checks the exponents, points and units (std::invalid_argument naming the option), sweeps every
// unit over the exponents, prints the table (and the paper figures), writes --json, --csv and
// --plot; returns the exit code.
int run_spec_error(const SpecErrorOptions& o);

}  // namespace shadesim
