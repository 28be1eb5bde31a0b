// shadesim area's power step: energy per pixel of the unit's library netlist (the liberty flow's
// buffered osu018 netlist, sim/eda/sta/liberty_flow.h) under the scene's own switching activity
// (sim/eda/power/activity.h: the traced co-simulation of the scene), from OpenSTA's report_power
// (sim/eda/power/power.h), at the flow's Fmax. Cached in the area cache as power-<key>.json, the
// key hashing the liberty flow's key (RTL, parameters, liberty, scripts, tools), the scene file's
// content and the unit. docs/power.md says what is measured and what is left out.
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include "model/unit_config.h"
#include "sim/eda/power/power.h"
#include "sim/eda/sta/liberty_flow.h"

namespace shadesim {

struct AreaPower {
  PowerReport report;
  std::string key;
  bool from_cache = false;
  double seconds = 0;  // wall time of the activity run and OpenSTA when measured
};

// The unit's power on `scene` at the liberty report's Fmax; `progress` gets one line per step.
// Throws std::runtime_error (naming the step) when the co-simulation or OpenSTA fails.
AreaPower scene_power(const UnitConfig& unit, const std::string& scene,
                      const LibertyReport& liberty, const std::string& cache_dir,
                      std::ostream* progress);

// The report's lines (pJ/pixel and mW at Fmax beside the default-activity figures).
void print_area_power(std::ostream& os, const AreaPower& p);

}  // namespace shadesim
