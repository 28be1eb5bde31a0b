// Each specular unit described once: its configurable fields (JSON key, command-line option,
// Verilog parameter, range), its slot timing and its cost, in one table (specular_units.cpp).
//
// The code that handles units generically walks this table instead of naming fields:
//   - the UnitConfig JSON reader and writer (model/command_stream.cpp),
//   - the width options of the CLI (sim/cli/width_options.h),
//   - the Verilog parameter mapping (model/rtl_parameters.cpp),
//   - SpecularConfig::validate and describe (model/specular_config.cpp),
//   - SlotTiming::of (model/cycle_model.cpp; rtl/shade_pkg.sv spec_latency / spec_interval is
//     its RTL twin, checked against it in co-simulation),
//   - spec-error's cost columns and Pareto front (sim/engines/spec_error.cpp),
//   - the area estimate's size of the specular slot (sim/eda/yosys/area.cpp),
//   - the unit's knobs in `shadesim explore` (explore/explore.cpp).
// A unit's field is added to its config struct (model/exponent_lut_config.h,
// schlick_divider_config.h, wpow_unit_config.h) and one row here.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "model/specular_config.h"

namespace shadesim {

// One configurable field of a unit's config struct, stored as an int (an enum field by its
// code, which is also its Verilog code: the enums are declared in RTL order).
struct SpecularField {
  const char* key;   // JSON key under "specular.<unit>"; the name in errors is "<unit>.<key>"
  const char* cli;   // command-line option; fields sharing one are set together; "" = none
  const char* help;  // the option's help text
  // The field in the RTL: its localparam in the unit's module (rtl/exponent_lut.sv, ...), which
  // decodes it from slot `slot` of SPEC_PARAMS (shade_pkg::spec_slot); "" and -1 = host-only
  // (shapes the stream, not the RTL). The slot is explicit so reordering rows cannot move it.
  const char* verilog;
  int slot;
  int lo, hi;                           // accepted values (an enum field: its codes)
  bool power_of_two;                    // the value must also be a power of two
  std::string (*value_name)(int code);  // an enum field's names; nullptr for an integer field
  int (*get)(const SpecularConfig&);
  void (*set)(SpecularConfig&, int);
  // `shadesim explore` narrows the field over explore_lo .. explore_hi(starting value);
  // explore_hi nullptr = not explored.
  int explore_lo = 0;
  int (*explore_hi)(int start) = nullptr;

  bool is_enum() const { return value_name != nullptr; }
  bool in_range(int v) const;
  // "1..20", "a power of two 1..32", "one of truncate, nearest".
  std::string expected() const;
  // The value as text: the enum name or the integer.
  std::string text(const SpecularConfig& c) const;
  // An enum name or an integer; throws std::invalid_argument "`what`: ..." naming what was
  // expected. The range is not checked (validate and the callers do, naming the field).
  int parse(const std::string& text, const std::string& what) const;
};

// spec-error's cost columns. area is a proxy: ROM bit 1, full-adder bit kFullAdderArea.
struct SpecularCost {
  int64_t table_bits = 0;
  int multipliers = 0;
  int divider_iterations = 0;
  int cycles_per_pixel = 1;
  int latency = 0;
  int64_t reload_cycles = 0;  // cycles to reload the unit's table on a material switch
  double area = 0;
};
constexpr double kFullAdderArea = 8.0;

struct SpecularUnitDescriptor {
  SpecularUnitKind kind;
  const char* name;  // to_string(kind): JSON "kind", --specular, spec-error --units
  int verilog_kind;  // shade_unit's SPECULAR_KIND code
  // A unit module that approximates t^n in the RTL (its output rounding and SPEC_PARAMS are
  // Verilog parameters). False for the ideal yardstick (no RTL, no cost) and for none (no
  // specular term at all: no unit, no series).
  bool hardware;
  int series_per_light;  // specular series per light the unit consumes (none: 0)
  std::vector<SpecularField> fields;
  int (*latency)(const SpecularConfig&);   // slot latency in cycles
  int (*interval)(const SpecularConfig&);  // cycles per pixel
  SpecularCost (*cost)(const SpecularConfig&);
  std::string (*describe)(const SpecularConfig&);  // the text after the name, e.g. " A=10 B=8 trn"
  // What the slot's cells grow with, for the area estimate's scaling (sim/engines/area_report.h),
  // given the series width the slot reads; 0 for no hardware.
  double (*slot_size)(const SpecularConfig&, int series_wl);
  // Rules across the unit's fields, after each field's range: throws std::invalid_argument
  // "<unit>.<key> ..."; nullptr = none.
  void (*check)(const SpecularConfig&) = nullptr;

  std::string field_name(const SpecularField& f) const { return std::string(name) + "." + f.key; }
};

// Every unit, ideal first, in SpecularUnitKind order (none last).
const std::vector<SpecularUnitDescriptor>& specular_units();
const SpecularUnitDescriptor& specular_unit(SpecularUnitKind kind);
// The selected unit's costs; latency and cycles per pixel are the descriptor's (SlotTiming's).
SpecularCost specular_cost(const SpecularConfig& config);
// The unit a shade_unit parameter list builds (as parameter_map, model/rtl_parameters.h, gives
// it): SPECULAR_KIND and the unit's fields from their slots "SPEC_PARAMS[k]" (an absent slot
// keeps the model's default; host-only fields keep theirs). Throws std::invalid_argument when
// SPECULAR_KIND is missing or names no unit.
SpecularConfig specular_config_of_parameters(const std::map<std::string, int64_t>& params);
// nullptr when no unit has this name.
const SpecularUnitDescriptor* find_specular_unit(const std::string& name);
// "ideal, lut, schlick, wpow, none" (hardware_only: "lut, schlick, wpow").
std::string specular_unit_names(bool hardware_only = false);

}  // namespace shadesim
