// LayoutReport <-> JSON (sim/eda/layout/qflow_layout.h): the cache entry and `layout --json`.
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "sim/eda/layout/qflow_layout.h"

namespace shadesim {

std::string layout_report_to_json(const LayoutReport& r) {
  nlohmann::json j;
  j["key"] = r.key;
  j["density"] = r.density;
  j["period_ns"] = r.period_ns;
  j["clock_mhz"] = 1000.0 / r.period_ns;
  j["die"] = {{"width_um", r.die_width_um},
              {"height_um", r.die_height_um},
              {"area_um2", r.die_area_um2},
              {"area_mm2", r.die_area_um2 / 1e6}};
  j["core_area_um2"] = r.core_area_um2;
  j["cell_area_um2"] = r.cell_area_um2;
  j["utilisation"] = r.utilisation;
  j["cells"] = r.cells;
  j["fill_cells"] = r.fill_cells;
  j["pins"] = r.pins;
  j["nets"] = r.nets;
  j["wire_length_um"] = r.wire_length_um;
  j["wire_length_by_layer_um"] = r.wire_length_by_layer_um;
  j["vias"] = r.vias;
  j["timing"] = {{"worst_slack_ns", r.worst_slack_ns},
                 {"fmax_mhz", r.fmax_mhz},
                 {"meets_clock", r.worst_slack_ns >= 0},
                 {"path_arrival_ns", r.path_arrival_ns},
                 {"path_setup_ns", r.path_setup_ns},
                 {"path_wire_delay_ns", r.path_wire_delay_ns},
                 {"path_from", r.path_from},
                 {"path_to", r.path_to},
                 {"path_group", r.path_group},
                 {"no_wires_slack_ns", r.preroute_slack_ns},
                 {"no_wires_fmax_mhz", r.preroute_fmax_mhz}};
  nlohmann::json path = nlohmann::json::array();
  for (const auto& c : r.path)
    path.push_back({{"pin", c.instance},
                    {"cell", c.cell},
                    {"net", c.net},
                    {"fanout", c.fanout},
                    {"delay_ns", c.delay_ns},
                    {"time_ns", c.time_ns}});
  j["timing"]["path"] = path;
  j["annotation"] = {{"netlist_nets", r.netlist_nets},
                     {"spef_nets", r.spef_nets},
                     {"unannotated_nets", r.unannotated_nets},
                     {"unannotated_examples", r.unannotated},
                     {"sta_spef_warnings", r.spef_warnings}};
  j["drc"] = {{"errors", r.drc_errors}, {"kinds", r.drc_kinds}};
  j["lvs"] = {{"clean", r.lvs_clean}, {"verdict", r.lvs_verdict}, {"errors", r.lvs_errors}};
  j["files"] = {{"gds", r.gds_path},
                {"png", r.png_path},
                {"def", r.def_path},
                {"spef", r.spef_path},
                {"netlist", r.netlist_path}};
  j["step_seconds"] = r.step_seconds;
  j["seconds"] = r.seconds;
  return j.dump(2);
}

LayoutReport layout_report_from_json(const std::string& text, const std::string& source) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    LayoutReport r;
    r.key = j.at("key");
    r.density = j.at("density");
    r.period_ns = j.at("period_ns");
    r.die_width_um = j.at("die").at("width_um");
    r.die_height_um = j.at("die").at("height_um");
    r.die_area_um2 = j.at("die").at("area_um2");
    r.core_area_um2 = j.at("core_area_um2");
    r.cell_area_um2 = j.at("cell_area_um2");
    r.utilisation = j.at("utilisation");
    r.cells = j.at("cells");
    r.fill_cells = j.at("fill_cells");
    r.pins = j.at("pins");
    r.nets = j.at("nets");
    r.wire_length_um = j.at("wire_length_um");
    r.wire_length_by_layer_um =
        j.at("wire_length_by_layer_um").get<std::map<std::string, double>>();
    r.vias = j.at("vias");
    const auto& t = j.at("timing");
    r.worst_slack_ns = t.at("worst_slack_ns");
    r.fmax_mhz = t.at("fmax_mhz");
    r.path_arrival_ns = t.at("path_arrival_ns");
    r.path_setup_ns = t.at("path_setup_ns");
    r.path_wire_delay_ns = t.at("path_wire_delay_ns");
    r.path_from = t.at("path_from");
    r.path_to = t.at("path_to");
    r.path_group = t.at("path_group");
    r.preroute_slack_ns = t.at("no_wires_slack_ns");
    r.preroute_fmax_mhz = t.at("no_wires_fmax_mhz");
    for (const auto& c : t.at("path"))
      r.path.push_back({c.at("pin"), c.at("cell"), c.at("net"), c.at("fanout"), c.at("delay_ns"),
                        c.at("time_ns")});
    const auto& a = j.at("annotation");
    r.netlist_nets = a.at("netlist_nets");
    r.spef_nets = a.at("spef_nets");
    r.unannotated_nets = a.at("unannotated_nets");
    r.unannotated = a.at("unannotated_examples").get<std::vector<std::string>>();
    r.spef_warnings = a.at("sta_spef_warnings");
    r.drc_errors = j.at("drc").at("errors");
    r.drc_kinds = j.at("drc").at("kinds").get<std::vector<std::string>>();
    r.lvs_clean = j.at("lvs").at("clean");
    r.lvs_verdict = j.at("lvs").at("verdict");
    r.lvs_errors = j.at("lvs").at("errors");
    const auto& f = j.at("files");
    r.gds_path = f.at("gds");
    r.png_path = f.at("png");
    r.def_path = f.at("def");
    r.spef_path = f.at("spef");
    r.netlist_path = f.at("netlist");
    r.step_seconds = j.at("step_seconds").get<std::map<std::string, double>>();
    r.seconds = j.at("seconds");
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(source + ": not a layout report: " + e.what());
  }
}

}  // namespace shadesim
