#include "sim/engines/explore_front.h"

#include <fmt/format.h>

#include <algorithm>
#include <iostream>

#include "sim/eda/common/flow_tools.h"
#include "sim/engines/area_report.h"

namespace shadesim {
namespace {

// How the table and the verdict name the library: as a designer knows the default one, else by
// the liberty's own name.
std::string library_label(const LibertyReport& l) {
  return l.liberty_path == kDefaultLiberty ? "osu018" : l.library;
}

void fill_library(const LibertyReport& l, MeasuredArea& m) {
  m.library = library_label(l);
  m.library_fmax_mhz = l.fmax_mhz;
  m.library_area_um2 = l.area_um2;
  m.library_critical_path = l.path_from + " -> " + l.path_to;
}

std::string site_of(const ExploreJobOptions& o) {
  ClockTarget t;
  t.mhz = o.clock_mhz;
  t.site = o.clock_site;
  t.liberty = o.liberty;
  return site_name(t);
}

std::string figure(const std::optional<double>& v) {
  return v ? fmt::format("{:.1f}", *v) : std::string("-");
}

nlohmann::json or_null(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

// The library's name for the column heads: from the measurements, else from the options.
std::string table_library(const ExploreResult& r, const ExploreJobOptions& o) {
  for (const auto& p : r.points)
    if (p.measured && !p.measured->library.empty()) return p.measured->library;
  return o.liberty.empty() ? "osu018" : "library";
}

void print_front_title(std::ostream& os, const std::string& lib, const ExploreJobOptions& o) {
  os << "Pareto front, Yosys-measured (shadesim area on each point)\n"
     << "  iCE40   Fmax from nextpnr-ice40 on an HX8K, out of context"
     << (o.no_pnr ? " - not run (--no-pnr)" : "") << "\n"
     << "  " << fmt::format("{:<7}", lib) << " Fmax = 1000 / ("
     << fmt::format("{:g}", LibertyOptions{}.period_ns)
     << " ns - worst slack), OpenSTA on the unit mapped onto "
     << (o.liberty.empty() ? "osu018 0.18 um" : o.liberty) << " (docs/area.md)"
     << (o.no_liberty ? " - not run (--no-liberty)" : "") << "\n"
     << "  Mp/s    Mpixel/s = that Fmax / cyc/px\n";
  if (o.clock_mhz > 0) {
    os << "  clock   whether the " << (o.clock_site == ClockSite::kIce40 ? "iCE40" : lib)
       << " Fmax meets " << fmt::format("{:g}", o.clock_mhz)
       << " MHz (--clock-mhz; in a library with the pre-route guard band of docs/area.md;"
       << " reported, not enforced)\n";
  }
}

}  // namespace

MeasureFunction front_measure(const ExploreJobOptions& o) {
  std::optional<LibertyOptions> library;
  if (!o.no_liberty) {
    library = LibertyOptions{};
    library->liberty_path = resolve_liberty(o.liberty);
    (void)flow_tools::find_tool(library->sta, "opensta");
  }
  return [o, library](const UnitConfig& c) {
    AreaOptions ao;
    ao.cache_dir = o.area_cache;
    ao.place_and_route = !o.no_pnr;
    ao.breakdown = false;
    ao.liberty = library;
    ao.progress = o.quiet ? nullptr : &std::cerr;
    const AreaReport a = unit_area(c, ao);
    MeasuredArea m;
    m.cells = static_cast<double>(a.cells);
    m.gate_equivalents = static_cast<double>(a.gate_equivalents());
    m.lut4 = static_cast<double>(a.ice40.lut4);
    m.fits_hx8k = a.ice40.fits_hx8k;
    m.fmax_mhz = a.ice40.fmax_mhz;
    m.logic_depth = a.logic_depth.gates;
    m.note = a.ice40.fmax_mhz ? a.ice40.fit_note : a.ice40.pnr_note;
    m.critical_path = a.ice40.critical_path;
    if (a.liberty) fill_library(*a.liberty, m);
    return m;
  };
}

std::vector<std::size_t> measured_front_rows(const ExploreResult& r) {
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < r.points.size(); ++i)
    if (r.points[i].measured && (r.points[i].pareto || (r.chosen && *r.chosen == i)))
      rows.push_back(i);
  std::stable_sort(rows.begin(), rows.end(), [&](std::size_t a, std::size_t b) {
    return r.points[a].front_area() < r.points[b].front_area();
  });
  return rows;
}

std::optional<double> clock_fmax(const ExplorePoint& p, ClockSite site) {
  if (!p.measured) return std::nullopt;
  return site == ClockSite::kIce40 ? p.measured->fmax_mhz : p.measured->library_fmax_mhz;
}

std::optional<bool> meets_clock(const ExplorePoint& p, const ExploreJobOptions& o) {
  if (!(o.clock_mhz > 0) || !p.measured) return std::nullopt;
  const std::optional<double> f = clock_fmax(p, o.clock_site);
  ClockTarget target;
  target.mhz = o.clock_mhz;
  target.site = o.clock_site;
  return f && *f >= required_mhz(target);
}

// Yosys's cells beside the estimate, GE, LUT4s, depth, then each site's Fmax and Mpixel/s.
void print_measured_front(std::ostream& os, const ExploreResult& r, const ExploreJobOptions& o) {
  const std::string lib = table_library(r, o);
  print_front_title(os, lib, o);
  const std::string clock_head = fmt::format("{:g} MHz", o.clock_mhz);
  os << fmt::format(
            "{:<6}{:<22}{:<8}{:>8}{:>8}{:>10}{:>10}{:>8}{:>9}{:>8}{:>7}{:>11}{:>11}{:>12}{:>12}",
            "point", "knob", "value", "max LSB", "cyc/px", "est cells", "cells", "est err", "GE",
            "LUT4", "depth", "iCE40 MHz", "iCE40 Mp/s", lib + " MHz", lib + " Mp/s")
     << (o.clock_mhz > 0 ? fmt::format("{:>11}", clock_head) : std::string()) << "\n";
  for (const std::size_t i : measured_front_rows(r)) {
    const ExplorePoint& p = r.points[i];
    const MeasuredArea& m = *p.measured;
    const double err = m.cells > 0 ? 100.0 * (p.figures.area.cells / m.cells - 1.0) : 0.0;
    os << fmt::format(
              "{:<6}{:<22}{:<8}{:>8}{:>8.3f}{:>10.0f}{:>10.0f}{:>+7.1f}%{:>9.0f}{:>8.0f}{:>7}", i,
              p.knob.empty() ? p.phase : p.knob, p.value.empty() ? "-" : p.value,
              p.figures.error.max_code_lsb, p.figures.cycles_per_pixel, p.figures.area.cells,
              m.cells, err, m.gate_equivalents, m.lut4, m.logic_depth)
       << fmt::format("{:>11}{:>11}{:>12}{:>12}", figure(m.fmax_mhz), figure(p.mpixel_per_s()),
                      figure(m.library_fmax_mhz), figure(p.library_mpixel_per_s()));
    if (const std::optional<bool> meets = meets_clock(p, o))
      os << fmt::format("{:>11}", *meets ? "meets" : "misses");
    os << (r.chosen && *r.chosen == i ? "  CHOSEN" : "") << (p.pareto ? "" : "  (off the front)")
       << "\n";
  }
  const EstimateError e = estimate_error(r);
  os << fmt::format(
      "estimate vs Yosys on these {} points: median |error| {:.1f} %, max {:.1f} % (generic "
      "cells; the sweep's other points carry estimates only)\n",
      e.count, e.median_pct, e.max_pct);
}

namespace {

// No point within the budget meets the clock: the fastest on the site and what limits it.
std::string clock_miss(const ExploreResult& r, const ExploreJobOptions& o,
                       const std::vector<std::size_t>& rows, const std::string& at) {
  std::optional<std::size_t> fastest, cheapest_meeting;
  for (const std::size_t i : rows) {
    const std::optional<double> f = clock_fmax(r.points[i], o.clock_site);
    if (f && (!fastest || *f > *clock_fmax(r.points[*fastest], o.clock_site))) fastest = i;
    if (!cheapest_meeting && meets_clock(r.points[i], o).value_or(false)) cheapest_meeting = i;
  }
  if (cheapest_meeting) {
    const ExplorePoint& p = r.points[*cheapest_meeting];
    return fmt::format(
        "no measured point meets both max {:g} LSB and {}: the cheapest that meets the clock is "
        "point {} (max {} LSB, {:.1f} MHz)",
        o.budget_lsb, at, *cheapest_meeting, p.figures.error.max_code_lsb,
        *clock_fmax(p, o.clock_site));
  }
  if (!fastest) {
    const std::string why =
        rows.empty() ? std::string("no point was measured") : r.points[rows.front()].measured->note;
    return fmt::format("no measured point meets {}: none has an Fmax there ({})", at, why);
  }
  const MeasuredArea& m = *r.points[*fastest].measured;
  // A cache entry from before nextpnr's path was recorded has none to name.
  const std::string path =
      o.clock_site == ClockSite::kLiberty ? "its critical path " + m.library_critical_path
      : m.critical_path.empty()
          ? "its post-route critical path (nextpnr-ice40; not in this cache entry)"
          : "its critical path " + m.critical_path + " (nextpnr-ice40, post-route)";
  return fmt::format(
      "no measured point meets {}: the fastest is point {} at {:.1f} MHz, limited "
      "by {}",
      at, *fastest, *clock_fmax(r.points[*fastest], o.clock_site), path);
}

}  // namespace

ClockVerdict clock_verdict(const ExploreResult& r, const ExploreJobOptions& o) {
  const std::string at = fmt::format("{:g} MHz on {}", o.clock_mhz, site_of(o));
  const std::vector<std::size_t> rows = measured_front_rows(r);
  ClockVerdict v;
  for (const std::size_t i : rows) {
    const ExplorePoint& p = r.points[i];
    if (!p.meets_budget || !meets_clock(p, o).value_or(false)) continue;
    // On a tie in area the chosen point, the one explore recommends, is the one named.
    if (!v.point ||
        (r.chosen && i == *r.chosen && p.front_area() == r.points[*v.point].front_area()))
      v.point = i;
  }
  if (!v.point) {
    v.line = clock_miss(r, o, rows, at);
    return v;
  }
  const ExplorePoint& p = r.points[*v.point];
  const std::optional<double> mpix =
      o.clock_site == ClockSite::kIce40 ? p.mpixel_per_s() : p.library_mpixel_per_s();
  v.line = fmt::format(
      "point {} meets {}: the cheapest measured point within max {:g} LSB that does (Fmax {:.1f} "
      "MHz, {} Mpixel/s, {:.0f} cells)",
      *v.point, at, o.budget_lsb, *clock_fmax(p, o.clock_site), figure(mpix), p.front_area());
  return v;
}

nlohmann::json measured_json(const ExplorePoint& p, const ExploreJobOptions& o) {
  const MeasuredArea& m = *p.measured;
  const std::optional<bool> meets = meets_clock(p, o);
  return {{"cells", m.cells},
          {"gate_equivalents", m.gate_equivalents},
          {"lut4", m.lut4},
          {"fits_hx8k", m.fits_hx8k},
          {"fmax_mhz", or_null(m.fmax_mhz)},
          {"mpixel_per_s", or_null(p.mpixel_per_s())},
          {"logic_depth", m.logic_depth},
          {"note", m.note},
          {"ice40_critical_path",
           m.critical_path.empty() ? nlohmann::json(nullptr) : nlohmann::json(m.critical_path)},
          {"library", m.library.empty() ? nlohmann::json(nullptr) : nlohmann::json(m.library)},
          {"library_fmax_mhz", or_null(m.library_fmax_mhz)},
          {"library_mpixel_per_s", or_null(p.library_mpixel_per_s())},
          {"library_area_um2", or_null(m.library_area_um2)},
          {"library_critical_path", m.library_critical_path.empty()
                                        ? nlohmann::json(nullptr)
                                        : nlohmann::json(m.library_critical_path)},
          {"meets_clock", meets ? nlohmann::json(*meets) : nlohmann::json(nullptr)}};
}

nlohmann::json clock_json(const ExploreResult& r, const ExploreJobOptions& o) {
  if (!(o.clock_mhz > 0)) return nullptr;
  const ClockVerdict v = clock_verdict(r, o);
  return {{"mhz", o.clock_mhz},
          {"target", o.clock_site == ClockSite::kIce40 ? "ice40" : "osu018"},
          {"site", site_of(o)},
          {"point", v.point ? nlohmann::json(*v.point) : nlohmann::json(nullptr)},
          {"summary", v.line}};
}

}  // namespace shadesim
