// The error a unit reaches on a scene: the scene shaded on exactly that unit through the
// bit-accurate model and the double-precision reference, with render's metrics. `config`
// measures its derived unit with it; the derivation tries specular units with it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "host/metrics.h"
#include "model/unit_config.h"

namespace shadesim {

// budget_lsb: setup's Taylor budget (unset: the scene's); max_depth: its subdivision limit.
ErrorStats scene_error(const std::string& scene_path, const UnitConfig& config,
                       std::optional<double> budget_lsb, int max_depth);

// A frame's cycles on one unit (the closed-form cycle model: no gaps, no back-pressure).
struct SceneCycles {
  uint64_t cycles = 0, pixels = 0;
  double per_pixel() const {
    return pixels ? static_cast<double>(cycles) / static_cast<double>(pixels) : 0.0;
  }
};
SceneCycles scene_cycles(const std::string& scene_path, const UnitConfig& config,
                         std::optional<double> budget_lsb, int max_depth);

// The cycles per pixel of the scene on exactly `config` (the closed-form cycle model: no gaps, no
// back-pressure), as `shadesim cycles` counts them.
double scene_cycles_per_pixel(const std::string& scene_path, const UnitConfig& config,
                              std::optional<double> budget_lsb, int max_depth);

}  // namespace shadesim
