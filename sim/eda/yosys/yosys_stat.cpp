#include "sim/eda/yosys/yosys_stat.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "model/json_error.h"
#include "model/text_file.h"

namespace shadesim {
namespace {

using Json = nlohmann::json;

bool is_flip_flop_type(const std::string& cell_type) {
  return (cell_type.rfind("$_", 0) == 0 && cell_type.find("DFF") != std::string::npos) ||
         cell_type.rfind("SB_DFF", 0) == 0;
}

std::string text_spelling(const std::string& yosys_id) {
  return yosys_id.rfind('\\', 0) == 0 ? yosys_id.substr(1) : yosys_id;
}

// "13330" or "13330+" (the "+": cells without a CMOS cost).
void read_transistors(const std::string& field, StatSection& s) {
  const bool partial = !field.empty() && field.back() == '+';
  const std::string digits = field.substr(0, field.size() - (partial ? 1 : 0));
  if (digits.empty() || digits.size() > 18 ||
      !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    throw std::runtime_error("estimated_num_transistors \"" + field + "\" is not a count");
  s.transistors = std::stoll(digits);
  s.transistors_partial = partial;
}

StatSection read_stat_section(const Json& j, bool cmos) {
  StatSection s;
  s.cells = j.at("num_cells").get<int64_t>();
  for (const auto& [type, n] : j.at("num_cells_by_type").items())
    s.by_type[text_spelling(type)] += n.get<int64_t>();
  if (cmos) read_transistors(j.at("estimated_num_transistors").get<std::string>(), s);
  return s;
}

}  // namespace

StatReport read_stat_json(const std::filesystem::path& p, bool cmos) {
  const std::string text = read_text_file(p.string());
  Json j;
  try {
    j = Json::parse(text);
  } catch (const Json::exception& e) {
    const JsonTextError error = describe_json_error(text, e);
    throw std::runtime_error(p.string() + error.place + ": Yosys's stat -json is not valid JSON (" +
                             error.reason +
                             "); Yosys 0.23's is invalid when no top module is known or a module "
                             "below the top instantiates another");
  }
  StatReport r;
  std::string section = "the report";
  try {
    for (const auto& [name, m] : j.at("modules").items()) {
      section = "module " + text_spelling(name);
      r.modules[text_spelling(name)] = read_stat_section(m, cmos);
    }
    section = "design";
    if (j.contains("design")) r.design = read_stat_section(j.at("design"), cmos);
  } catch (const Json::exception& e) {
    throw std::runtime_error(p.string() + ": Yosys's stat -json, " + section + ": " +
                             describe_json_error(text, e).reason);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(p.string() + ": Yosys's stat -json, " + section + ": " + e.what());
  }
  if (r.modules.empty()) throw std::runtime_error(p.string() + ": no statistics from Yosys");
  return r;
}

std::string base_module_name(const std::string& yosys_name) {
  const std::string short_paramod = "$paramod\\";
  if (yosys_name.rfind(short_paramod, 0) == 0) {
    const auto end = yosys_name.find('\\', short_paramod.size());
    return yosys_name.substr(short_paramod.size(), end == std::string::npos
                                                       ? std::string::npos
                                                       : end - short_paramod.size());
  }
  const auto bs = yosys_name.rfind('\\');
  return bs == std::string::npos ? yosys_name : yosys_name.substr(bs + 1);
}

const std::string& stat_top_name(const StatReport& stat, const std::filesystem::path& p) {
  for (const auto& [name, sec] : stat.modules) {
    if (base_module_name(name) == "shade_unit") return name;
  }
  throw std::runtime_error(p.string() + ": Yosys statistics have no shade_unit module");
}

int64_t flip_flops_of(const StatSection& s) {
  int64_t n = 0;
  for (const auto& [type, count] : s.by_type) {
    if (is_flip_flop_type(type)) n += count;
  }
  return n;
}

int64_t flip_flop_transistors_of(const StatSection& s) {
  int64_t n = 0;
  for (const auto& [type, count] : s.by_type) {
    if (type == "$_DFF_P_" || type == "$_DFF_N_") n += count * kYosysCmosPlainDffTransistors;
  }
  return n;
}

CmosStat read_cmos_stat(const std::string& stat_file, const std::string& module) {
  const StatReport stat = read_stat_json(stat_file, true);
  const StatSection* sec = nullptr;
  if (!module.empty()) {
    for (const auto& [name, s] : stat.modules)
      if (base_module_name(name) == module) sec = &s;
  } else if (stat.modules.size() == 1) {
    sec = &stat.modules.begin()->second;
  } else if (stat.design) {
    sec = &*stat.design;
  }
  if (!sec) throw std::runtime_error(stat_file + ": no statistics for module '" + module + "'");
  CmosStat c;
  c.cells = sec->cells;
  c.transistors = sec->transistors;
  c.transistors_partial = sec->transistors_partial;
  c.flip_flops = flip_flops_of(*sec);
  c.logic_transistors = sec->transistors - flip_flop_transistors_of(*sec);
  return c;
}

int64_t read_memory_bits(const std::string& dump_file) {
  // "  cell $mem_v2 \name" then its "    parameter \SIZE n" and "    parameter \WIDTH n".
  // Only the tables count: register arrays (shade_unit's coef_q, ambient_q, ...) are $mem cells
  // too at this point, and are logic.
  std::istringstream is(read_text_file(dump_file));
  static const std::regex cell(R"(^\s*cell \$mem(_v2)? \\(\S*\.)?)" +
                               std::string(kTableMemoryName) + R"(\s*$)");
  static const std::regex any_cell(R"(^\s*cell )");
  static const std::regex param(R"(^\s*parameter \\(SIZE|WIDTH) ([0-9]+)\s*$)");
  static const std::regex end(R"(^\s*end\s*$)");
  int64_t total = 0, size = -1, width = -1;
  bool in_mem = false;
  auto close = [&] {
    if (!in_mem) return;
    if (size < 0 || width < 0)
      throw std::runtime_error(dump_file + ": a memory cell without SIZE or WIDTH");
    total += size * width;
    in_mem = false;
  };
  std::smatch m;
  for (std::string line; std::getline(is, line);) {
    if (std::regex_search(line, m, cell)) {
      close();
      in_mem = true;
      size = width = -1;
      // NOLINTNEXTLINE(bugprone-branch-clone): another cell ends a memory, as its end line does
    } else if (std::regex_search(line, m, any_cell)) {
      close();
    } else if (in_mem && std::regex_match(line, m, param)) {
      (m[1].str() == "SIZE" ? size : width) = std::stoll(m[2].str());
    } else if (in_mem && std::regex_match(line, end)) {
      close();
    }
  }
  close();
  return total;
}

LogicDepth read_logic_depth(const std::string& ltp_file) {
  // "Longest topological path in shade_unit (length=87):", then "    0: \\cmd_data_i [16]",
  // one "  n: wire (via cell)" line per cell, and "ff: \\q (via $dff)" where it ends at one.
  std::istringstream is(read_text_file(ltp_file));
  static const std::regex head(R"(Longest topological path in \S+ \(length=([0-9]+)\))");
  static const std::regex step(R"(^\s*([0-9]+|ff):\s*\\?(.*?)(\s+\(via .*\))?\s*$)");
  LogicDepth d;
  std::smatch m;
  bool in_path = false;
  for (std::string line; std::getline(is, line);) {
    if (std::regex_search(line, m, head)) {
      d.gates = std::stoll(m[1].str());
      in_path = true;
    } else if (in_path && std::regex_match(line, m, step)) {
      if (m[1] == "0") d.from = m[2];
      d.to = m[2];
    }
  }
  if (d.gates < 0) throw std::runtime_error(ltp_file + ": no 'Longest topological path' line");
  return d;
}

}  // namespace shadesim
