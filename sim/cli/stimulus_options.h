// The command-line options of a run's stimulus (sim/harness/stimulus.h): idle gaps on the command
// port and back-pressure on the pixel port, with their ranges. `cycles` and `regress` share them.
#pragma once

#include <CLI/CLI.hpp>

#include "sim/regress/regress_stimulus.h"

namespace shadesim {

inline void add_stimulus_options(CLI::App* sub, int& gap_pct, int& max_gap, int& stall_pct) {
  sub->add_option("--gap-pct", gap_pct, "chance of idle cycles before a command word")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  sub->add_option("--max-gap", max_gap, "longest idle gap in cycles")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--stall-pct", stall_pct, "chance of output back-pressure per cycle")
      ->check(CLI::Range(0, 99))
      ->capture_default_str();
}

}  // namespace shadesim
