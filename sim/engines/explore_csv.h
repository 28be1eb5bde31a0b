// shadesim explore --csv: every point, one row each (the run itself: sim/engines/explore.cpp).
#pragma once

#include <string>

#include "explore/explore.h"
#include "sim/engines/explore.h"

namespace shadesim {

// Every point: what it changed, its error, cycles per pixel, estimated area, budget, front and
// chosen flags, then a measured point's library figures as the JSON's `measured` object has them
// (library_area_um2, library_fmax_mhz, library_mpixel_per_s, meets_clock); empty where the point
// was not measured or the figure not taken (meets_clock: 1 or 0, empty without --clock-mhz).
void write_explore_csv(const std::string& path, const ExploreResult& r, int channels,
                       const ExploreJobOptions& o);

}  // namespace shadesim
