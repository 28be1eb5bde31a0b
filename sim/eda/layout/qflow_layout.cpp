// shadesim layout's flow (sim/eda/layout/qflow_layout.h); the JSON of its report is in
// sim/eda/layout/layout_report_json.cpp.
#include "sim/eda/layout/qflow_layout.h"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <stdexcept>

#include "host/image.h"
#include "model/text_file.h"
#include "sim/eda/common/build_paths.h"
#include "sim/eda/common/content_hash.h"
#include "sim/eda/common/flow_tools.h"
#include "sim/eda/common/tool_script.h"
#include "sim/eda/layout/layout_png.h"
#include "sim/eda/layout/layout_reports.h"
#include "sim/eda/layout/spef.h"
#include "sim/eda/sta/liberty.h"
#include "sim/eda/sta/sta_report.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;
using flow_tools::write_atomically;

constexpr const char* kScripts[] = {"import.ys", "project_vars.sh", "magic_drc.tcl",
                                    "layout_flow.sh"};
// The post-route report (its header says what it asks for).
std::string post_route_report() { return tool_script("sim/eda/layout/post_route_report.tcl"); }

std::string scripts_dir(const LayoutFlowOptions& o) {
  return o.scripts_dir.empty() ? source_dir() + "/sim/eda/layout" : o.scripts_dir;
}

// The qflow project: source/ with the netlist, import.ys (in synthesis), project_vars.sh and
// magic_drc.tcl filled in.
void prepare_project(const LibertyReport& lib, const LayoutFlowOptions& o, const fs::path& work) {
  for (const char* d : {"source", "synthesis", "layout", "log"}) fs::create_directories(work / d);
  fs::copy_file(lib.netlist_path, work / "source" / "shade_unit.v",
                fs::copy_options::overwrite_existing);
  std::ostringstream density;
  density << o.density;
  const std::map<std::string, std::string> values = {
      {"@LIBERTY@", lib.liberty_path},
      {"@NETLIST@", (work / "source" / "shade_unit.v").string()},
      {"@WORK@", work.string()},
      {"@DENSITY@", density.str()},
      {"@TECHDIR@", o.tech_dir},
      {"@LEF@", o.tech_dir + "/osu018_stdcells.lef"},
      {"@GDS@", (work / "layout" / "shade_unit.gds").string()}};
  const std::string dir = scripts_dir(o);
  write_atomically(work / "synthesis" / "import.ys",
                   fill_placeholders(read_text_file(dir + "/import.ys"), values));
  write_atomically(work / "project_vars.sh",
                   fill_placeholders(read_text_file(dir + "/project_vars.sh"), values));
  write_atomically(work / "magic_drc.tcl",
                   fill_placeholders(read_text_file(dir + "/magic_drc.tcl"), values));
}

// One step through layout_flow.sh; throws naming the step's log when `must_exist` is missing.
double run_step(const std::string& step, const fs::path& work, const LayoutFlowOptions& o,
                const fs::path& must_exist, std::ostream* progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path log = work / "log" / ("step_" + step + ".out");
  flow_tools::run_tool({"/bin/bash", scripts_dir(o) + "/layout_flow.sh", work.string(), step}, log,
                       "layout " + step, progress);
  if (!must_exist.empty() && !fs::exists(must_exist))
    throw std::runtime_error("layout " + step + " left no " + must_exist.string() + "; see " +
                             log.string() + " and " + (work / "log").string() + "/");
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// qrouter's verdict: its last "Final:" line must say no failed routes.
void check_routed(const fs::path& work) {
  const fs::path log = work / "log" / "route.log";
  const std::string text = fs::exists(log) ? read_text_file(log.string()) : "";
  const auto at = text.rfind("Final:");
  if (at == std::string::npos || text.find("No failed routes", at) == std::string::npos)
    throw std::runtime_error("layout route: qrouter did not route every net; see " + log.string() +
                             (at == std::string::npos ? "" : ": " + first_line(text.substr(at))));
}

// OpenSTA's warnings on the SPEF ("Warning: FILE.spef, line N pin|net X not found.").
int64_t count_spef_warnings(const std::string& out) {
  std::istringstream in(out);
  int64_t n = 0;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("Warning:", 0) == 0 && line.find(".spef") != std::string::npos) ++n;
  return n;
}

// OpenSTA on the routed netlist with (spef non-empty) or without its parasitics.
std::string run_sta(const LayoutTools& tools, const LibertyReport& lib, const fs::path& netlist,
                    const fs::path& spef, double period_ns, const fs::path& tcl) {
  write_atomically(tcl, sta_setup_tcl(lib.liberty_path, netlist.string(), period_ns,
                                      lib.constraints, spef.empty() ? "" : spef.string()) +
                            post_route_report());
  const fs::path log = fs::path(tcl).replace_extension(".out");
  flow_tools::run_tool({tools.sta, "-no_splash", "-exit", tcl.string()}, log,
                       "layout OpenSTA " + tcl.stem().string(), nullptr);
  std::string out = read_text_file(log.string());  // returned: moved
  const auto error = out.find("Error");
  if (error != std::string::npos)
    throw std::runtime_error("OpenSTA failed; log " + log.string() + ": " +
                             first_line(out.substr(error)));
  return out;
}

// The worst path: its cells' output rows, and its wires' delay (the input-pin rows' delays).
void read_timing(const std::string& out, const std::string& source, const LibertyLibrary& lib,
                 LayoutReport& r) {
  const std::vector<StaPath> paths = parse_sta_paths(out, source);
  const StaPath& p = worst_path(paths);
  r.worst_slack_ns = p.slack_ns;
  r.fmax_mhz = 1000.0 / (r.period_ns - p.slack_ns);
  r.path_from = p.startpoint;
  r.path_to = p.endpoint;
  r.path_group = p.group;
  r.path_arrival_ns = p.arrival_ns;
  r.path_setup_ns = p.setup_ns;
  for (const StaStage& s : p.stages) {
    const auto cell = lib.cells.find(s.cell);
    const LibertyPin* pin = cell == lib.cells.end() ? nullptr : cell->second.pin(s.pin);
    const bool input = pin && pin->direction == "input";
    if (input) r.path_wire_delay_ns += s.delay_ns;
    r.path.push_back({s.instance + (s.pin.empty() ? "" : "/" + s.pin), s.cell, s.net, s.fanout,
                      s.delay_ns, s.time_ns});
  }
}

// Every net the routed netlist connects has a D_NET in the SPEF?
void count_annotation(const std::string& netlist, const std::string& fixed_spef, LayoutReport& r) {
  const VerilogNets v = verilog_nets(netlist);
  const std::set<std::string> annotated = spef_net_names(fixed_spef);
  r.netlist_nets = static_cast<int64_t>(v.connected.size());
  r.spef_nets = static_cast<int64_t>(annotated.size());
  for (const std::string& n : v.connected) {
    // A pin tied to a rail (qflow ties constants to vdd / gnd through a buffer) is on the power
    // grid, which qrouter does not extract: not a signal net.
    if (annotated.count(n) || n == "vdd" || n == "gnd") continue;
    ++r.unannotated_nets;
    if (r.unannotated.size() < 10) r.unannotated.push_back(n);
  }
}

void read_layout(const LibertyReport& lib, const LayoutFlowOptions& o, const fs::path& work,
                 const fs::path& out_dir, LayoutReport& r) {
  const auto sizes = parse_lef_sizes(read_text_file(o.tech_dir + "/osu018_stdcells.lef"));
  const fs::path def_path = work / "layout" / "shade_unit.def";
  const DefSummary d = parse_def(read_text_file(def_path.string()), def_path.string(), sizes);
  r.die_width_um = d.die_x1_um - d.die_x0_um;
  r.die_height_um = d.die_y1_um - d.die_y0_um;
  r.die_area_um2 = d.die_area_um2();
  r.core_area_um2 = d.core_area_um2();
  r.cell_area_um2 = lib.area_um2;
  r.utilisation = r.core_area_um2 > 0 ? lib.area_um2 / r.core_area_um2 : 0;
  r.cells = d.components - d.fill_cells;
  r.fill_cells = d.fill_cells;
  r.pins = d.pins;
  r.nets = d.nets;
  r.wire_length_um = d.wire_length_um;
  r.vias = d.vias;
  r.wire_length_by_layer_um = d.wire_length_by_layer_um;
  r.png_path = (out_dir / "shade_unit.png").string();
  write_png(r.png_path, draw_layout(d, sizes, o.picture_side));
}

}  // namespace

namespace {

// flow_tools::find_tool, its message naming this command.
std::string find_layout_tool(const std::string& name, const std::string& package) {
  try {
    return flow_tools::find_tool(name, package);
  } catch (const MissingToolError& e) {
    std::string what = e.what();
    const auto at = what.find("shadesim area");
    if (at != std::string::npos) what.replace(at, 13, "shadesim layout");
    throw MissingToolError(what);
  }
}

}  // namespace

LayoutTools find_layout_tools(const LayoutFlowOptions& o) {
  LayoutTools t;
  t.qflow = find_layout_tool("qflow", "qflow");
  t.graywolf = find_layout_tool("graywolf", "graywolf");
  t.qrouter = find_layout_tool("qrouter", "qrouter");
  t.magic = find_layout_tool("magic", "magic");
  t.netgen = find_layout_tool("netgen-lvs", "netgen-lvs");
  t.sta = find_layout_tool("sta", "opensta");
  for (const char* f : {"/osu018_stdcells.lef", "/osu018.magicrc", "/osu018.sh"}) {
    if (!fs::exists(o.tech_dir + f))
      throw MissingToolError(o.tech_dir + f +
                             " is missing: shadesim layout needs qflow's osu018 technology "
                             "(Debian package qflow-tech-osu018; scripts/setup installs it)");
  }
  std::ostringstream v;
  v << "qflow " << flow_tools::tool_version("/usr/bin/dpkg-query", {"-W", "-f=${Version}", "qflow"})
    << "\nqrouter "
    << flow_tools::tool_version("/usr/bin/dpkg-query", {"-W", "-f=${Version}", "qrouter"})
    << "\ngraywolf "
    << flow_tools::tool_version("/usr/bin/dpkg-query", {"-W", "-f=${Version}", "graywolf"})
    << "\nmagic "
    << flow_tools::tool_version("/usr/bin/dpkg-query", {"-W", "-f=${Version}", "magic"})
    << "\nnetgen "
    << flow_tools::tool_version("/usr/bin/dpkg-query", {"-W", "-f=${Version}", "netgen-lvs"})
    << "\nsta " << flow_tools::tool_version(t.sta, {"-version"});
  t.versions = v.str();
  return t;
}

std::string layout_key(const LibertyReport& lib, const LayoutFlowOptions& o,
                       const LayoutTools& tools) {
  ContentHash h;
  h.add("shadesim-layout-v1").add(lib.key).add(tools.versions).add(post_route_report());
  h.add(sta_read_tcl("", ""));  // lib.key covers the constraints
  for (const char* s : kScripts) h.add(script_commands(read_text_file(scripts_dir(o) + "/" + s)));
  std::ostringstream opts;
  opts << o.density << ' ' << o.period_ns << ' ' << o.picture_side << ' ' << o.tech_dir;
  h.add(opts.str()).add(read_text_file(o.tech_dir + "/osu018_stdcells.lef"));
  return h.hex();
}

LayoutReport run_qflow_layout(const LibertyReport& lib, const LayoutFlowOptions& o,
                              const LayoutTools& tools, const fs::path& work,
                              const fs::path& out_dir, std::ostream* progress) {
  const auto t0 = std::chrono::steady_clock::now();
  LayoutReport r;
  r.density = o.density;
  r.period_ns = o.period_ns;
  prepare_project(lib, o, work);
  fs::create_directories(out_dir);
  const fs::path syn = work / "synthesis", lay = work / "layout";
  const std::vector<std::pair<std::string, fs::path>> steps = {
      {"synthesize", syn / "shade_unit.blif"}, {"place", lay / "shade_unit.cel"},
      {"pins", lay / "shade_unit.cel"},        {"route", lay / "shade_unit.def"},
      {"backanno", syn / "shade_unit.spef"},   {"migrate", lay / "shade_unit.mag"},
      {"lvs", work / "log" / "lvs.log"},       {"drc", lay / "shade_unit.gds"}};
  for (const auto& [step, file] : steps) {
    r.step_seconds[step] = run_step(step, work, o, file, progress);
    if (step == "route") check_routed(work);
  }
  read_layout(lib, o, work, out_dir, r);
  const std::string drc_log = read_text_file((work / "log" / "drc_magic.log").string());
  r.drc_errors = parse_magic_drc_count(drc_log);
  std::istringstream why(drc_log);
  for (std::string line; std::getline(why, line);)
    if (line.rfind("drc why: ", 0) == 0) r.drc_kinds.push_back(line.substr(9));
  const LvsResult lvs = parse_netgen_lvs(read_text_file((work / "log" / "lvs.log").string()));
  r.lvs_clean = lvs.clean;
  r.lvs_verdict = lvs.found ? lvs.verdict : "no verdict in log/lvs.log";
  r.lvs_errors = lvs.total_errors;
  // Timing: blif2Verilog's netlist with rc2dly's SPEF, fixed (sim/eda/layout/spef.h).
  const std::string netlist = read_text_file((syn / "shade_unit.rtlnopwr.v").string());
  const std::string spef = fix_qflow_spef(read_text_file((syn / "shade_unit.spef").string()),
                                          verilog_nets(netlist).bus_ports);
  r.netlist_path = (out_dir / "shade_unit.v").string();
  r.spef_path = (out_dir / "shade_unit.spef").string();
  r.def_path = (out_dir / "shade_unit.def").string();
  r.gds_path = (out_dir / "shade_unit.gds").string();
  write_atomically(r.netlist_path, netlist);
  write_atomically(r.spef_path, spef);
  fs::copy_file(lay / "shade_unit.def", r.def_path, fs::copy_options::overwrite_existing);
  fs::copy_file(lay / "shade_unit.gds", r.gds_path, fs::copy_options::overwrite_existing);
  count_annotation(netlist, spef, r);
  const LibertyLibrary library = read_liberty(lib.liberty_path);
  const auto t_sta = std::chrono::steady_clock::now();
  const std::string post =
      run_sta(tools, lib, r.netlist_path, r.spef_path, o.period_ns, work / "post_route.tcl");
  r.spef_warnings = count_spef_warnings(post);
  read_timing(post, (work / "post_route.out").string(), library, r);
  const std::string pre =
      run_sta(tools, lib, r.netlist_path, "", o.period_ns, work / "no_wires.tcl");
  const StaPath p = worst_path(parse_sta_paths(pre, (work / "no_wires.out").string()));
  r.preroute_slack_ns = p.slack_ns;
  r.preroute_fmax_mhz = 1000.0 / (o.period_ns - p.slack_ns);
  r.step_seconds["sta"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_sta).count();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace shadesim
