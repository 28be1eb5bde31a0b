// shadesim merge's engine: the regress output folders DIR... reported as one regression
// (sim/regress/merge.cpp says how). The command line that fills MergeOptions: sim/cli/merge.cpp.
#pragma once

#include <string>
#include <vector>

namespace shadesim {

struct MergeOptions {
  std::vector<std::string> dirs;
  std::string json_path;
  std::string junit_path;
};

// Prints the table and summary, writes the reports asked for; returns the exit code (1 when a
// planned run is missing, a run is duplicated or unreadable, or any run failed).
int run_merge(const MergeOptions& o);

}  // namespace shadesim
