#include "sim/eda/layout/spef.h"

#include <cctype>
#include <map>
#include <regex>
#include <sstream>
#include <vector>

namespace shadesim {
namespace {

bool all_digits(const std::string& s, size_t from, size_t to) {
  if (from >= to) return false;
  for (size_t i = from; i < to; ++i)
    if (!std::isdigit(static_cast<unsigned char>(s[i]))) return false;
  return true;
}

// "12_3" -> "*12:3"; anything else as it is.
std::string fix_node(const std::string& w) {
  const auto u = w.find('_');
  if (u == std::string::npos || !all_digits(w, 0, u) || !all_digits(w, u + 1, w.size())) return w;
  return "*" + w.substr(0, u) + ":" + w.substr(u + 1);
}

// blif2Verilog's rule for a bit name that is not a bus port's bit: brackets become '_'.
std::string verilog_name(std::string name, const std::set<std::string>& bus_ports) {
  const auto open = name.find('[');
  if (open == std::string::npos || bus_ports.count(name.substr(0, open))) return name;
  for (char& c : name)
    if (c == '[' || c == ']') c = '_';
  return name;
}

}  // namespace

std::string fix_qflow_spef(const std::string& text, const std::set<std::string>& bus_ports) {
  std::istringstream in(text);
  std::ostringstream out;
  std::string section;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::vector<std::string> t;
    for (std::string w; words >> w;) t.push_back(w);
    if (!t.empty() && t[0].size() > 1 && t[0][0] == '*' && !std::isdigit(t[0][1])) section = t[0];
    if (t.size() == 3 && t[0] == "*C_UNIT" && t[2] == "FF") {
      out << "*C_UNIT " << t[1] << " PF\n";
    } else if (section == "*NAME_MAP" && t.size() == 2 && t[0][0] == '*') {
      out << t[0] << ' ' << verilog_name(t[1], bus_ports) << '\n';
    } else if (section == "*CAP" || section == "*RES") {
      for (size_t i = 0; i < t.size(); ++i) out << (i ? " " : "") << fix_node(t[i]);
      out << '\n';
    } else {
      out << line << '\n';
    }
  }
  return out.str();
}

std::set<std::string> spef_net_names(const std::string& text) {
  std::istringstream in(text);
  std::map<std::string, std::string> names;
  std::set<std::string> nets;
  bool in_map = false;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string a, b;
    words >> a >> b;
    if (a == "*NAME_MAP") {
      in_map = true;
      continue;
    }
    if (in_map && a.size() > 1 && a[0] == '*' && std::isdigit(static_cast<unsigned char>(a[1]))) {
      names[a] = b;
      continue;
    }
    if (!a.empty() && a[0] == '*') in_map = false;
    if (a == "*D_NET") {
      const auto it = names.find(b);
      nets.insert(it == names.end() ? b : it->second);
    }
  }
  return nets;
}

VerilogNets verilog_nets(const std::string& text) {
  VerilogNets v;
  static const std::regex pin(R"(\.\w+\(\s*([^\s\)]+)\s*\))");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), pin); it != std::sregex_iterator();
       ++it)
    v.connected.insert((*it)[1]);
  static const std::regex bus(R"((?:input|output|inout)\s*\[\s*\d+\s*:\s*\d+\s*\]\s*(\w+))");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), bus); it != std::sregex_iterator();
       ++it)
    v.bus_ports.insert((*it)[1]);
  return v;
}

}  // namespace shadesim
