// shadesim explore's engine: width sweeps of the bit-accurate model against error, cycles per
// pixel and area, the cheapest widths meeting a budget and the Pareto front
// (sim/engines/explore.cpp; the search itself is explore/explore.h). The command line that fills
// ExploreJobOptions: sim/cli/explore.cpp.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "sim/eda/common/build_paths.h"
#include "sim/engines/clock_target.h"

namespace shadesim {

struct ExploreJobOptions {
  std::vector<std::string> scenes;
  double budget_lsb = 1.0;
  double setup_budget_lsb = std::nan("");
  int max_depth = 12;
  std::string specular;
  int jobs = 2;
  std::string json_path, csv_path, out_dir;
  std::string config_path;
  std::string area_cache = binary_dir() + "/area-cache";
  int out_bits = 8;
  bool verify = false;
  bool widths_only = false;    // sweep the widths alone: the start's structure throughout
  bool estimate_only = false;  // no Yosys for the front: estimates only, labelled so
  bool no_pnr = false;         // measure the front without nextpnr (no Fmax, no Mpixel/s)
  std::string liberty;         // --liberty FILE for the front's library flow; empty: osu018
  bool no_liberty = false;     // measure the front without the library flow and OpenSTA
  double clock_mhz = 0;        // --clock-mhz: mark the front against it; 0: no clock
  std::string emit_jobs;       // FILE: the verification's regress runs as job lines, not run
  bool quiet = false;
  ClockSite clock_site = ClockSite::kLiberty;  // --clock-target: where --clock-mhz is timed
};

// Chooses the start, sweeps and measures, prints the run, verifies the choice (--verify, or its
// --emit-jobs lines), writes --json and --csv; returns the exit code (0 when a point meets the
// budget and every verification passed, else 1; --clock-mhz is reported, not enforced).
int run_explore(const ExploreJobOptions& o);

}  // namespace shadesim
