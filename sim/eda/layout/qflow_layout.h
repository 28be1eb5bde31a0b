// shadesim layout's flow: the liberty flow's osu018 netlist (sim/eda/sta/liberty_flow.h) placed and
// routed with Debian's qflow 1.3 (graywolf, qrouter), extracted (rc2dly's SPEF), timed by
// OpenSTA with those parasitics (the liberty flow's own setup, sta_setup_tcl, plus read_spef),
// checked by magic (DRC) and netgen (LVS), written as GDS and drawn as a PNG.
//
// The tool scripts are files beside this driver (import.ys, project_vars.sh, magic_drc.tcl,
// layout_flow.sh); the driver fills in their @NAMES@ into a qflow project folder and runs
// layout_flow.sh one step at a time. docs/layout.md says what is measured and left out.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "sim/eda/sta/liberty_flow.h"

namespace shadesim {

constexpr const char* kQflowTechDir = "/usr/share/qflow/tech/osu018";

struct LayoutFlowOptions {
  double density = 0.6;    // qflow's initial_density: cells / core row area
  double period_ns = 4.0;  // the analysis clock (250 MHz: config's default target)
  std::string tech_dir = kQflowTechDir;
  std::string scripts_dir;  // the folder of import.ys ...; empty: this checkout's
  int picture_side = 1200;  // the PNG's longer side in pixels
};

// The programs the flow runs, their versions (part of the cache key).
struct LayoutTools {
  std::string qflow, graywolf, qrouter, magic, netgen, sta;
  std::string versions;  // one line per tool
};
// Finds every tool (MissingToolError naming its Debian package) and the osu018 tech files.
LayoutTools find_layout_tools(const LayoutFlowOptions& o);

struct LayoutReport {
  std::string key;
  bool from_cache = false;
  double density = 0, period_ns = 0;
  // Placement and routing (the routed DEF).
  double die_width_um = 0, die_height_um = 0, die_area_um2 = 0, core_area_um2 = 0;
  double cell_area_um2 = 0;  // the liberty flow's figure: the cells' own area
  double utilisation = 0;    // cell area / core area
  int64_t cells = 0, fill_cells = 0, pins = 0, nets = 0;
  double wire_length_um = 0;
  int64_t vias = 0;
  std::map<std::string, double> wire_length_by_layer_um;
  // Post-route timing (OpenSTA with the SPEF).
  int64_t netlist_nets = 0, spef_nets = 0, unannotated_nets = 0;
  std::vector<std::string> unannotated;  // the first few names
  int64_t spef_warnings = 0;             // OpenSTA's "not found" warnings on the SPEF
  double worst_slack_ns = 0, fmax_mhz = 0, path_arrival_ns = 0, path_setup_ns = 0;
  double path_wire_delay_ns = 0;  // the path's delay less the same cells' delay without wires
  double preroute_fmax_mhz = 0, preroute_slack_ns = 0;
  std::string path_from, path_to, path_group;
  std::vector<LibertyPathCell> path;
  // Checks.
  int64_t drc_errors = -1;
  std::vector<std::string> drc_kinds;  // magic's "why" lines
  bool lvs_clean = false;
  std::string lvs_verdict;
  int64_t lvs_errors = -1;
  // Files (in the cache folder when there is one).
  std::string gds_path, png_path, def_path, spef_path, netlist_path;
  std::map<std::string, double> step_seconds;
  double seconds = 0;
};

// The flow's cache key: the liberty flow's key, the scripts, the options and the tools.
std::string layout_key(const LibertyReport& lib, const LayoutFlowOptions& o,
                       const LayoutTools& tools);

// Runs every step in `work` (kept: the qflow project), copies the results into `out_dir` and
// returns the report. Progress lines go to `progress`. Throws std::runtime_error naming the step
// and its log when a step fails to produce its files.
LayoutReport run_qflow_layout(const LibertyReport& lib, const LayoutFlowOptions& o,
                              const LayoutTools& tools, const std::filesystem::path& work,
                              const std::filesystem::path& out_dir, std::ostream* progress);

std::string layout_report_to_json(const LayoutReport& r);  // one JSON object
LayoutReport layout_report_from_json(const std::string& text, const std::string& source);

}  // namespace shadesim
