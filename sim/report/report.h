// shadesim report's engine: one self-contained HTML page from the JSON the other commands write
// (sim/report/report.cpp). The command line that fills ReportOptions: sim/cli/report.cpp.
#pragma once

#include <string>
#include <vector>

namespace shadesim {

struct ReportOptions {
  std::vector<std::string> inputs;
  std::string out_dir = "out/report";
  std::string run;  // "all", or a comma list of render, cycles, spec-error, explore, regress
};

// Runs the --run steps, reads the inputs, draws the plots and writes index.html into out_dir;
// returns the exit code (1 when an input is missing or malformed, or a plot or a --run step
// failed).
int run_report(const ReportOptions& o);

}  // namespace shadesim
