#include "sim/eda/ice40/area_ice40.h"

#include <algorithm>
#include <iomanip>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "model/digit_grouping.h"
#include "model/text_file.h"
#include "sim/eda/common/tool_script.h"
#include "sim/eda/yosys/yosys_stat.h"

namespace shadesim::ice40_flow {
namespace {

namespace fs = std::filesystem;

// HX8K in its largest package (206 I/O). --freq is the target nextpnr's timing-driven placement
// and routing work toward: 60 MHz, above the iCE40's 50 MHz clock target (default_clock_mhz),
// so the critical paths get its effort (at a target every path meets with slack, none is worked
// on); the reported Fmax is what the routed design reaches either way.
constexpr const char* kPnrArgs = "--hx8k --package ct256 --freq 60 --timing-allow-fail";
// Fmax is measured out of context: the unit inside fmax_shell (fmax_shell_verilog below), which
// shifts one input pin into every input port and folds every output port into one output pin
// through a chain of registers, so no I/O count limits placement (a four-word command port
// alone is 256 pins, more than an HX8K has) and every output still matters. Only the unit's
// own logic lies between two registers of the shell on a path longer than one LUT. Its Yosys
// script is fmax_shell.ys beside this file.
std::string fmax_shell_script() { return tool_script("sim/eda/ice40/fmax_shell.ys"); }
constexpr const char* kShellVersion = "fmax_shell v2";

int64_t parameter_value(const std::vector<VerilogParameter>& ps, const char* name) {
  for (const auto& p : ps)
    if (p.name == name) return p.value;
  throw std::logic_error(std::string("area: no parameter ") + name);
}

// nextpnr's last "Max frequency for clock ..." line (the post-route one).
std::optional<double> read_fmax(const std::string& log) {
  static const std::regex re(R"(Max frequency for clock[^:]*:\s*([0-9.]+)\s*MHz)");
  std::optional<double> f;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), re); it != std::sregex_iterator();
       ++it) {
    f = std::stod((*it)[1].str());
  }
  return f;
}

}  // namespace

std::string read_critical_path(const std::string& log) {
  const size_t at = log.rfind("Critical path report for clock");
  if (at == std::string::npos) return "";
  // Nets, not cells: nextpnr names a packed cell after whatever ABC called its LUT, while the
  // nets keep the RTL's names (the first leaves the launching register, the last enters the
  // capturing one).
  static const std::regex net(R"(Info:\s+[0-9.-]+\s+[0-9.-]+\s+Net\s+(\S+))");
  static const std::regex split(R"(Info:\s+([0-9.]+) ns logic, ([0-9.]+) ns routing)");
  const size_t end = log.find("\n\n", at);
  const std::string block = log.substr(at, end == std::string::npos ? std::string::npos : end - at);
  std::string from, to, times;
  for (auto it = std::sregex_iterator(block.begin(), block.end(), net);
       it != std::sregex_iterator(); ++it) {
    if (from.empty()) from = (*it)[1].str();
    to = (*it)[1].str();
  }
  std::smatch m;
  if (std::regex_search(block, m, split))
    times = " (" + m[1].str() + " ns logic, " + m[2].str() + " ns routing)";
  if (from.empty()) return "";
  return "net " + from + " -> net " + to + times;
}

namespace {

void read_ice40_stat(const StatSection& s, Ice40Area& a) {
  for (const auto& [type, n] : s.by_type) {
    if (type == "SB_LUT4")
      a.lut4 += n;
    else if (type.rfind("SB_DFF", 0) == 0)
      a.dff += n;
    else if (type == "SB_CARRY")
      a.carry += n;
    else if (type.rfind("SB_RAM40_4K", 0) == 0)
      a.ram4k += n;
  }
}

// Whether the synth_ice40 counts alone rule out an HX8K (each logic cell holds one LUT4 and one
// DFF). Passing this check is necessary, not sufficient: nextpnr has the last word.
void check_fit(Ice40Area& a) {
  const int64_t need = std::max(a.lut4, a.dff);
  std::ostringstream os;
  if (need > Ice40Area::kHx8kLogicCells) {
    a.fits_hx8k = false;
    os << "does not fit an iCE40 HX8K: needs at least " << grouped(need) << " logic cells ("
       << (a.lut4 >= a.dff ? "LUT4s" : "DFFs") << "), the HX8K has "
       << grouped(Ice40Area::kHx8kLogicCells) << " (" << grouped(need - Ice40Area::kHx8kLogicCells)
       << " over, " << std::fixed << std::setprecision(2)
       << static_cast<double>(need) / Ice40Area::kHx8kLogicCells << "x)";
  } else if (a.ram4k > Ice40Area::kHx8kRam4k) {
    a.fits_hx8k = false;
    os << "does not fit an iCE40 HX8K: needs " << a.ram4k << " RAM40_4K blocks, the HX8K has "
       << Ice40Area::kHx8kRam4k;
  } else {
    a.fits_hx8k = true;
    os << "fits an iCE40 HX8K by LUT4/DFF count (" << grouped(need) << " of "
       << grouped(Ice40Area::kHx8kLogicCells) << " logic cells)";
  }
  a.fit_note = os.str();
}

}  // namespace

std::string synth_script() { return tool_script("sim/eda/ice40/synth_ice40.ys"); }

void add_place_and_route_recipe(ContentHash& key) {
  key.add(kPnrArgs);
  key.add(kShellVersion).add(fmax_shell_script());
}

void read_synthesis(const fs::path& work, Ice40Area& a) {
  const fs::path p = work / "ice40_stat.json";  // no -tech: no transistor estimate
  const StatReport stat = read_stat_json(p, false);
  read_ice40_stat(stat.modules.at(stat_top_name(stat, p)), a);
  check_fit(a);
}

std::string fmax_shell_verilog(const std::vector<VerilogParameter>& parameters) {
  const int64_t cmd_w = parameter_value(parameters, "PORT_WORDS") * 64;
  const int64_t xy = parameter_value(parameters, "XY_BITS");
  const int64_t lanes = parameter_value(parameters, "LANES");
  const int64_t colour_w =
      lanes * parameter_value(parameters, "CHANNELS") * parameter_value(parameters, "OUT_BITS");
  const int64_t in_w = cmd_w + 2;                           // cmd_data, cmd_valid, pix_ready
  const int64_t out_w = 1 + 2 * xy + colour_w + lanes + 2;  // ready, x, y, colour, mask, eor, valid
  std::ostringstream v;
  v << "// Generated by shadesim area (sim/eda/ice40/area_ice40.cpp): the out-of-context Fmax "
       "shell.\n"
    << "module fmax_shell (input logic clk_i, input logic rst_ni, input logic in_i,\n"
    << "                   output logic out_o);\n"
    << "  logic [" << in_w - 1 << ":0] in_q;\n"
    << "  logic [" << out_w - 1 << ":0] o, chain_q;\n"
    << "  always_ff @(posedge clk_i) in_q <= {in_q[" << in_w - 2 << ":0], in_i};\n"
    << "  always_ff @(posedge clk_i) chain_q <= {chain_q[" << out_w - 2 << ":0], 1'b0} ^ o;\n"
    << "  assign out_o = chain_q[" << out_w - 1 << "];\n"
    << "  shade_unit #(\n";
  for (size_t i = 0; i < parameters.size(); ++i)
    v << "    ." << parameters[i].name << "(" << parameters[i].literal() << ")"
      << (i + 1 < parameters.size() ? "," : "") << "\n";
  v << "  ) u_unit (\n"
    << "    .clk_i(clk_i), .rst_ni(rst_ni),\n"
    << "    .cmd_data_i(in_q[" << cmd_w - 1 << ":0]), .cmd_valid_i(in_q[" << cmd_w << "]),\n"
    << "    .pix_ready_i(in_q[" << cmd_w + 1 << "]),\n"
    << "    .cmd_ready_o(o[0]), .pix_x_o(o[" << xy << ":1]), .pix_y_o(o[" << 2 * xy << ":" << xy + 1
    << "]),\n"
    << "    .pix_colour_o(o[" << 2 * xy + colour_w << ":" << 2 * xy + 1 << "]),\n"
    << "    .pix_mask_o(o[" << 2 * xy + colour_w + lanes << ":" << 2 * xy + colour_w + 1 << "]),\n"
    << "    .pix_eor_o(o[" << out_w - 2 << "]), .pix_valid_o(o[" << out_w - 1 << "]));\n"
    << "endmodule\n";
  return v.str();
}

bool place_and_route(const FlowInputs& in, const std::string& nextpnr,
                     const std::vector<VerilogParameter>& parameters, const fs::path& work,
                     std::ostream* progress, Ice40Area& a) {
  std::vector<std::string> argv = {nextpnr};
  std::istringstream args(kPnrArgs);
  for (std::string arg; args >> arg;) argv.push_back(arg);
  argv.insert(argv.end(), {"--json", (work / "shell.json").string(), "--asc",
                           (work / "shell.asc").string(), "-l", (work / "pnr.log").string()});
  // The shell's synthesis failing is the flow's fault, not a finding: it throws.
  flow_tools::write_atomically(work / "fmax_shell.sv", fmax_shell_verilog(parameters));
  std::vector<fs::path> shell_files = in.files;
  shell_files.push_back(work / "fmax_shell.sv");
  const fs::path script = work / "shell.ys";
  flow_tools::write_atomically(
      script, flow_tools::yosys_script(shell_files, "", fmax_shell_script(), work));
  flow_tools::run_tool({in.yosys, "-q", "-l", (work / "shell.log").string(), script.string()},
                       work / "shell.out", "yosys synth_ice40 of the unit in its Fmax shell",
                       progress);
  try {
    flow_tools::run_tool(argv, work / "pnr.out", "nextpnr-ice40 place and route (HX8K)", progress);
    const std::string log = read_text_file((work / "pnr.log").string());
    a.fmax_mhz = read_fmax(log);
    if (!a.fmax_mhz) a.pnr_note = "nextpnr-ice40 reported no Fmax";
    if (a.fmax_mhz) a.critical_path = read_critical_path(log);
    return false;
  } catch (const std::runtime_error& e) {
    // A failed placement (no room once packed, too many I/O) is a finding about the design.
    a.fits_hx8k = false;
    a.fit_note = "does not fit an iCE40 HX8K: nextpnr-ice40 failed (log " +
                 (work / "pnr.log").string() + ")";
    a.pnr_note = "no Fmax: " + first_line(e.what());
    return true;
  }
}

}  // namespace shadesim::ice40_flow
