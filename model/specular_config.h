// Which specular unit raises the specular cosine t to the power n, and its widths.
//
// Each unit's own fields live in its config header (model/exponent_lut_config.h,
// schlick_divider_config.h, wpow_unit_config.h) and its row of model/specular_units.cpp, which
// maps them to JSON, the CLI and the RTL. Per-material choices (exponent, fitted parameters, the
// input shift) travel in the MATERIAL command's unit_params words, not here.
#pragma once

#include <string>

#include "model/exponent_lut_config.h"
#include "model/fixed_point.h"
#include "model/schlick_divider_config.h"
#include "model/specular_enums.h"
#include "model/wpow_unit_config.h"

namespace shadesim {

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
