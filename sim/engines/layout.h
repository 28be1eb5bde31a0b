// shadesim layout's engine: the unit --config names placed and routed in osu018 with qflow
// (sim/eda/layout/qflow_layout.h), from shadesim area's liberty netlist, with its post-route
// timing, DRC, LVS, GDS and picture. Its options: sim/cli/layout.cpp. docs/layout.md.
#pragma once

#include <string>

#include "sim/eda/common/build_paths.h"

namespace shadesim {

struct LayoutJobOptions {
  std::string config_path;  // own (default) | default | a named build | FILE.json
  std::string scene;
  std::string cache_dir = binary_dir() + "/area-cache";  // shared with shadesim area
  std::string json_path;
  double density = 0.6;
  double clock_mhz = 250;  // the post-route analysis clock (config's default target)
};

// Places and routes, prints the report, writes --json; returns the exit code (0; 1 when a
// check fails: DRC errors, LVS not clean, unannotated nets).
int run_layout(const LayoutJobOptions& o);

}  // namespace shadesim
