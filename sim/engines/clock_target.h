// shadesim config --clock-mhz: the unit timed where it will be built (a standard-cell library
// through OpenSTA, or an iCE40 HX8K through nextpnr; sim/engines/area_report.h runs both), and the
// pipelining config may add to reach the clock (sim/engines/clock_target.cpp).
#pragma once

#include <string>

#include "derive/derive_config.h"
#include "derive/pipelining.h"
#include "model/unit_config.h"

namespace shadesim {

enum class ClockSite { kLiberty, kIce40 };
ClockSite parse_clock_site(const std::string& text, const std::string& what);  // osu018 | ice40
// config's clock target when none is given: 250 MHz in a standard-cell library (twice
// the 117.5 Mpixel/s of Lai et al.'s unit at about one pixel per clock), 50 MHz on the iCE40.
double default_clock_mhz(ClockSite site);

struct ClockTarget {
  double mhz = 0;  // 0: no clock target
  ClockSite site = ClockSite::kLiberty;
  std::string liberty;    // the library for kLiberty; empty: osu018
  std::string cache_dir;  // shadesim area's cache
};

// The Fmax a unit needs to meet `target`: in a library, its clock over (1 - the guard band of
// sim/eda/sta/sta_constraints.h), since OpenSTA's figure is pre-route; on the iCE40 (nextpnr,
// post-route) the clock itself.
double required_mhz(const ClockTarget& target);

ClockTiming time_unit(const UnitConfig& unit, const ClockTarget& target);

// Times `derived.config` where `target` says; where it misses the clock, climbs its pipelining
// ladder (climb_ladder, derive/pipelining.h), each rung timed by time_unit. `derived` becomes the
// chosen unit, with a "combine_stages" reason stating the figures.
ClockOutcome meet_clock(const FrameSet& frames, const DeriveOptions& options,
                        const ClockTarget& target, DerivedConfig& derived);

std::string site_name(const ClockTarget& target);  // "osu018 0.18 um (OpenSTA)", ...

}  // namespace shadesim
