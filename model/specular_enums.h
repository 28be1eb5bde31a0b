// The enums every specular unit shares: which unit, how a per-exponent parameter is fitted, and
// whether a unit is pipelined or iterative. Their own header so that each unit's config header
// (model/exponent_lut_config.h, schlick_divider_config.h, wpow_unit_config.h) can use them and
// model/specular_config.h can include those without an include cycle.
#pragma once

#include <string>

namespace shadesim {

enum class SpecularUnitKind {
  kIdeal,    // exact pow() of the fixed-point t in double: not hardware, the yardstick
  kLut,      // exponent look-up table (Bishop & Weimer)
  kSchlick,  // Schlick's rational form through a radix-2 divider
  kWpow,     // W_m shift-and-square (Romanyuk et al.)
  kNone,     // no specular term: no series, no unit, nothing added (a diffuse-only scene's unit)
};

std::string to_string(SpecularUnitKind kind);
// Throws std::invalid_argument naming `what` and the accepted names.
SpecularUnitKind parse_specular_unit(const std::string& name, const std::string& what);

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

std::string to_string(FitObjective v);
std::string to_string(UnitTiming v);
FitObjective parse_fit_objective(const std::string& s, const std::string& what);
UnitTiming parse_unit_timing(const std::string& s, const std::string& what);

}  // namespace shadesim
