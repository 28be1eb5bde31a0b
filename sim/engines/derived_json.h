// A whole DerivedConfig (derive/derive_config.h) as JSON and back, for the derivation cache
// (sim/engines/derivation_cache.h): the unit, and all `shadesim config` prints beside it (each
// field's reason, the measurements, the cycles misses), so a cached derivation prints as a fresh
// one does.
//
// The unit's fields sit at the top level exactly as config_to_json writes them, so an entry is a
// UnitConfig file: load_unit_config and `--config FILE` read it and ignore the rest, which is
// under "derivation" (as in the file `shadesim config --json` writes):
//   "derivation": {"reasons": [{"field", "value", "reason"}...], "measured": {...every
//                  ConfigMeasurements field...}, "substitute": bool, "cycles_misses": [...]}
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "derive/derive_config.h"

namespace shadesim {

// Throws std::domain_error when a measurement is not finite (JSON has no infinity or NaN; such a
// derivation is not cached).
nlohmann::json derived_to_json(const DerivedConfig& derived);

// Throws std::runtime_error naming `source` and what is missing or wrong, and
// UnitConfigFileError (a std::runtime_error) when the unit's fields are no valid UnitConfig.
DerivedConfig derived_from_json(const nlohmann::json& j, const std::string& source);

}  // namespace shadesim
