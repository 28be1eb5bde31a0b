// Widening a format the scenes measure too coarse. The width rules bound each
// format's error within its share of the budget, but a frame of many pixels still finds the
// code boundaries those shares sit on: where exact pow misses the budget on the derived formats
// and formats that lose nothing meet it, the formats hold the scenes back, and more fraction
// bits in them are measured, not bounded. The specular search then tries the units again on the
// widened formats (derive/specular_search.h, kWideningRule).
#pragma once

#include <optional>
#include <string>

#include "host/prepared_scene.h"
#include "model/unit_config.h"

namespace shadesim {

// Fraction bits added on top of the width rules' (0: none). Part of DeriveOptions (and of the
// derivation cache's key).
struct FormatWidening {
  int spec_colour = 0;
  int specular_out = 0;
  int series_coef = 0;  // to both series and coef (with_more_fraction_bits)
  // How it was measured, for the reasons: exact pow's error on the scenes before and after.
  int exact_before = 0, exact_after = 0;
  bool any() const { return spec_colour > 0 || specular_out > 0 || series_coef > 0; }
  // "spec_colour +4 fraction bits", formats joined by ", ".
  std::string describe() const;
};

// `unit` with widening's fraction bits added (integer bits, rounding and overflow unchanged).
UnitConfig widened(const UnitConfig& unit, const FormatWidening& widening);

// The widening that brings exact pow on `unit`'s formats within `allowed` output codes on every
// scene, measured: the single format that does so with the fewest bits (spec_colour, then the
// specular output, then series and coef at equal bits), else all three by the same bits.
// nullopt where even formats that lose nothing miss (the formats do not hold the scenes back).
std::optional<FormatWidening> widening_that_holds(const FrameSet& frames, const UnitConfig& unit,
                                                  int allowed);

}  // namespace shadesim
