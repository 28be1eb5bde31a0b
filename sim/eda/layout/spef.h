// The SPEF that qflow's rc2dly writes from qrouter's routes, made readable by OpenSTA, and the
// counts that say whether every net of the routed netlist got its parasitics.
//
// rc2dly (qflow 1.3) departs from IEEE 1481 in three ways that OpenSTA 2019 trips over:
//   - internal nodes are written "12_3" where SPEF wants "*12:3" (net *12, node 3); OpenSTA then
//     warns "pin 12_3 not found" and drops the net's RC tree, leaving its pins' load only;
//   - the header says *C_UNIT 1 FF but the values are pF (a DFFPOSX1's CLK pin is written 0.00938,
//     osu018's liberty gives 0.00938 pF), so OpenSTA would see every wire a thousand times
//     lighter;
//   - the name map keeps Yosys's bit names ("eng_diffuse[9]") while blif2Verilog's netlist,
//     which the SPEF annotates, writes them "eng_diffuse_9_" (a bus port's bits stay "x[3]").
#pragma once

#include <set>
#include <string>

namespace shadesim {

// rc2dly's SPEF with the three fixes above. `bus_ports`: the netlist's vector ports ("cmd_data_i"),
// whose bit names stay as they are.
std::string fix_qflow_spef(const std::string& text, const std::set<std::string>& bus_ports);

// The nets a SPEF annotates (its *D_NET names, through the name map).
std::set<std::string> spef_net_names(const std::string& text);

// A flat structural Verilog netlist as blif2Verilog writes it: the nets its cell pins connect to
// (".A(net)", ".B(bus[3])"), and its vector ports' names.
struct VerilogNets {
  std::set<std::string> connected;
  std::set<std::string> bus_ports;
};
VerilogNets verilog_nets(const std::string& text);

}  // namespace shadesim
