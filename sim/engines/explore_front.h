// shadesim explore's measured front (the search is sim/engines/explore.cpp): each Pareto point
// measured by shadesim area (Yosys's generic cells, nextpnr-ice40's Fmax out of context, the unit
// on a standard-cell library timed by OpenSTA), its table, its JSON, and --clock-mhz's verdict.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "explore/explore.h"
#include "sim/engines/explore.h"

namespace shadesim {

// shadesim area on a point's unit, cached like `area`. The library and OpenSTA are looked up
// here, before the sweep, so a missing one stops explore before minutes of model runs.
MeasureFunction front_measure(const ExploreJobOptions& o);

// The measured points the table shows: on the front, and the chosen one; by front area.
std::vector<std::size_t> measured_front_rows(const ExploreResult& r);

// The point's Fmax where --clock-target times it; none where it was not measured there.
std::optional<double> clock_fmax(const ExplorePoint& p, ClockSite site);
// Whether the point meets --clock-mhz; none without a clock or a measurement.
std::optional<bool> meets_clock(const ExplorePoint& p, const ExploreJobOptions& o);

void print_measured_front(std::ostream& os, const ExploreResult& r, const ExploreJobOptions& o);

// --clock-mhz's one line: the cheapest measured front point within the budget that meets the
// clock, else the fastest and the path that limits it.
struct ClockVerdict {
  std::optional<std::size_t> point;  // the cheapest that meets the budget and the clock
  std::string line;
};
ClockVerdict clock_verdict(const ExploreResult& r, const ExploreJobOptions& o);

// A measured point's "measured" object and the run's "clock" object (null without --clock-mhz).
nlohmann::json measured_json(const ExplorePoint& p, const ExploreJobOptions& o);
nlohmann::json clock_json(const ExploreResult& r, const ExploreJobOptions& o);

}  // namespace shadesim
