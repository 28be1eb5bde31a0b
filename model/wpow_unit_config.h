// The W_m unit's configurable fields (model/wpow_unit.h, rtl/wpow_unit.sv). Each field is one
// row of the "wpow" unit in model/specular_units.cpp (JSON key, CLI option, RTL slot, range); a
// new field is added here, there, and in the unit's own model and RTL.
#pragma once

#include "model/specular_enums.h"

namespace shadesim {

struct WpowConfig {
  int max_m = 16;      // m: squaring stages = log2(m); 4, 8 or 16
  int base_bits = 16;  // B: fraction bits of the base and of every squaring result
  UnitTiming timing = UnitTiming::kPipelined;
  // Registers per squaring, pipelined timing only: 1, or 2 (each square formed as two partial
  // squares and a cross product in one cycle, summed in the next: twice the squarings' latency,
  // a shorter clock path).
  int square_stages = 1;
  FitObjective fit = FitObjective::kNone;  // kNone: zeta = n/m
};

}  // namespace shadesim
