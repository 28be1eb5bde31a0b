// The two files the power flow reads besides the activity (sim/eda/power/power.h): a Liberty
// library's cells (pin directions and functions, the state pins of ff / latch groups) and a flat
// mapped netlist as Yosys's write_verilog writes it (cell instances with named pin connections,
// assign aliases, input ports). Small readers of exactly that much, not general parsers.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace shadesim {

struct LibertyCellPins {
  std::map<std::string, std::string> direction;  // pin -> input | output | inout | internal
  std::map<std::string, std::string> function;   // output pin -> its function text
  std::string state_pin, state_pin_inv;          // ff (IQ, IQN) / latch (IQ, IQN); empty: logic
  bool sequential() const { return !state_pin.empty(); }
  // The output pins whose function is the state (or its inverse): Q, QN.
  std::vector<std::string> state_outputs() const;
  // Whether a state output carries the inverse (QN: "IQN" or "!IQ").
  bool inverted_output(const std::string& pin) const;
};

// Every cell of the library by name. Throws std::runtime_error when the file cannot be read or
// has no cell.
std::map<std::string, LibertyCellPins> read_liberty_cells(const std::string& liberty_path);

struct PinConnection {
  std::string pin;
  std::string net;   // the net's name ("u_decoder.pos_q[1]"), or a constant (1'h1 ...)
  std::string text;  // as written ("\\u_decoder.pos_q[1] "), for writing it back
};

struct NetlistInstance {
  std::string cell, name;
  std::vector<PinConnection> pins;
};

struct MappedNetlist {
  std::vector<NetlistInstance> instances;
  std::vector<std::pair<std::string, std::string>> assigns;  // lhs, rhs (single nets only)
  std::vector<std::string> inputs;  // input port bits ("cmd_data_i[3]"), declaration order
};

// Module `top` of a Yosys-written netlist (escaped names without their backslash: the
// flattened RTL names, "u_decoder.pos_q[1]"; a bus bit as "name[3]"). Throws std::runtime_error
// naming the file when it cannot be read or has no module `top`.
MappedNetlist read_mapped_netlist(const std::string& verilog_path, const std::string& top);

// A constant connection (1'h1, 1'b0, ...): its value, or -1 for a net.
int constant_value(const std::string& net);

// The names of each net: itself and every name joined to it by assigns (a -> {a, b, ...}).
std::map<std::string, std::vector<std::string>> net_aliases(const MappedNetlist& n);

// `verilog` (the text of a netlist read_mapped_netlist reads) with one new input port of module
// `top` per entry, each assigned to the net given as written (PinConnection::text): port -> net.
// Throws std::runtime_error when there is no module `top`.
std::string add_input_ports(const std::string& verilog, const std::string& top,
                            const std::vector<std::pair<std::string, std::string>>& ports);

}  // namespace shadesim
