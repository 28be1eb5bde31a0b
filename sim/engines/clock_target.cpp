#include "sim/engines/clock_target.h"

#include <fmt/format.h>

#include <iostream>
#include <stdexcept>

#include "sim/eda/sta/sta_constraints.h"
#include "sim/engines/area_report.h"

namespace shadesim {

ClockSite parse_clock_site(const std::string& text, const std::string& what) {
  if (text == "osu018") return ClockSite::kLiberty;
  if (text == "ice40") return ClockSite::kIce40;
  throw std::invalid_argument(what + ": expected osu018 or ice40, got '" + text + "'");
}

double default_clock_mhz(ClockSite site) { return site == ClockSite::kIce40 ? 50.0 : 250.0; }

std::string site_name(const ClockTarget& target) {
  if (target.site == ClockSite::kIce40) return "iCE40 HX8K (Yosys synth_ice40, nextpnr-ice40)";
  return (target.liberty.empty() ? std::string("osu018 0.18 um") : target.liberty) +
         " (Yosys + abc -liberty, OpenSTA)";
}

namespace {

std::string clock_path_limit(const LibertyReport& l) {
  return fmt::format(
      "critical path {} -> {} ({}): arrival {:.3f} ns + setup {:.3f} ns + clock uncertainty "
      "{:g} ns",
      l.path_from, l.path_to, l.path_group, l.path_arrival_ns, l.path_setup_ns,
      l.constraints.policy.clock_uncertainty_ns);
}

}  // namespace

double required_mhz(const ClockTarget& target) {
  // nextpnr's Fmax is post-route; OpenSTA's is a synthesis estimate, which the guard band covers.
  return target.site == ClockSite::kLiberty ? required_fmax_mhz(target.mhz) : target.mhz;
}

ClockTiming time_unit(const UnitConfig& unit, const ClockTarget& target) {
  AreaOptions ao;
  ao.cache_dir = target.cache_dir;
  ao.breakdown = false;
  ao.progress = &std::cerr;
  ao.place_and_route = target.site == ClockSite::kIce40;
  if (target.site == ClockSite::kLiberty) {
    ao.liberty = LibertyOptions{};
    ao.liberty->liberty_path = resolve_liberty(target.liberty);
  }
  const AreaReport r = unit_area(unit, ao);
  ClockTiming t;
  t.unit = unit;
  if (target.site == ClockSite::kLiberty) {
    t.fmax_mhz = r.liberty->fmax_mhz;
    t.area = r.liberty->area_um2;
    t.limit = clock_path_limit(*r.liberty);
  } else {
    t.fmax_mhz = r.ice40.fmax_mhz;
    t.area = static_cast<double>(r.ice40.lut4);
    if (!r.ice40.fmax_mhz) {
      t.limit = r.ice40.pnr_note + " (" + r.ice40.fit_note + ")";
    } else if (r.ice40.critical_path.empty()) {
      t.limit =
          "nextpnr-ice40's post-route critical path (not in this cache entry: its log is "
          "gone; run with a fresh --area-cache)";
    } else {
      t.limit = "critical path " + r.ice40.critical_path + " (nextpnr-ice40, post-route)";
    }
  }
  return t;
}

namespace {

std::string clock_figures(const ClockTiming& t, const ClockTarget& target) {
  const std::string area = target.site == ClockSite::kIce40 ? fmt::format("{:.0f} LUT4", t.area)
                                                            : fmt::format("{:.0f} um^2", t.area);
  return (t.fmax_mhz ? fmt::format("Fmax {:.1f} MHz", *t.fmax_mhz) : std::string("no Fmax")) +
         ", " + area;
}

}  // namespace

ClockOutcome meet_clock(const FrameSet& frames, const DeriveOptions& options,
                        const ClockTarget& target, DerivedConfig& derived) {
  RungTimer timer;
  timer.mhz = target.mhz;
  timer.required_mhz = required_mhz(target);
  timer.at = target.site == ClockSite::kLiberty
                 ? fmt::format("{:g} MHz (Fmax {:.1f} MHz with the pre-route guard band) on {}",
                               target.mhz, timer.required_mhz, site_name(target))
                 : fmt::format("{:g} MHz on {}", target.mhz, site_name(target));
  timer.time = [&target](const UnitConfig& unit) { return time_unit(unit, target); };
  timer.figures = [&target](const ClockTiming& t) { return clock_figures(t, target); };
  return climb_ladder(frames, options, timer, derived);
}

}  // namespace shadesim
