// The picture of a routed layout: drawn from its DEF (sim/eda/layout/layout_reports.h) with the
// project's PNG writer (host/image.h), not by a viewer, so it needs no display and no klayout.
// Cells are filled grey (filler darker), each metal layer's routes a colour of their own, the die
// outlined.
#pragma once

#include <map>
#include <string>

#include "host/image.h"
#include "sim/eda/layout/layout_reports.h"

namespace shadesim {

// The layout at `max_side` pixels on its longer side (the die's aspect kept), top row = top of
// the die.
Image draw_layout(const DefSummary& def, const std::map<std::string, LefSize>& sizes, int max_side);

}  // namespace shadesim
