// The one mapping from a UnitConfig to the Verilog parameters of rtl/shade_unit.sv.
//
// Every RTL build uses it: the named builds the tests share (sim/harness/builds.json), the
// builds `shadesim` Verilates on demand into its cache, `shadesim area` (Yosys chparam), the lint
// and Icarus checks. A parameter that shade_unit gains is added here once, and nowhere else.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "model/unit_config.h"

namespace shadesim {

// SPEC_PARAMS, shade_unit's one parameter for the specular unit's own fields: kSpecSlots slots of
// kSpecSlotBits bits, slot k in bits [k * kSpecSlotBits +: kSpecSlotBits]. The C++ twin of
// rtl/shade_pkg.sv SpecSlots / SpecSlotW (tests/specular_units_test.cpp reads both).
constexpr int kSpecSlots = 8;
constexpr int kSpecSlotBits = 32;

struct VerilogParameter {
  VerilogParameter(std::string n, int64_t v) : name(std::move(n)), value(v) {}
  VerilogParameter(std::string n, std::vector<int64_t> packed)
      : name(std::move(n)), slots(std::move(packed)) {}

  std::string name;  // shade_unit's parameter name
  int64_t value = 0;
  // Non-empty: a packed parameter (SPEC_PARAMS) of slots; `value` is unused.
  std::vector<int64_t> slots;

  // As every tool reads it: "12", "-1", or a sized hex literal "256'h...0a" for a packed one
  // (Verilator -G, Icarus -P and Yosys chparam -set all accept it).
  std::string literal() const;
};

// shade_unit's parameters for `unit` (validated first; throws std::invalid_argument naming the
// field). The selected unit's fields go into SPEC_PARAMS, each in its row's slot
// (model/specular_units.cpp); a hardware unit always gets all kSpecSlots slots. Host-only choices
// (LUT addressing and shared range, fit objectives, coefficient rounding and overflow) shape the
// command stream, not the hardware, and have no parameter.
std::vector<VerilogParameter> shade_unit_parameters(const UnitConfig& unit);

// name -> value, a packed parameter as one entry per slot ("SPEC_PARAMS[3]"), so that comparing
// two lists compares every field.
std::map<std::string, int64_t> parameter_map(const std::vector<VerilogParameter>& params);

// The same list in each tool's syntax.
std::vector<std::string> verilator_parameter_args(const std::vector<VerilogParameter>& params);
std::vector<std::string> iverilog_parameter_args(const std::vector<VerilogParameter>& params,
                                                 const std::string& root_module);
std::string yosys_chparam_args(const std::vector<VerilogParameter>& params);  // "-set N V ..."

}  // namespace shadesim
