// The liberty flow's files (sim/eda/sta/liberty_flow.h): its report as JSON (the cache entry and
// the "liberty" object of `shadesim area --json`) and the flip-flop -> Q net map of its netlist.
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "model/text_file.h"
#include "sim/eda/sta/liberty_flow.h"

namespace shadesim {
namespace {

using Json = nlohmann::json;

Json buffering_json(const FanoutBufferResult& b) {
  return {{"buffer_cell", b.buffer_cell},       {"max_fanout", b.max_fanout},
          {"nets_buffered", b.nets_buffered},   {"buffers", b.buffers},
          {"largest_fanout", b.largest_fanout}, {"clock_nets_skipped", b.clock_nets_skipped}};
}

FanoutBufferResult buffering_of(const Json& j) {
  FanoutBufferResult b;
  b.buffer_cell = j.at("buffer_cell");
  b.max_fanout = j.at("max_fanout");
  b.nets_buffered = j.at("nets_buffered");
  b.buffers = j.at("buffers");
  b.largest_fanout = j.at("largest_fanout");
  b.clock_nets_skipped = j.at("clock_nets_skipped");
  return b;
}

Json critical_path_json(const LibertyReport& r) {
  Json cells = Json::array();
  for (const auto& c : r.path) {
    cells.push_back({{"instance", c.instance},
                     {"cell", c.cell},
                     {"net", c.net},
                     {"fanout", c.fanout},
                     {"delay_ns", c.delay_ns},
                     {"time_ns", c.time_ns}});
  }
  return {{"from", r.path_from},         {"to", r.path_to},
          {"group", r.path_group},       {"arrival_ns", r.path_arrival_ns},
          {"setup_ns", r.path_setup_ns}, {"cells", cells}};
}

void read_critical_path(const Json& j, LibertyReport& r) {
  r.path_from = j.at("from");
  r.path_to = j.at("to");
  r.path_group = j.at("group");
  r.path_arrival_ns = j.at("arrival_ns");
  r.path_setup_ns = j.at("setup_ns");
  for (const auto& c : j.at("cells")) {
    r.path.push_back({c.at("instance"), c.at("cell"), c.at("net"), c.at("fanout"), c.at("delay_ns"),
                      c.at("time_ns")});
  }
}

// A Verilog net reference as OpenSTA names it: "\u_decoder.pos_q [1] " -> "u_decoder.pos_q[1]".
std::string verilog_net_name(std::string ref) {
  const auto b = ref.find_first_not_of(" \t");
  const auto e = ref.find_last_not_of(" \t");
  ref = b == std::string::npos ? "" : ref.substr(b, e - b + 1);
  if (!ref.empty() && ref[0] == '\\') ref.erase(0, 1);
  const auto space = ref.find(' ');
  if (space != std::string::npos && ref.find('[', space) != std::string::npos)
    ref.erase(space, ref.find('[', space) - space);
  return ref;
}

// The output pin of a sequential cell that carries its state (Q), else its inverse (QN).
std::string liberty_state_output(const LibertyCell& c) {
  for (int k = 0; k < 2 && k < static_cast<int>(c.state_vars.size()); ++k) {
    for (const LibertyPin* p : c.outputs())
      if (p->function == c.state_vars[static_cast<size_t>(k)]) return p->name;
  }
  const auto outs = c.outputs();
  return outs.empty() ? "" : outs[0]->name;
}

}  // namespace

std::string liberty_report_to_json(const LibertyReport& r) {
  // The figures a designer reads first, then how they were made.
  const Json j = {{"library", r.library},
                  {"liberty_path", r.liberty_path},
                  {"area_um2", r.area_um2},
                  {"nand2_equivalents", r.nand2_equivalents()},
                  {"nand2_cell", r.nand2_cell},
                  {"nand2_area_um2", r.nand2_area_um2},
                  {"cells", r.cells},
                  {"flip_flops", r.flip_flops},
                  {"period_ns", r.period_ns},
                  {"worst_slack_ns", r.worst_slack_ns},
                  {"fmax_mhz", r.fmax_mhz},
                  {"critical_path", critical_path_json(r)},
                  {"flip_flop_overhead_ns", r.flip_flop_overhead_ns},
                  {"overhead_cell", r.overhead_cell},
                  {"abc_delay_ps", r.abc_delay_ps},
                  {"constraints", constraints_to_json(r.constraints)},
                  {"buffering", buffering_json(r.buffering)},
                  {"netlist_path", r.netlist_path},
                  {"key", r.key},
                  {"from_cache", r.from_cache},
                  {"sta_version", r.sta_version},
                  {"seconds", r.seconds},
                  {"warnings", r.warnings}};
  return j.dump(2);
}

LibertyReport liberty_report_from_json(const std::string& text, const std::string& source) {
  try {
    const Json j = Json::parse(text);
    LibertyReport r;
    r.library = j.at("library");
    r.liberty_path = j.at("liberty_path");
    r.area_um2 = j.at("area_um2");
    r.nand2_cell = j.at("nand2_cell");
    r.nand2_area_um2 = j.at("nand2_area_um2");
    r.cells = j.at("cells");
    r.flip_flops = j.at("flip_flops");
    r.period_ns = j.at("period_ns");
    r.worst_slack_ns = j.at("worst_slack_ns");
    r.fmax_mhz = j.at("fmax_mhz");
    read_critical_path(j.at("critical_path"), r);
    r.flip_flop_overhead_ns = j.at("flip_flop_overhead_ns");
    r.overhead_cell = j.at("overhead_cell");
    r.abc_delay_ps = j.at("abc_delay_ps");
    r.constraints = constraints_from_json(j.at("constraints"), source);
    r.buffering = buffering_of(j.at("buffering"));
    r.netlist_path = j.at("netlist_path");
    r.key = j.at("key");
    r.from_cache = j.at("from_cache");
    r.sta_version = j.at("sta_version");
    r.seconds = j.at("seconds");
    r.warnings = j.at("warnings").get<std::vector<std::string>>();
    return r;
  } catch (const Json::exception& e) {
    throw std::runtime_error(source + ": not a liberty flow report: " + e.what());
  }
}

std::map<std::string, std::string> flip_flop_q_nets(const std::string& netlist_v,
                                                    const LibertyLibrary& lib) {
  // Yosys's write_verilog: "  DFFSR _21100_ (" then one ".PIN(net)," line per pin, then "  );".
  static const std::regex head(R"(^\s*(\S+)\s+(\S+)\s*\(\s*$)");
  static const std::regex pin(R"(^\s*\.(\w+)\((.*)\),?\s*$)");
  std::istringstream is(read_text_file(netlist_v));
  std::map<std::string, std::string> out;
  const LibertyCell* cell = nullptr;
  std::string instance, q;
  std::smatch m;
  for (std::string line; std::getline(is, line);) {
    if (!cell && std::regex_match(line, m, head)) {
      const auto it = lib.cells.find(m[1].str());
      if (it == lib.cells.end() || !it->second.sequential) continue;
      cell = &it->second;
      instance = verilog_net_name(m[2].str());
      q = liberty_state_output(*cell);
    } else if (cell && std::regex_match(line, m, pin)) {
      if (m[1].str() == q) out[instance] = verilog_net_name(m[2].str());
    } else if (cell && line.find(");") != std::string::npos) {
      cell = nullptr;
    }
  }
  return out;
}

}  // namespace shadesim
