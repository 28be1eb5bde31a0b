// shadesim area's generic flow: the unit flattened and mapped onto 2-input gates and MUXes
// (generic cells, the CMOS transistor estimate, GE, logic depth), its table memories, and the
// per-module breakdown. Its Yosys scripts are the .ys files beside this one; the conventions are in
// sim/eda/yosys/generic_area.h; the run and the cache in sim/engines/area_synthesis.cpp.
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

#include "model/exponent_lut.h"
#include "model/specular_units.h"
#include "sim/eda/common/tool_script.h"
#include "sim/eda/yosys/area_generic.h"
#include "sim/eda/yosys/yosys_stat.h"

namespace shadesim {
namespace generic_flow {

namespace fs = std::filesystem;

std::string flat_script() { return tool_script("sim/eda/yosys/flat.ys"); }
std::string memory_script() { return tool_script("sim/eda/yosys/memory.ys"); }
std::string breakdown_script() { return tool_script("sim/eda/yosys/breakdown.ys"); }
std::string netlist_write_script() { return tool_script("sim/eda/yosys/netlist_write.ys"); }

namespace {

// Per-module rows from the kept-hierarchy stat: each module with its submodules folded in,
// instance counts from the top down, then the top's own glue.
void read_breakdown(const StatReport& stat, const fs::path& p, GenericArea& r) {
  struct Totals {
    int64_t cells = 0, transistors = 0, ffs = 0, logic = 0;
  };
  std::map<std::string, Totals> memo;
  auto is_module = [&](const std::string& type) { return stat.modules.count(type) > 0; };
  std::function<Totals(const std::string&)> total = [&](const std::string& name) -> Totals {
    if (auto f = memo.find(name); f != memo.end()) return f->second;
    const StatSection& sec = stat.modules.at(name);
    Totals t{sec.cells, sec.transistors, flip_flops_of(sec),
             sec.transistors - flip_flop_transistors_of(sec)};
    for (const auto& [type, n] : sec.by_type) {
      if (!is_module(type)) continue;
      const Totals sub = total(type);
      t.cells += n * (sub.cells - 1);  // each instance counts as one cell in sec.cells
      t.transistors += n * sub.transistors;
      t.ffs += n * sub.ffs;
      t.logic += n * sub.logic;
    }
    return memo[name] = t;
  };
  const StatSection& top = stat.modules.at(stat_top_name(stat, p));
  r.modules.clear();
  int64_t glue_cells = top.cells;
  for (const auto& [type, n] : top.by_type) {
    if (!is_module(type)) continue;
    const Totals sub = total(type);
    glue_cells -= n;
    r.modules.push_back({base_module_name(type), static_cast<int>(n), sub.cells, sub.transistors,
                         sub.ffs, sub.logic});
  }
  r.modules.push_back({"shade_unit", 1, glue_cells, top.transistors, flip_flops_of(top),
                       top.transistors - flip_flop_transistors_of(top)});
  // The table memories sit in specular_unit (exponent_lut): their bits from the parameters,
  // checked against Yosys's count of the flat flow in check_ram().
  const int64_t ram_each = ram_bits_per_specular_unit(r.parameters);
  for (auto& m : r.modules) {
    if (m.module == "specular_unit") m.ram_bits_each = ram_each;
  }
  r.breakdown_cells = 0;
  for (const auto& m : r.modules) r.breakdown_cells += m.cells();
  if (stat.design && stat.design->cells != r.breakdown_cells) {
    throw std::runtime_error(p.string() + ": per-module cells sum to " +
                             std::to_string(r.breakdown_cells) + ", Yosys's design total is " +
                             std::to_string(stat.design->cells));
  }
}

}  // namespace

int64_t diffuse_series_of(const std::map<std::string, int64_t>& p) {
  const auto it = p.find("DIFFUSE_MULTIPLY");
  const bool multiply = it != p.end() && it->second == 1;
  return (multiply ? 1 : p.at("CHANNELS")) * p.at("LIGHTS");
}

// Every series the unit uses must survive synthesis (the ideal slot outputs 0, so its specular
// series legitimately go). Fewer means Yosys's netlist is not the unit the co-simulation checks
// and its area is understated: say so.
void check_series(GenericArea& r) {
  if (r.modules.empty()) {
    r.warnings.clear();
    if (r.ram_bits != r.ram_bits_expected) {
      r.warnings.push_back("Yosys found " + std::to_string(r.ram_bits) +
                           " table memory bits, the parameters give " +
                           std::to_string(r.ram_bits_expected));
    }
    return;
  }
  const std::map<std::string, int64_t> p = parameter_map(r.parameters);
  const int64_t kind = p.at("SPECULAR_KIND");
  const int64_t expected =
      diffuse_series_of(p) +
      (kind == 0 ? 0 : p.at("LIGHTS") * specular_config_of_parameters(p).series_per_light());
  // Each series has a span_setup, or with host span setup (SPAN_SETUP 1) engines of its own.
  const auto host = p.find("SPAN_SETUP");
  const bool host_setup = host != p.end() && host->second == 1;
  const auto lanes_it = p.find("LANES");
  const int64_t per_series = host_setup && lanes_it != p.end() ? lanes_it->second : 1;
  int64_t kept = 0;
  for (const auto& m : r.modules) {
    if (m.module == (host_setup ? "series_engine" : "span_setup")) kept += m.instances;
  }
  kept /= per_series;
  r.warnings.clear();
  if (r.ram_bits != r.ram_bits_expected) {
    r.warnings.push_back("Yosys found " + std::to_string(r.ram_bits) +
                         " table memory bits, the parameters give " +
                         std::to_string(r.ram_bits_expected) +
                         ": GE leaves out Yosys's count, the per-module rows the parameters'");
  }
  if (kept < expected) {
    r.warnings.push_back(
        "Yosys kept " + std::to_string(kept) + " of the " + std::to_string(expected) +
        " series (span_setup or, with host setup, series_engine instances) this unit uses: the "
        "others did not reach an output "
        "in Yosys's elaboration, so these figures are understated");
  }
}

void read_syntheses(const fs::path& work, bool breakdown, GenericArea& r) {
  {
    const fs::path p = work / "flat_stat.json";
    const StatReport stat = read_stat_json(p, true);
    const StatSection& top = stat.modules.at(stat_top_name(stat, p));
    r.cells = top.cells;
    r.transistors = top.transistors;
    r.transistors_partial = top.transistors_partial;
    r.flip_flops = flip_flops_of(top);
    r.logic_transistors = top.transistors - flip_flop_transistors_of(top);
    r.ram_bits = read_memory_bits((work / "flat_mem.txt").string());
    r.ram_bits_expected = ram_bits_of_parameters(r.parameters);
    r.logic_depth = read_logic_depth((work / "flat_ltp.txt").string());
  }
  if (breakdown) {
    const fs::path p = work / "breakdown_stat.json";
    read_breakdown(read_stat_json(p, true), p, r);
  }
  check_series(r);
}

}  // namespace generic_flow

int64_t gate_equivalents(int64_t logic_transistors, int64_t flip_flops, int64_t ram_bits) {
  return std::llround(static_cast<double>(logic_transistors) / kTransistorsPerGate) +
         kGatesPerFlipFlop * (flip_flops - ram_bits);
}

int64_t ModuleArea::gate_equivalents_each() const {
  return shadesim::gate_equivalents(logic_transistors_each, flip_flops_each, ram_bits_each);
}

int64_t GenericArea::gate_equivalents() const {
  return shadesim::gate_equivalents(logic_transistors, flip_flops, ram_bits);
}

int64_t ram_bits_per_specular_unit(const std::vector<VerilogParameter>& parameters) {
  const std::map<std::string, int64_t> p = parameter_map(parameters);
  const SpecularConfig unit = specular_config_of_parameters(p);
  if (unit.kind != SpecularUnitKind::kLut) return 0;
  const auto banks = p.find("MATERIAL_BUFFERS");
  return ExponentLut::table_bits(unit.lut) * (banks == p.end() ? 1 : banks->second);
}

int64_t ram_bits_of_parameters(const std::vector<VerilogParameter>& parameters) {
  const std::map<std::string, int64_t> p = parameter_map(parameters);
  const auto lanes = p.find("LANES");
  return ram_bits_per_specular_unit(parameters) * p.at("LIGHTS") *
         (lanes == p.end() ? 1 : lanes->second);
}

}  // namespace shadesim
