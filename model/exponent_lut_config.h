// The exponent LUT's configurable fields (model/exponent_lut.h, rtl/exponent_lut.sv). Each field
// is one row of the "lut" unit in model/specular_units.cpp (JSON key, CLI option, RTL slot,
// range); a new field is added here, there, and in the unit's own model and RTL.
#pragma once

#include <string>

#include "model/specular_enums.h"

namespace shadesim {

// How a table address is formed from the address value: drop the fraction (truncate) or round
// to the nearest entry. Setup places the table's sample points to match (see exponent_lut.h).
enum class LutIndex { kTruncate, kNearest };
// (a) one table per exponent, indexed by t, reloaded on a material switch (Bishop & Weimer);
// (b) one shared table of exp(-U x), addressed by the pre-scaled series x = k (1 - t) / U.
enum class LutAddressing { kPerExponent, kShared };

std::string to_string(LutIndex v);
std::string to_string(LutAddressing v);
LutIndex parse_lut_index(const std::string& s, const std::string& what);
LutAddressing parse_lut_addressing(const std::string& s, const std::string& what);

struct LutConfig {
  int addr_bits = 10;   // A: 2^A entries
  int entry_bits = 8;   // B: entry e means e / 2^B
  int interp_bits = 0;  // F: fraction bits of the address kept for linear interpolation; 0 = off
  LutIndex index = LutIndex::kTruncate;
  LutAddressing addressing = LutAddressing::kPerExponent;
  // Shared table only: the table spans u = k (1 - t) in [0, 2^range_log2).
  int shared_range_log2 = 4;
  FitObjective fit = FitObjective::kNone;  // shared table only: how k is chosen
};

}  // namespace shadesim
