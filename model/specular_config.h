// Which specular unit raises the specular cosine t to the power n, and its widths.
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

struct SpecularConfig {
  SpecularUnitKind kind = SpecularUnitKind::kIdeal;
  // The unit's output: the specular intensity in [0, 1].
  FixedFormat out{17, 1, false, Quantization::kTruncate, Overflow::kSaturate};

  // How many series per light the unit consumes (Schlick needs numerator and denominator).
  int series_per_light() const { return kind == SpecularUnitKind::kSchlick ? 2 : 1; }
};

}  // namespace shadesim
