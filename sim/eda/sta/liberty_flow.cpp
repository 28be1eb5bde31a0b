// The liberty flow's run (sim/eda/sta/liberty_flow.h); its cache entry's JSON and the netlist
// readers are in sim/eda/sta/liberty_flow_io.cpp.
#include "sim/eda/sta/liberty_flow.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "model/text_file.h"
#include "sim/eda/common/content_hash.h"
#include "sim/eda/common/tool_script.h"
#include "sim/eda/sta/sta_report.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;
using flow_tools::write_atomically;
using Json = nlohmann::json;

// The scripts beside this file; their headers say what each does and which @NAME@ fields it has.
std::string liberty_map_ys() { return tool_script("sim/eda/sta/liberty_map.ys"); }
std::string liberty_abc() { return tool_script("sim/eda/sta/liberty.abc"); }
std::string liberty_write_ys() { return tool_script("sim/eda/sta/liberty_write.ys"); }
std::string liberty_report_tcl() { return tool_script("sim/eda/sta/liberty_report.tcl"); }
std::string flip_flop_overhead_tcl() { return tool_script("sim/eda/sta/flip_flop_overhead.tcl"); }
constexpr const char* kBufferRule = "fanout tree v1: strongest buffer, even groups, clocks left";

// Runs OpenSTA on `tcl`; its errors do not change its exit status, so they are looked for.
std::string run_opensta_script(const std::string& sta, const fs::path& tcl,
                               const std::string& label) {
  const fs::path log = fs::path(tcl).replace_extension(".out");
  flow_tools::run_tool({sta, "-no_splash", "-exit", tcl.string()}, log, label, nullptr);
  std::string out = read_text_file(log.string());  // returned: moved
  const auto error = out.find("Error");
  if (error != std::string::npos)
    throw std::runtime_error(label + " failed; log " + log.string() + ": " +
                             first_line(out.substr(error)));
  return out;
}

// Clock-to-Q (the path's arrival) and setup of the library's plain flip-flop, by OpenSTA under an
// ideal clock: one flip-flop's Q loaded with the D pins of max_fanout others (the most load a net
// keeps after buffering), into one's setup.
StaPath flip_flop_overhead(const LibertyRun& run, const PlainFlipFlop& ff, const fs::path& work) {
  const std::string c = ff.cell->name;
  std::ostringstream v;
  v << "module shade_unit (clk_i, d_i);\n  input clk_i;\n  input d_i;\n  wire m;\n"
    << "  " << c << " a (." << ff.clock << "(clk_i), ." << ff.d << "(d_i), ." << ff.q << "(m));\n";
  for (int k = 0; k < run.options.max_fanout; ++k)
    v << "  " << c << " b" << k << " (." << ff.clock << "(clk_i), ." << ff.d << "(m));\n";
  v << "endmodule\n";
  write_atomically(work / "overhead.v", v.str());
  write_atomically(work / "overhead.tcl",
                   sta_read_tcl(run.options.liberty_path, (work / "overhead.v").string()) +
                       fill_placeholders(flip_flop_overhead_tcl(),
                                         {{"@PERIOD@", std::to_string(run.options.period_ns)},
                                          {"@D_PIN@", ff.d}}));
  const std::string out =
      run_opensta_script(run.sta, work / "overhead.tcl", "OpenSTA flip-flop overhead");
  return worst_path(parse_sta_paths(out, (work / "overhead.out").string()));
}

LibertyPathCell liberty_path_cell(const StaStage& s) {
  return {s.instance, s.cell, s.net, s.fanout, s.delay_ns, s.time_ns};
}

// The worst path into r: its ends as register (Q net) or port names, and its cells without the
// launching clock pin's row.
void read_liberty_timing(const std::string& out, const std::string& source,
                         const std::map<std::string, std::string>& q_nets, LibertyReport& r) {
  const std::vector<StaPath> paths = parse_sta_paths(out, source);
  const StaPath& p = worst_path(paths);
  const auto name = [&](const std::string& instance) {
    const auto it = q_nets.find(instance);
    return it == q_nets.end() ? instance : it->second;
  };
  r.worst_slack_ns = p.slack_ns;
  r.fmax_mhz = 1000.0 / (r.period_ns - p.slack_ns);
  r.path_from = name(p.startpoint);
  r.path_to = name(p.endpoint);
  r.path_group = p.group;
  r.path_arrival_ns = p.arrival_ns;
  r.path_setup_ns = p.setup_ns;
  for (size_t i = 0; i < p.stages.size(); ++i) {
    const bool launch = i == 0 && p.stages.size() > 1 && !p.stages[0].pin.empty() &&
                        p.stages[1].instance == p.stages[0].instance;
    if (!launch) r.path.push_back(liberty_path_cell(p.stages[i]));
  }
  const std::optional<double> worst = parse_worst_slack(out);
  if (!worst || std::abs(*worst - p.slack_ns) > 0.0015) {
    r.warnings.push_back(source + ": report_worst_slack says " +
                         (worst ? std::to_string(*worst) : std::string("nothing")) +
                         ", the worst reported path's slack is " + std::to_string(p.slack_ns));
  }
}

// Area, cells and flip-flops of the buffered netlist from the library's cells.
void read_liberty_area(const Json& netlist, const LibertyLibrary& lib, const std::string& source,
                       LibertyReport& r) {
  for (const auto& [name, cell] : netlist.at("modules").at("shade_unit").at("cells").items()) {
    const std::string type = cell.at("type");
    const auto it = lib.cells.find(type);
    if (it == lib.cells.end())
      throw std::runtime_error(source + ": cell " + name + " is a " + type + ", not a cell of " +
                               lib.path);
    r.area_um2 += it->second.area;
    ++r.cells;
    if (it->second.sequential) ++r.flip_flops;
  }
}

Json read_yosys_json_netlist(const fs::path& p) {
  try {
    return Json::parse(read_text_file(p.string()));
  } catch (const Json::exception& e) {
    throw std::runtime_error(p.string() + ": not Yosys's JSON netlist: " + e.what());
  }
}

// Yosys maps, the netlist is buffered and written as Verilog; returns the buffered netlist.
Json map_and_buffer(const LibertyRun& run, const LibertyLibrary& lib, const fs::path& work,
                    LibertyReport& r) {
  const std::map<std::string, std::string> values = {
      {"@LIB@", run.options.liberty_path},
      {"@ABC@", (work / "liberty.abc").string()},
      {"@WORK@", work.string()},
      {"@D@", std::to_string(std::llround(r.abc_delay_ps))}};
  write_atomically(work / "liberty.abc", fill_placeholders(liberty_abc(), values));
  write_atomically(work / "liberty.ys",
                   flow_tools::yosys_script(run.flow.files, run.flow.chparam,
                                            fill_placeholders(liberty_map_ys(), values), work));
  flow_tools::run_tool(
      {run.flow.yosys, "-q", "-l", (work / "liberty.log").string(), (work / "liberty.ys").string()},
      work / "liberty.out", "yosys liberty mapping", nullptr);
  Json netlist = read_yosys_json_netlist(work / "liberty_mapped.json");
  r.buffering = buffer_fanout(netlist, "shade_unit", lib, run.options.max_fanout,
                              (work / "liberty_mapped.json").string());
  write_atomically(work / "liberty_buffered.json", netlist.dump());
  write_atomically(work / "liberty_write.ys", fill_placeholders(liberty_write_ys(), values));
  flow_tools::run_tool({run.flow.yosys, "-q", "-l", (work / "liberty_write.log").string(),
                        (work / "liberty_write.ys").string()},
                       work / "liberty_write.out", "yosys write of the buffered netlist", nullptr);
  return netlist;
}

}  // namespace

std::string resolve_liberty(const std::string& requested, const std::string& default_path) {
  std::string path = requested.empty() ? default_path : requested;  // returned: moved
  if (fs::is_regular_file(path)) return path;
  if (requested.empty() || requested == default_path)
    throw MissingToolError("the osu018 standard-cell library " + default_path +
                           " is missing: shadesim area maps the unit onto it (Debian package " +
                           kDefaultLibertyPackage +
                           "; scripts/setup installs it), or give --liberty FILE or --no-liberty");
  throw std::runtime_error(path + ": no such Liberty file (--liberty expects a .lib file)");
}

LibertyRun prepare_liberty_run(const FlowInputs& flow, const LibertyOptions& o) {
  LibertyRun run;
  run.flow = flow;
  run.options = o;
  run.options.liberty_path = fs::absolute(resolve_liberty(o.liberty_path)).string();
  run.sta = flow_tools::find_tool(o.sta, "opensta");
  run.sta_version = flow_tools::tool_version(run.sta, {"-version"});
  ContentHash h;
  h.add("shadesim-liberty-v2").add(flow.chparam);
  for (const auto& f : flow.files) h.add(f.filename().string()).add(read_text_file(f.string()));
  h.add(flow.yosys_version).add(run.sta_version);
  h.add(read_text_file(run.options.liberty_path));
  h.add(liberty_map_ys()).add(liberty_abc());
  h.add(liberty_write_ys()).add(liberty_report_tcl()).add(sta_read_tcl("", "")).add(kBufferRule);
  h.add(flip_flop_overhead_tcl());
  h.add(constraints_template()).add(std::to_string(o.constraints.clock_uncertainty_ns));
  h.add(std::to_string(o.constraints.load_pins));  // the guard band is the caller's comparison
  h.add(std::to_string(o.period_ns)).add(std::to_string(o.max_fanout));
  run.key = h.hex();
  return run;
}

std::string liberty_log_path(const std::string& cache_dir, const std::string& key) {
  return (fs::absolute(fs::path(cache_dir)) / ("liberty-log-" + key + ".txt")).string();
}

std::optional<LibertyReport> cached_liberty(const LibertyRun& run, const std::string& cache_dir) {
  if (cache_dir.empty()) return std::nullopt;
  const fs::path entry = fs::path(cache_dir) / ("liberty-" + run.key + ".json");
  const fs::path netlist = fs::path(cache_dir) / ("liberty-netlist-" + run.key + ".v");
  if (!fs::exists(entry) || !fs::exists(netlist)) return std::nullopt;
  LibertyReport r = liberty_report_from_json(read_text_file(entry.string()), entry.string());
  r.from_cache = true;
  r.netlist_path = fs::absolute(netlist).string();
  return r;
}

LibertyReport run_liberty_flow(const LibertyRun& run, const fs::path& work,
                               const std::string& cache_dir) {
  const auto t0 = std::chrono::steady_clock::now();
  const LibertyLibrary lib = read_liberty(run.options.liberty_path);
  LibertyReport r;
  r.library = lib.name;
  r.liberty_path = run.options.liberty_path;
  r.key = run.key;
  r.sta_version = run.sta_version;
  r.period_ns = run.options.period_ns;
  const LibertyCell& nand2 = nand2_cell(lib);
  r.nand2_cell = nand2.name;
  r.nand2_area_um2 = nand2.area;
  const PlainFlipFlop ff = required_plain_flip_flop(
      lib, "the flow measures the registers' overhead and the ports' constraints on it");
  r.overhead_cell = ff.cell->name;
  const StaPath overhead = flip_flop_overhead(run, ff, work);
  r.flip_flop_overhead_ns = overhead.arrival_ns + overhead.setup_ns;
  r.constraints =
      resolve_constraints(run.options.constraints, lib, overhead.arrival_ns, overhead.setup_ns);
  r.abc_delay_ps = 1000.0 * (r.period_ns - r.flip_flop_overhead_ns);
  const Json netlist = map_and_buffer(run, lib, work, r);
  read_liberty_area(netlist, lib, (work / "liberty_buffered.json").string(), r);
  const fs::path netlist_v = work / "liberty_netlist.v";
  write_atomically(work / "liberty_sta.tcl",
                   sta_setup_tcl(r.liberty_path, netlist_v.string(), r.period_ns, r.constraints) +
                       liberty_report_tcl());
  const std::string out = run_opensta_script(run.sta, work / "liberty_sta.tcl", "OpenSTA timing");
  read_liberty_timing(out, (work / "liberty_sta.out").string(),
                      flip_flop_q_nets(netlist_v.string(), lib), r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.netlist_path = netlist_v.string();
  if (!cache_dir.empty()) {
    fs::create_directories(cache_dir);
    // The netlist first: an entry is complete once its .json exists.
    const fs::path kept = fs::absolute(fs::path(cache_dir) / ("liberty-netlist-" + r.key + ".v"));
    write_atomically(kept, read_text_file(netlist_v.string()));
    r.netlist_path = kept.string();
    // Yosys's log beside it: the power flow reads which registers its fsm pass re-encoded.
    write_atomically(liberty_log_path(cache_dir, r.key),
                     read_text_file((work / "liberty.log").string()));
    write_atomically(fs::path(cache_dir) / ("liberty-" + r.key + ".json"),
                     liberty_report_to_json(r) + "\n");
  }
  return r;
}

std::string sta_read_tcl(const std::string& liberty, const std::string& netlist_v) {
  return fill_placeholders(tool_script("sim/eda/sta/sta_read.tcl"),
                           {{"@LIBERTY@", liberty}, {"@NETLIST@", netlist_v}});
}

std::string sta_setup_tcl(const std::string& liberty, const std::string& netlist_v,
                          double period_ns, const ResolvedConstraints& constraints,
                          const std::string& spef) {
  return sta_read_tcl(liberty, netlist_v) + constraints_tcl(constraints, period_ns) +
         (spef.empty() ? "" : "read_spef {" + spef + "}\n");
}

}  // namespace shadesim
