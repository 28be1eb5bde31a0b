// The error a unit reaches on a scene: the prepared scene re-encoded and shaded on exactly that
// unit through the bit-accurate model, against the double-precision reference, with render's
// metrics. `config` measures its derived unit with it; the derivation tries specular units with it.
#pragma once

#include <cstdint>

#include "host/metrics.h"
#include "host/prepared_scene.h"
#include "model/unit_config.h"

namespace shadesim {

ErrorStats scene_error(const PreparedScene& frame, const UnitConfig& config);

// A frame's cycles on one unit (the closed-form cycle model: no gaps, no back-pressure).
struct SceneCycles {
  uint64_t cycles = 0, pixels = 0;
  double per_pixel() const {
    return pixels ? static_cast<double>(cycles) / static_cast<double>(pixels) : 0.0;
  }
};
SceneCycles scene_cycles(const PreparedScene& frame, const UnitConfig& config);

}  // namespace shadesim
