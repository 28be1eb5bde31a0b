// Which specular unit raises the specular cosine t to the power n, and its widths.
//
// Every width here is a run-time value in the model and a Verilog parameter of the matching RTL
// module (same name, same order). Per-material choices (exponent, fitted parameters, the input
// shift) travel in the MATERIAL command's unit_params words, not here.
#pragma once

#include <string>

#include "model/fixed_point.h"

namespace shadesim {

enum class SpecularUnitKind {
  kIdeal,    // exact pow() of the fixed-point t in double: not hardware, the yardstick
  kLut,      // exponent look-up table (Bishop & Weimer)
  kSchlick,  // Schlick's rational form through a radix-2 divider
  kWpow,     // W_m shift-and-square (Romanyuk et al.)
};

std::string to_string(SpecularUnitKind kind);
// Throws std::invalid_argument naming `what` and the accepted names.
SpecularUnitKind parse_specular_unit(const std::string& name, const std::string& what);

// How a table address is formed from the address value: drop the fraction (truncate) or round
// to the nearest entry. Setup places the table's sample points to match (see exponent_lut.h).
enum class LutIndex { kTruncate, kNearest };
// (a) one table per exponent, indexed by t, reloaded on a material switch (Bishop & Weimer);
// (b) one shared table of exp(-U x), addressed by the pre-scaled series x = k (1 - t) / U.
enum class LutAddressing { kPerExponent, kShared };
// How setup fits a free per-exponent parameter (W_m's zeta, Schlick's n', the shared LUT's k).
enum class FitObjective {
  kNone,       // the paper's choice: zeta = n/m, n' = n, k = n
  kEpicentre,  // minimise the max relative error where t^n >= 0.5
  kAbsolute,   // minimise the max absolute error over t in [0, 1]
};
enum class UnitTiming {
  kPipelined,  // one pixel per cycle; one hardware stage per step
  kIterative,  // one shared stage reused: one pixel per `steps` cycles
};

std::string to_string(LutIndex v);
std::string to_string(LutAddressing v);
std::string to_string(FitObjective v);
std::string to_string(UnitTiming v);
LutIndex parse_lut_index(const std::string& s, const std::string& what);
LutAddressing parse_lut_addressing(const std::string& s, const std::string& what);
FitObjective parse_fit_objective(const std::string& s, const std::string& what);
UnitTiming parse_unit_timing(const std::string& s, const std::string& what);

// The units' fields: each is also one row of model/specular_units.cpp (JSON, CLI, Verilog, range).
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

struct SchlickConfig {
  int quotient_bits = 16;  // Q: quotient fraction bits = divider iterations
  int operand_bits = 24;   // fraction bits of numerator and denominator fed to the divider
  UnitTiming timing = UnitTiming::kIterative;
  FitObjective fit = FitObjective::kNone;  // kNone: Schlick's n; otherwise a fitted n'
};

struct WpowConfig {
  int max_m = 16;      // m: squaring stages = log2(m); 4, 8 or 16
  int base_bits = 16;  // B: fraction bits of the base and of every squaring result
  UnitTiming timing = UnitTiming::kPipelined;
  FitObjective fit = FitObjective::kNone;  // kNone: zeta = n/m
};

struct SpecularConfig {
  SpecularUnitKind kind = SpecularUnitKind::kIdeal;
  // The unit's output: the specular intensity in [0, 1].
  FixedFormat out{17, 1, false, Quantization::kTruncate, Overflow::kSaturate};

  LutConfig lut;
  SchlickConfig schlick;
  WpowConfig wpow;

  // How many series per light the unit consumes (Schlick needs numerator and denominator).
  int series_per_light() const;

  // Checks the selected unit's fields against their ranges (model/specular_units.h); throws
  // std::invalid_argument naming the field.
  void validate() const;
  // Short text, e.g. "wpow m=16 B=16 pipe fit=epicentre".
  std::string describe() const;
};

}  // namespace shadesim
