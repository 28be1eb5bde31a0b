// The one mapping from a UnitConfig to the Verilog parameters of rtl/shade_unit.sv.
//
// Every RTL build uses it: the named builds the tests share (sim/harness/builds.json), the
// builds `shadesim` Verilates on demand into its cache, `shadesim area` (Yosys chparam), the lint
// and Icarus checks. A parameter that shade_unit gains is added here once, and nowhere else.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/unit_config.h"

namespace shadesim {

// Deliberate faults for the harness's own tests (shade_unit FAULT_* parameters); -1 = off.
struct InjectedFaults {
  int lsb_row = -1;    // add 1 LSB to channel 0 of every pixel of this row
  int stall_row = -1;  // one extra engine stall before the last_in_row span of this row
  int hang_row = -1;   // the engines stop for good on this row: no more pixels (a hang)
  bool any() const { return lsb_row >= 0 || stall_row >= 0 || hang_row >= 0; }
};

struct VerilogParameter {
  std::string name;  // shade_unit's parameter name
  int64_t value;
};

// shade_unit's parameters for `unit` (validated first; throws std::invalid_argument naming the
// field). Host-only choices (LUT addressing and shared range, fit objectives, coefficient
// rounding and overflow) shape the command stream, not the hardware, and have no parameter.
std::vector<VerilogParameter> shade_unit_parameters(const UnitConfig& unit,
                                                    const InjectedFaults& faults = {});

// The same list in each tool's syntax.
std::vector<std::string> verilator_parameter_args(const std::vector<VerilogParameter>& params);
std::vector<std::string> iverilog_parameter_args(const std::vector<VerilogParameter>& params,
                                                 const std::string& root_module);
std::string yosys_chparam_args(const std::vector<VerilogParameter>& params);  // "-set N V ..."

}  // namespace shadesim
