// unit_netlist (sim/engines/area_report.h): the generic flow's flat netlist of a unit, written out
// for simulation in place of the RTL (regress --netlist), cached and checked against the RTL's
// ports.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "model/text_file.h"
#include "sim/eda/common/build_paths.h"
#include "sim/eda/common/content_hash.h"
#include "sim/eda/common/flow_tools.h"
#include "sim/eda/common/process.h"
#include "sim/eda/yosys/area_generic.h"
#include "sim/eda/yosys/unit_netlist.h"

namespace shadesim {
namespace fs = std::filesystem;
using flow_tools::rtl_sources;
using flow_tools::run_tool;
using flow_tools::write_atomically;
using flow_tools::yosys_script;
using generic_flow::flat_script;
using generic_flow::netlist_write_script;

namespace {

// The ports of shade_unit the co-simulation glue drives (sim/harness/cosim_glue.cpp), with their
// widths from the parameters (rtl/shade_unit.sv's port list).
std::map<std::string, std::pair<std::string, int64_t>> expected_ports(
    const std::vector<VerilogParameter>& parameters) {
  const std::map<std::string, int64_t> p = parameter_map(parameters);
  const auto get_or = [&](const char* n, int64_t d) {
    const auto it = p.find(n);
    return it == p.end() ? d : it->second;
  };
  const int64_t lanes = get_or("LANES", 1);
  return {{"clk_i", {"input", 1}},
          {"rst_ni", {"input", 1}},
          {"cmd_data_i", {"input", get_or("PORT_WORDS", 1) * 64}},
          {"cmd_valid_i", {"input", 1}},
          {"cmd_ready_o", {"output", 1}},
          {"pix_x_o", {"output", p.at("XY_BITS")}},
          {"pix_y_o", {"output", p.at("XY_BITS")}},
          {"pix_colour_o", {"output", lanes * p.at("CHANNELS") * p.at("OUT_BITS")}},
          {"pix_mask_o", {"output", lanes}},
          {"pix_eor_o", {"output", 1}},
          {"pix_valid_o", {"output", 1}},
          {"pix_ready_i", {"input", 1}}};
}

// Throws naming the netlist and the port when its top is not shade_unit with exactly the ports
// (direction, width) the glue drives.
void check_netlist_ports(const fs::path& netlist, const std::vector<VerilogParameter>& params) {
  std::istringstream is(read_text_file(netlist.string()));
  static const std::regex module_re(R"(^\s*module\s+(\S+?)\s*\()");
  static const std::regex port_re(
      R"(^\s*(input|output|inout)\s+(\[(-?[0-9]+):(-?[0-9]+)\]\s+)?(\S+)\s*;)");
  std::map<std::string, std::pair<std::string, int64_t>> found;
  int modules = 0;
  std::smatch m;
  for (std::string line; std::getline(is, line);) {
    if (std::regex_search(line, m, module_re)) {
      ++modules;
      if (m[1].str() != "shade_unit")
        throw std::runtime_error(netlist.string() + ": its module is '" + m[1].str() +
                                 "', not shade_unit");
    } else if (std::regex_search(line, m, port_re)) {
      const int64_t w =
          m[2].matched ? std::llabs(std::stoll(m[3].str()) - std::stoll(m[4].str())) + 1 : 1;
      found[m[5].str()] = {m[1].str(), w};
    }
  }
  if (modules != 1)
    throw std::runtime_error(netlist.string() + ": " + std::to_string(modules) +
                             " modules, expected the flat shade_unit alone");
  const auto want = expected_ports(params);
  for (const auto& [name, dw] : want) {
    const auto it = found.find(name);
    if (it == found.end())
      throw std::runtime_error(netlist.string() + ": shade_unit has no port " + name);
    if (it->second != dw)
      throw std::runtime_error(netlist.string() + ": port " + name + " is " + it->second.first +
                               " [" + std::to_string(it->second.second) + "], the RTL's is " +
                               dw.first + " [" + std::to_string(dw.second) + "]");
  }
  for (const auto& [name, dw] : found) {
    if (!want.count(name))
      throw std::runtime_error(netlist.string() + ": shade_unit has a port " + name +
                               " the RTL's port list (and the glue) does not");
  }
}

}  // namespace

std::string default_netlist_cache_dir() {
  return (fs::path(binary_dir()) / "netlist-cache").string();
}

UnitNetlist unit_netlist(const UnitConfig& unit, const NetlistOptions& o) {
  if (o.cache_dir.empty()) throw std::invalid_argument("unit_netlist: no cache folder");
  const std::vector<VerilogParameter> params = shade_unit_parameters(unit);  // validates
  const std::string chparam = yosys_chparam_args(params);
  const std::string yosys = flow_tools::find_tool(o.yosys, "yosys");
  std::string dir = o.rtl_dir;
  if (dir.empty()) {
    const char* other = std::getenv("SHADESIM_RTL_DIR");
    dir = other && *other ? std::string(other) : source_dir() + "/rtl";
  }
  const std::vector<fs::path> files = rtl_sources(dir);
  const std::string version = first_line(run_process({yosys, "-V"}, "").output);
  ContentHash h;
  h.add("shadesim-netlist-v1").add(chparam);
  for (const auto& f : files) {
    h.add(f.filename().string());
    h.add(read_text_file(f.string()));
  }
  const std::string flat = flat_script(), write = netlist_write_script();
  h.add(version).add(flat).add(write);
  UnitNetlist n;
  n.key = h.hex();
  const fs::path cache = fs::absolute(o.cache_dir);
  fs::create_directories(cache);
  const fs::path path = cache / ("netlist-" + n.key + ".v");
  const fs::path info = cache / ("netlist-" + n.key + ".json");
  n.path = path.string();
  auto read_info = [&] {
    const nlohmann::json j = nlohmann::json::parse(read_text_file(info.string()));
    n.cells = j.at("cells");
    n.flip_flops = j.at("flip_flops");
    n.gate_equivalents = j.at("gate_equivalents");
    n.ram_bits = j.at("ram_bits");
    n.seconds = j.at("seconds");
  };
  if (fs::exists(path) && fs::exists(info)) {
    read_info();
    n.from_cache = true;
    return n;
  }
  std::string tmpl = (cache / ("work-" + n.key + "-XXXXXX")).string();
  if (!::mkdtemp(tmpl.data())) throw std::runtime_error(tmpl + ": cannot create a work folder");
  const fs::path work = tmpl;
  const auto t0 = std::chrono::steady_clock::now();
  write_atomically(work / "netlist.ys", yosys_script(files, chparam, flat + write, work));
  run_tool({yosys, "-q", "-l", (work / "netlist.log").string(), (work / "netlist.ys").string()},
           work / "netlist.out", "yosys netlist of " + unit.to_string(), o.progress);
  check_netlist_ports(work / "netlist.v", params);
  const CmosStat c = read_cmos_stat((work / "flat_stat.json").string(), "shade_unit");
  n.cells = c.cells;
  n.flip_flops = c.flip_flops;
  n.ram_bits = ram_bits_of_parameters(params);  // the area report measures them with Yosys
  n.gate_equivalents = gate_equivalents(c.logic_transistors, c.flip_flops, n.ram_bits);
  n.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The netlist first, then its stat: an entry is complete once the .json exists.
  write_atomically(path, read_text_file((work / "netlist.v").string()));
  const nlohmann::json j = {{"unit", unit.to_string()},   {"key", n.key},
                            {"yosys_version", version},   {"cells", n.cells},
                            {"flip_flops", n.flip_flops}, {"gate_equivalents", n.gate_equivalents},
                            {"ram_bits", n.ram_bits},     {"seconds", n.seconds}};
  write_atomically(info, j.dump(2) + "\n");
  std::error_code ec;
  fs::remove_all(work, ec);
  return n;
}

}  // namespace shadesim
