// The Schlick divider's configurable fields (model/schlick_divider.h, rtl/schlick_divider.sv).
// Each field is one row of the "schlick" unit in model/specular_units.cpp (JSON key, CLI option,
// RTL slot, range); a new field is added here, there, and in the unit's own model and RTL.
#pragma once

#include "model/specular_enums.h"

namespace shadesim {

struct SchlickConfig {
  int quotient_bits = 16;  // Q: quotient fraction bits = divider iterations
  int operand_bits = 24;   // fraction bits of numerator and denominator fed to the divider
  UnitTiming timing = UnitTiming::kIterative;
  FitObjective fit = FitObjective::kNone;  // kNone: Schlick's n; otherwise a fitted n'
};

}  // namespace shadesim
