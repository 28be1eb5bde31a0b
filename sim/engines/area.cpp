// shadesim area's engine (its options: sim/cli/area.cpp): area and timing of one unit configuration
// from Yosys (generic cells, CMOS transistor estimate, iCE40 LUT4/DFF/CARRY) and nextpnr-ice40
// (Fmax on an HX8K where it fits), with the per-module breakdown. sim/engines/area_report.h has the
// flow.
#include "sim/engines/area.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "derive/derive_config.h"
#include "host/frame.h"
#include "host/scene_error.h"
#include "model/command_stream.h"
#include "model/digit_grouping.h"
#include "model/text_file.h"
#include "model/unit_config_file.h"
#include "sim/engines/area_report.h"
#include "sim/engines/unit_choice.h"
#include "sim/engines/unit_power.h"

namespace shadesim {
namespace {

// The unit --config names (sim/engines/unit_choice.h): a build or a file alone, or own (the
// default) or default for the SCENE given.
UnitConfig unit_to_measure(const AreaCommandOptions& o, std::string* source) {
  const std::string choice = o.config_path.empty() ? kOwnUnit : o.config_path;
  if (o.scene.empty() && (choice == kOwnUnit || choice == kDefaultUnit))
    throw std::invalid_argument("area: --config " + choice + " is a scene's unit: give the SCENE");
  std::string origin;
  const RtlConfig unit = resolve_unit(choice, o.scene, "--config", &origin);
  *source = choice == kOwnUnit       ? o.scene + " (its own configuration; " + origin + ")"
            : choice == kDefaultUnit ? o.scene + " (the default widths)"
                                     : choice;
  return unit.unit;
}

void print_report(std::ostream& os, const std::string& source, const UnitConfig& unit,
                  const AreaReport& r) {
  os << "unit         " << unit.to_string() << "  (from " << source << ")\n"
     << "yosys        " << r.yosys_version
     << (r.from_cache ? "  [cached " + r.key + "]" : "  [key " + r.key + "]") << "\n\n"
     << "generic synthesis (synth -flatten; abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX; stat -tech cmos)\n"
     << "  cells        " << std::setw(10) << grouped(r.cells)
     << "   2-input gates, MUXes and flip-flops\n"
     << "  transistors  " << std::setw(10) << grouped(r.transistors)
     << "   CMOS estimate (stat -tech cmos)"
     << (r.transistors_partial ? "; flip-flops not included (Yosys has no CMOS cost for them)" : "")
     << "\n"
     << "  flip-flops   " << std::setw(10) << grouped(r.flip_flops)
     << (r.ram_bits > 0 ? "   of which " + grouped(r.ram_bits) + " hold table RAM bits" : "")
     << "\n";
  os << "  GE           " << std::setw(10) << grouped(r.gate_equivalents())
     << "   NAND2 gate equivalents, a convention (not a library's figure): (transistors less\n"
     << "                          Yosys's flip-flop cost, " << grouped(r.logic_transistors)
     << ") / 4\n"
     << "                          + 6 per flip-flop outside the table RAM ("
     << grouped(r.flip_flops - r.ram_bits) << ")\n"
     << "  RAM bits     " << std::setw(10) << grouped(r.ram_bits)
     << "   table memories ($mem cells' SIZE x WIDTH before memory_map; parameters: "
     << grouped(r.ram_bits_expected) << "),\n"
     << "                          apart from GE: an SRAM macro (iCE40: block RAM), not "
        "flip-flops\n";
  os << "\n";
  if (!r.modules.empty()) {
    os << "where the area goes (same flow, datapath modules kept: " << grouped(r.breakdown_cells)
       << " cells; more than flat, as\n"
       << "Yosys cannot drop logic across a kept boundary; each row includes its submodules)\n"
       << "  " << std::left << std::setw(16) << "module" << std::right << std::setw(5) << "inst"
       << std::setw(11) << "cells each" << std::setw(11) << "cells" << std::setw(8) << "share"
       << std::setw(13) << "transistors" << std::setw(8) << "FFs" << std::setw(10) << "GE"
       << std::setw(8) << "GE %" << std::setw(10) << "RAM bits" << '\n';
  }
  int64_t breakdown_ge = 0;
  for (const auto& m : r.modules) breakdown_ge += m.gate_equivalents();
  for (const auto& m : r.modules) {
    const double pct = r.breakdown_cells ? 100.0 * static_cast<double>(m.cells()) /
                                               static_cast<double>(r.breakdown_cells)
                                         : 0.0;
    const std::string name = m.module == "shade_unit" ? "shade_unit glue" : m.module;
    os << "  " << std::left << std::setw(16) << name << std::right << std::setw(5) << m.instances
       << std::setw(11) << grouped(m.cells_each) << std::setw(11) << grouped(m.cells())
       << std::setw(7) << std::fixed << std::setprecision(1) << pct << "%" << std::setw(13)
       << grouped(m.transistors()) << std::setw(8) << grouped(m.flip_flops_each * m.instances);
    const double ge_pct = breakdown_ge > 0 ? 100.0 * static_cast<double>(m.gate_equivalents()) /
                                                 static_cast<double>(breakdown_ge)
                                           : 0.0;
    os << std::setw(10) << grouped(m.gate_equivalents()) << std::setw(7) << ge_pct << "%"
       << std::setw(10) << grouped(m.ram_bits_each * m.instances);
    os << '\n';
  }
  if (breakdown_ge > 0) {
    os << "  (GE per module from the kept-hierarchy synthesis: " << grouped(breakdown_ge)
       << " GE in all; RAM bits\n   from the parameters, apart from GE)\n";
  }
  os << "\ntiming\n  logic depth  ";
  os << std::setw(10) << r.logic_depth.gates
     << "   levels of 2-input gates, MUXes and inverters on the longest path\n"
     << "                          (Yosys ltp -noff on the flat netlist), from "
     << r.logic_depth.from << "\n                          to " << r.logic_depth.to << "\n";
  os << "\niCE40 (synth_ice40)\n"
     << "  LUT4         " << std::setw(10) << grouped(r.ice40.lut4) << '\n'
     << "  DFF          " << std::setw(10) << grouped(r.ice40.dff) << '\n'
     << "  CARRY        " << std::setw(10) << grouped(r.ice40.carry) << '\n'
     << "  RAM40_4K     " << std::setw(10) << grouped(r.ice40.ram4k) << '\n'
     << "  HX8K         " << r.ice40.fit_note << '\n'
     << "  Fmax         ";
  if (r.ice40.fmax_mhz) {
    os << std::setprecision(1) << *r.ice40.fmax_mhz
       << " MHz (nextpnr-ice40, HX8K ct256, clk_i; out of context: the unit's ports shifted\n"
       << "                          through registers of a shell, so the pin count does not limit "
          "it)\n";
    if (!r.ice40.critical_path.empty())
      os << "  critical     " << r.ice40.critical_path << " (nextpnr's post-route report)\n";
  } else {
    os << "- (" << r.ice40.pnr_note << ")\n";
  }
  for (const auto& w : r.warnings) os << "\nWARNING      " << w << '\n';
  os << "\ntime         " << std::setprecision(1) << r.seconds << " s wall, " << r.cpu_seconds
     << " s CPU of Yosys and nextpnr"
     << (r.from_cache ? " when measured (this run: a cache hit)" : "") << '\n';
}

// The section's title: the library as a designer knows it (osu018 for the default file, else the
// liberty's own name) and the flow.
std::string liberty_title(const LibertyReport& l) {
  const std::string name = l.liberty_path == kDefaultLiberty ? "osu018 0.18 um" : l.library;
  return name + " (Yosys dfflibmap + abc -liberty, fanout-buffered; OpenSTA)";
}

void print_liberty_area(std::ostream& os, const LibertyReport& l) {
  const FanoutBufferResult& b = l.buffering;
  os << "\n"
     << liberty_title(l) << "\n"
     << "  library      " << l.library << "  (" << l.liberty_path << ")\n"
     << "  area         " << std::setw(10) << grouped(std::llround(l.area_um2))
     << "   um^2: the liberty areas of the buffered netlist's cells (no wire load, no\n"
     << "                          placement, the liberty's own corner)\n"
     << "  NAND2 eq.    " << std::setw(10) << grouped(std::llround(l.nand2_equivalents()))
     << "   area / " << l.nand2_cell << "'s " << l.nand2_area_um2 << " um^2 (from the liberty)\n"
     << "  cells        " << std::setw(10) << grouped(l.cells) << "   of which "
     << grouped(b.buffers) << " " << b.buffer_cell << " fanout buffers on "
     << grouped(b.nets_buffered) << " nets over " << b.max_fanout << " cell inputs\n"
     << "  flip-flops   " << std::setw(10) << grouped(l.flip_flops) << "\n";
}

// describe_constraints, a clause a line.
std::string wrapped_constraints(const ResolvedConstraints& c) {
  std::string text = describe_constraints(c);
  for (size_t at; (at = text.find("; ")) != std::string::npos;)
    text.replace(at, 2, ";\n                          ");
  return text;
}

void print_liberty_timing(std::ostream& os, const LibertyReport& l,
                          std::optional<double> cycles_per_pixel) {
  os << std::fixed << std::setprecision(1) << "  Fmax         " << std::setw(10) << l.fmax_mhz
     << "   MHz = 1000 / (" << std::setprecision(3) << l.period_ns << " ns period - worst slack "
     << l.worst_slack_ns << " ns):\n                          arrival " << l.path_arrival_ns
     << " ns (clock-to-Q included) + setup " << l.path_setup_ns << " ns + clock uncertainty "
     << l.constraints.policy.clock_uncertainty_ns << " ns\n"
     << "  constraints  " << wrapped_constraints(l.constraints) << "\n"
     << "  meets        " << std::setw(10) << std::setprecision(1)
     << l.fmax_mhz * (1.0 - l.constraints.policy.guard_band)
     << "   MHz at most, pre-route: Fmax less the " << std::setprecision(0)
     << 100.0 * l.constraints.policy.guard_band << " % guard band\n";
  if (cycles_per_pixel && *cycles_per_pixel > 0) {
    os << "  Mpixel/s     " << std::setw(10) << std::setprecision(1)
       << l.fmax_mhz / *cycles_per_pixel << "   Fmax / " << std::setprecision(3)
       << *cycles_per_pixel
       << " cycles per pixel (the cycle model on the scene: no gaps, no back-pressure)\n";
  }
  os << "  ABC target   " << std::setw(10) << std::setprecision(3) << l.abc_delay_ps / 1000
     << "   ns: the period less " << (l.overhead_cell.empty() ? "-" : l.overhead_cell)
     << "'s clock-to-Q + setup (" << l.flip_flop_overhead_ns << " ns, OpenSTA)\n"
     << "  critical path from " << l.path_from << " to " << l.path_to << " (" << l.path_group
     << ")\n"
     << "     delay     time  cell      instance              net (fanout)\n";
  for (const auto& c : l.path) {
    os << "  " << std::setw(8) << c.delay_ns << std::setw(9) << c.time_ns << "  " << std::left
       << std::setw(9) << c.cell << " " << std::setw(21) << c.instance << " " << c.net
       << (c.fanout >= 0 ? " (" + std::to_string(c.fanout) + ")" : "") << std::right << "\n";
  }
  for (const auto& w : l.warnings) os << "WARNING      " << w << '\n';
  os << "  netlist      " << l.netlist_path << "\n"
     << "  time         " << std::setprecision(1) << l.seconds << " s wall of Yosys, buffering and "
     << "OpenSTA " << l.sta_version
     << (l.from_cache ? " when measured (this run: a cache hit)" : "") << "\n";
}

// The fast estimate (sim/engines/area_report.h) of this unit from the OTHER measured units in the
// cache, beside the measurement: its error against a held-out Yosys run.
void print_estimate_check(std::ostream& os, const UnitConfig& unit, const AreaReport& measured,
                          const std::string& cache_dir) {
  std::vector<AreaReport> others;
  for (auto& a : load_area_reports(cache_dir)) {
    bool same = a.parameters.size() == measured.parameters.size();
    for (size_t i = 0; same && i < a.parameters.size(); ++i) {
      same = a.parameters[i].name == measured.parameters[i].name &&
             a.parameters[i].value == measured.parameters[i].value &&
             a.parameters[i].slots == measured.parameters[i].slots;
    }
    if (!same) others.push_back(std::move(a));
  }
  os << "estimate     ";
  try {
    const AreaEstimate e = estimate_area(unit, others);
    const double err = measured.cells ? 100.0 * static_cast<double>(e.cells - measured.cells) /
                                            static_cast<double>(measured.cells)
                                      : 0.0;
    os << grouped(e.cells) << " cells, " << grouped(e.lut4) << " LUT4";
    os << ", " << grouped(e.gate_equivalents) << " GE";
    os << ": " << e.label() << "; " << std::showpos << std::setprecision(1) << err << std::noshowpos
       << " % cells against this measurement";
    if (measured.gate_equivalents() > 0) {
      os << ", " << std::showpos
         << 100.0 * static_cast<double>(e.gate_equivalents - measured.gate_equivalents()) /
                static_cast<double>(measured.gate_equivalents())
         << std::noshowpos << " % GE";
    }
    os << "\n";
  } catch (const std::exception& ex) {
    os << "- (" << ex.what() << ")\n";
  }
}

// The unit's cycles per pixel on the scene (the closed-form cycle model, as `shadesim cycles`
// counts them: no gaps, no back-pressure); nullopt without a scene.
std::optional<double> cycles_per_pixel(const AreaCommandOptions& o, const UnitConfig& unit) {
  if (o.scene.empty()) return std::nullopt;
  const PreparedScene frame(o.scene,
                            PrepareKey{std::nullopt, FrameOptions{}.max_depth, unit.out_bits});
  return scene_cycles(frame, unit).per_pixel();
}

void write_json_report(const AreaCommandOptions& o, const std::string& source,
                       const UnitConfig& unit, const AreaReport& r, std::optional<double> cycles,
                       const std::optional<AreaPower>& power) {
  nlohmann::json j = nlohmann::json::parse(area_report_to_json(r));
  j["source"] = source;
  j["config"] = nlohmann::json::parse(config_to_json(unit));
  if (r.liberty) {
    j["liberty"]["cycles_per_pixel"] = cycles ? nlohmann::json(*cycles) : nlohmann::json(nullptr);
    j["liberty"]["mpixel_per_s"] =
        cycles ? nlohmann::json(r.liberty->fmax_mhz / *cycles) : nlohmann::json(nullptr);
    j["liberty"]["power"] = nullptr;
    if (power) {
      j["liberty"]["power"] = nlohmann::json::parse(power_report_to_json(power->report));
      j["liberty"]["power"]["key"] = power->key;
      j["liberty"]["pj_per_pixel"] = power->report.pj_per_pixel;
      j["liberty"]["mw_at_fmax"] = power->report.scene.total_mw;
    }
  }
  write_text_file(o.json_path, j.dump(2) + '\n');
}

}  // namespace

int run_area(const AreaCommandOptions& o) {
  std::string source;
  const UnitConfig unit = unit_to_measure(o, &source);
  AreaOptions ao;
  ao.cache_dir = o.cache_dir;
  ao.place_and_route = !o.no_pnr;
  ao.rtl_dir = o.rtl_dir;
  ao.progress = &std::cerr;
  if (!o.no_liberty) {
    ao.liberty = LibertyOptions{};
    ao.liberty->liberty_path = o.liberty;
  }
  const AreaReport r = unit_area(unit, ao);
  const std::optional<double> cycles = cycles_per_pixel(o, unit);
  print_report(std::cout, source, unit, r);
  std::optional<AreaPower> power;
  if (r.liberty) {
    print_liberty_area(std::cout, *r.liberty);
    print_liberty_timing(std::cout, *r.liberty, cycles);
    // Energy needs the scene's activity: a scene, and the power step not switched off.
    // (--rtl-dir: the co-simulation would run this tree's RTL, not DIR's: no energy.)
    if (!o.scene.empty() && !o.no_power && o.rtl_dir.empty()) {
      power = scene_power(unit, o.scene, *r.liberty, o.cache_dir, &std::cerr);
      print_area_power(std::cout, *power);
    } else {
      std::cout << "  energy       - ("
                << (o.scene.empty() ? "no scene: energy needs a scene's switching activity"
                    : o.no_power    ? "--no-power"
                                    : "--rtl-dir: the activity would come from this tree's RTL")
                << ")\n";
    }
  }
  std::cout << "\n";
  print_estimate_check(std::cout, unit, r, o.cache_dir);
  if (!o.json_path.empty()) write_json_report(o, source, unit, r, cycles, power);
  return 0;
}

}  // namespace shadesim
