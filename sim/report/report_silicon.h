// The Silicon section of `shadesim report`'s page: each unit's area, clock, energy and layout
// (area --json, layout --json) beside its error (render --json) and cycles (cycles --json). A
// unit is its `config`, the UnitConfig every command writes; a report without one is matched by
// its scene.
#pragma once

#include <string>

#include "sim/report/report_page.h"

namespace shadesim {

// The section's body: the summary table, one row per unit, then each unit's figures and its
// layout's picture; a note naming the commands when no area or layout input was given.
std::string silicon_section(const ReportPage& page);

}  // namespace shadesim
