// shadesim area's engine: area and timing of one unit from Yosys and nextpnr-ice40
// (sim/eda/area_job.cpp; the flow is sim/eda/area.h). The command line that fills AreaJobOptions:
// sim/cli/area.cpp.
#pragma once

#include <string>

namespace shadesim {

struct AreaJobOptions {
  std::string config_path;
  std::string scene;
  std::string cache_dir = SHADESIM_BINARY_DIR "/area-cache";
  std::string json_path;
  bool no_pnr = false;
  std::string rtl_dir;  // empty: this tree's rtl/
};

// Measures the unit --config names (for the SCENE), prints the report and the estimate's check,
// writes --json; returns the exit code.
int run_area(const AreaJobOptions& o);

}  // namespace shadesim
