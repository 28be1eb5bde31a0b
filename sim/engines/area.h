// shadesim area's engine: area and timing of one unit from Yosys, nextpnr-ice40 and, on a
// standard-cell library, OpenSTA (sim/engines/area.cpp; the flows are sim/engines/area_report.h).
// The command line that fills AreaCommandOptions: sim/cli/area.cpp.
#pragma once

#include <string>

#include "sim/eda/common/build_paths.h"

namespace shadesim {

struct AreaCommandOptions {
  std::string config_path;
  std::string scene;
  std::string cache_dir = binary_dir() + "/area-cache";
  std::string json_path;
  bool no_pnr = false;
  std::string rtl_dir;      // empty: this tree's rtl/
  std::string liberty;      // --liberty FILE; empty: osu018 (kDefaultLiberty)
  bool no_liberty = false;  // --no-liberty: no library mapping, no OpenSTA
  bool no_power = false;    // --no-power: no energy (it co-simulates the scene, traced)
};

// Measures the unit --config names (for the SCENE), prints the report and the estimate's check,
// writes --json; returns the exit code.
int run_area(const AreaCommandOptions& o);

}  // namespace shadesim
