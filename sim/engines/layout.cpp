#include "sim/engines/layout.h"

#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "model/digit_grouping.h"
#include "model/text_file.h"
#include "model/unit_config_file.h"
#include "sim/eda/common/flow_tools.h"
#include "sim/eda/layout/qflow_layout.h"
#include "sim/engines/area_report.h"
#include "sim/engines/unit_choice.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

UnitConfig unit_to_lay_out(const LayoutJobOptions& o, std::string* source) {
  const std::string choice = o.config_path.empty() ? kOwnUnit : o.config_path;
  if (o.scene.empty() && (choice == kOwnUnit || choice == kDefaultUnit))
    throw std::invalid_argument("layout: --config " + choice +
                                " is a scene's unit: give the SCENE");
  std::string origin;
  const RtlConfig unit = resolve_unit(choice, o.scene, "--config", &origin);
  *source = choice == kOwnUnit ? o.scene + " (its own configuration; " + origin + ")" : choice;
  return unit.unit;
}

// shadesim area's liberty flow (cached there): the mapped, buffered netlist.
LibertyReport liberty_netlist(const UnitConfig& unit, const LayoutJobOptions& o) {
  AreaOptions ao;
  ao.cache_dir = o.cache_dir;
  ao.place_and_route = false;
  ao.breakdown = false;
  ao.liberty = LibertyOptions{};
  ao.progress = &std::cerr;
  const AreaReport a = unit_area(unit, ao);
  if (!a.liberty) throw std::runtime_error("layout: shadesim area gave no liberty netlist");
  return *a.liberty;
}

LayoutReport cached_or_run(const LibertyReport& lib, const LayoutFlowOptions& fo,
                           const std::string& cache_dir) {
  const LayoutTools tools = find_layout_tools(fo);
  const std::string key = layout_key(lib, fo, tools);
  const fs::path out_dir = fs::absolute(fs::path(cache_dir) / ("layout-" + key));
  const fs::path entry = out_dir / "report.json";
  if (fs::exists(entry)) {
    LayoutReport r = layout_report_from_json(read_text_file(entry.string()), entry.string());
    r.from_cache = true;
    return r;
  }
  const fs::path work = flow_tools::make_work_folder(cache_dir, "layout-" + key);
  std::cerr << "[layout] qflow project in " << work.string() << "\n";
  LayoutReport r = run_qflow_layout(lib, fo, tools, fs::absolute(work), out_dir, &std::cerr);
  r.key = key;
  flow_tools::write_atomically(entry, layout_report_to_json(r) + "\n");
  std::error_code ec;
  fs::remove_all(work, ec);  // kept only when a step threw (its logs say why)
  return r;
}

void print_report(std::ostream& os, const std::string& source, const UnitConfig& unit,
                  const LibertyReport& lib, const LayoutReport& r) {
  os << std::fixed << std::setprecision(1);
  os << "unit         " << unit.to_string() << "  (from " << source << ")\n"
     << "layout       osu018 0.18 um, qflow (graywolf, qrouter, rc2dly, magic, netgen)"
     << (r.from_cache ? "  [cached " : "  [key ") << r.key << "]\n\n"
     << "area\n"
     << "  die          " << r.die_width_um << " x " << r.die_height_um
     << " um = " << std::setprecision(4) << r.die_area_um2 / 1e6 << " mm^2" << std::setprecision(1)
     << " (at initial density " << std::setprecision(2) << r.density << std::setprecision(1)
     << ")\n"
     << "  core         " << grouped(std::llround(r.core_area_um2))
     << " um^2 (the placed rows' extent); cells " << grouped(std::llround(r.cell_area_um2))
     << " um^2: utilisation " << 100 * r.utilisation << " %\n"
     << "  cells        " << grouped(r.cells) << " (+ " << grouped(r.fill_cells) << " FILL), "
     << r.pins << " pins, " << grouped(r.nets) << " nets\n"
     << "routing\n"
     << "  wire length  " << grouped(std::llround(r.wire_length_um)) << " um (";
  bool first = true;
  for (const auto& [layer, um] : r.wire_length_by_layer_um) {
    os << (first ? "" : ", ") << layer << " " << grouped(std::llround(um));
    first = false;
  }
  os << ")\n  vias         " << grouped(r.vias) << "\n"
     << "post-route timing (OpenSTA with the routed SPEF, shadesim area's constraints)\n"
     << "  annotated    " << r.spef_nets << " SPEF nets for " << r.netlist_nets
     << " connected nets: " << r.unannotated_nets << " unannotated; " << r.spef_warnings
     << " OpenSTA warnings on the SPEF\n";
  for (const auto& n : r.unannotated) os << "               unannotated: " << n << "\n";
  os << std::setprecision(3) << "  clock        " << 1000.0 / r.period_ns << " MHz (" << r.period_ns
     << " ns): worst slack " << r.worst_slack_ns << " ns, "
     << (r.worst_slack_ns >= 0 ? "met" : "MISSED") << "\n"
     << std::setprecision(1) << "  Fmax         " << r.fmax_mhz << " MHz post-route; "
     << r.preroute_fmax_mhz
     << " MHz on the same netlist without wires; shadesim area: " << lib.fmax_mhz << " MHz\n"
     << std::setprecision(3) << "  critical     " << r.path_from << " -> " << r.path_to << " ("
     << r.path_group << "): arrival " << r.path_arrival_ns << " ns + setup " << r.path_setup_ns
     << " ns, of which wires " << r.path_wire_delay_ns << " ns\n"
     << "     delay     time  cell      pin                   net (fanout)\n";
  for (const auto& c : r.path) {
    os << "  " << std::setw(8) << c.delay_ns << std::setw(9) << c.time_ns << "  " << std::left
       << std::setw(9) << c.cell << " ";
    if (c.net.empty()) {
      os << c.instance << std::right << "\n";  // an input pin: its wire's delay, no net row
      continue;
    }
    os << std::setw(21) << c.instance << " " << c.net
       << (c.fanout >= 0 ? " (" + std::to_string(c.fanout) + ")" : "") << std::right << "\n";
  }
  os << "checks\n"
     << "  DRC          " << r.drc_errors << " magic errors" << (r.drc_errors == 0 ? "" : "  <<")
     << "\n";
  for (const auto& k : r.drc_kinds) os << "               " << k << "\n";
  os << "  LVS          " << (r.lvs_clean ? "clean" : "NOT CLEAN") << " (netgen: " << r.lvs_verdict
     << (r.lvs_errors >= 0 ? "; count_lvs total errors " + std::to_string(r.lvs_errors) : "")
     << ")\n"
     << "files\n"
     << "  GDS          " << r.gds_path << "\n"
     << "  PNG          " << r.png_path << "\n"
     << "  DEF          " << r.def_path << "\n"
     << "  SPEF         " << r.spef_path << "\n";
  os << std::setprecision(1) << "time         " << r.seconds << " s wall (";
  first = true;
  for (const auto& [step, s] : r.step_seconds) {
    os << (first ? "" : ", ") << step << " " << s;
    first = false;
  }
  os << ")" << (r.from_cache ? " when measured (this run: a cache hit)" : "") << "\n";
}

}  // namespace

int run_layout(const LayoutJobOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string source;
  const UnitConfig unit = unit_to_lay_out(o, &source);
  if (o.clock_mhz <= 0) throw std::invalid_argument("layout: --clock-mhz must be positive");
  const LibertyReport lib = liberty_netlist(unit, o);
  LayoutFlowOptions fo;
  fo.density = o.density;
  fo.period_ns = 1000.0 / o.clock_mhz;
  const LayoutReport r = cached_or_run(lib, fo, o.cache_dir);
  print_report(std::cout, source, unit, lib, r);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "this run     " << std::fixed << std::setprecision(1) << wall << " s wall\n";
  if (!o.json_path.empty()) {
    nlohmann::json j = nlohmann::json::parse(layout_report_to_json(r));
    j["source"] = source;
    j["config"] = nlohmann::json::parse(config_to_json(unit));
    j["from_cache"] = r.from_cache;
    j["preroute"] = {{"area_um2", lib.area_um2},
                     {"fmax_mhz", lib.fmax_mhz},
                     {"cells", lib.cells},
                     {"liberty_key", lib.key}};
    write_text_file(o.json_path, j.dump(2) + '\n');
  }
  const bool ok = r.drc_errors == 0 && r.lvs_clean && r.unannotated_nets == 0;
  return ok ? 0 : 1;
}

}  // namespace shadesim
