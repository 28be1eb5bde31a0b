// shadesim config --clock-mhz: the unit timed where it will be built (a standard-cell library
// through OpenSTA, or an iCE40 HX8K through nextpnr; sim/eda/area.h runs both), and the
// pipelining config may add to reach the clock (sim/jobs/clock_target.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "derive/derive_config.h"
#include "model/unit_config.h"

namespace shadesim {

enum class ClockSite { kLiberty, kIce40 };
ClockSite parse_clock_site(const std::string& text, const std::string& what);  // osu018 | ice40
// config's clock target when none is given (issue 44): 250 MHz in a standard-cell library (twice
// the 117.5 Mpixel/s of Lai et al.'s unit at about one pixel per clock), 50 MHz on the iCE40.
double default_clock_mhz(ClockSite site);

struct ClockTarget {
  double mhz = 0;  // 0: no clock target
  ClockSite site = ClockSite::kLiberty;
  std::string liberty;    // the library for kLiberty; empty: osu018
  std::string cache_dir;  // shadesim area's cache
};

// One unit's clock where it is built.
struct ClockTiming {
  UnitConfig unit;
  std::optional<double> fmax_mhz;  // none: the unit was not timed (no fit on the HX8K)
  double area = 0;                 // um^2 in the library, LUT4s on the iCE40
  std::string limit;               // the critical path (library) or why no Fmax (iCE40)
  bool meets(double mhz) const { return fmax_mhz && *fmax_mhz >= mhz; }
};
ClockTiming time_unit(const UnitConfig& unit, const ClockTarget& target);

// What config did for the clock, for its report and --json.
struct ClockOutcome {
  std::vector<ClockTiming> tried;  // the derived unit, then each rung of its ladder timed
  size_t chosen = 0;               // index into `tried`: the cheapest that meets, else fastest
  bool meets = false;
  std::string miss;  // when none meets: the fastest's Fmax and the path that limits it
};
// Times `derived.config`; where it misses the clock, climbs its pipelining ladder
// (pipelining_ladder: the pixel combine's stages, then the W_m squarings'), timing each rung
// until one meets it. `derived` becomes the chosen unit, with a "combine_stages" reason stating
// the figures.
ClockOutcome meet_clock(const FrameSet& frames, const DeriveOptions& options,
                        const ClockTarget& target, DerivedConfig& derived);

std::string site_name(const ClockTarget& target);  // "osu018 0.18 um (OpenSTA)", ...

}  // namespace shadesim
