// derive_config, derived once per content (sim/engines/derivation_key.h has the key) and reused:
// every command that uses the scene's own unit (render, cycles, regress, area, explore: --config
// own, their default) and `shadesim config` itself go through cached_derive_config, so a scene
// is derived the first time any of them needs it, and read back after that.
//
// What is cached: the whole DerivedConfig (sim/engines/derived_json.h), not only the unit, because
// config prints every field's reason and the measurements; one entry serves both, and config
// with options other than the defaults gets entries of its own (the options are in the key).
// config's clock target (pipelining, --clock-mhz) is applied after, to the derivation read back;
// its synthesis has a cache of its own (the area cache).
//
// Where: $SHADESIM_UNIT_CACHE when set ("off": no cache); else <build>/unit-cache when the build
// directory shadesim was built in exists (beside rtl-cache and area-cache); else
// $XDG_CACHE_HOME/shadesim, else ~/.cache/shadesim. An entry is <key>.json: the DerivedConfig's
// JSON with "derivation": {"cache": {"key", "unit_xxh3", "inputs"}} added (the key's inputs, and
// the unit's own hash). Written to a temporary file and renamed into place, so a parallel
// shadesim sees a whole entry or none; two writing the same key write the same bytes.
//
// An entry that cannot be used (not JSON, truncated, another key inside, a unit that fails
// validate() or whose hash does not match) is named in a warning on `warnings`, derived again
// and overwritten: never a crash, never another unit.
#pragma once

#include <iostream>
#include <string>
#include <vector>

#include "derive/derive_config.h"

namespace shadesim {

// The folder described above; empty when caching is off or no folder can be named.
std::string default_unit_cache_dir();

struct CachedDerivation {
  DerivedConfig derived;
  std::string entry;    // the entry read or written; empty when not cached
  bool reused = false;  // read from `entry`, not derived now
  // For the unit line: "cached derivation, ENTRY", "derived, cached as ENTRY" or "derived".
  std::string origin() const;
};

// derive_config(scene_paths, options) through the cache in `cache_dir` (empty: no cache). Throws
// what derive_config throws; cache trouble (unreadable, unwritable) is only warned about.
CachedDerivation cached_derive_config(const std::vector<std::string>& scene_paths,
                                      const DeriveOptions& options, const std::string& cache_dir,
                                      std::ostream& warnings = std::cerr);
// The same, deriving (on a miss) on scenes the caller has prepared already (FrameSet's paths).
CachedDerivation cached_derive_config(const FrameSet& frames, const DeriveOptions& options,
                                      const std::string& cache_dir,
                                      std::ostream& warnings = std::cerr);

}  // namespace shadesim
