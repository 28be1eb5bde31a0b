// The specular units `shadesim config` tries for a scene, smallest first: the fields of the kind
// the materials name (a LUT's entries, entry bits, interpolation and addressing; Schlick's
// widths and fitted n'; W_m's squarings, base bits and fitted zeta), or for `ideal` the
// hardware units standing in for exact pow. derive_config measures each on the scenes and keeps
// the first within the budget (derive/derive_config.h).
#pragma once

#include <vector>

#include "model/specular_config.h"

namespace shadesim {

// The candidates for scenes naming `named` (a hardware kind), the kind's defaults first, then
// in order of table bits, squarings or divider width. Empty for kNone and kIdeal (the ideal
// stand-ins are DeriveOptions::ideal_substitute and ideal_fallbacks).
std::vector<SpecularConfig> named_unit_candidates(SpecularUnitKind named);

// The hardware units standing in for `ideal` after the first (W_16 B=16): W_16 with zeta fitted
// for the absolute error, W_32, W_32 fitted, then interpolating LUTs.
std::vector<SpecularConfig> ideal_stand_ins();

}  // namespace shadesim
