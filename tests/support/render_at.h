// What `shadesim render` measures at one unit configuration, end to end from the scene file: a
// fresh host setup, the bit-accurate model, the double reference, the comparison. Tests use it as
// the independent check of a configuration that another component (derive_config, explore) chose.
#pragma once

#include <string>

#include "host/frame.h"
#include "host/metrics.h"
#include "host/scene_error.h"

namespace shadesim {

// The scene on exactly `config` against the reference (the scene's own budget, depth 12).
inline ErrorStats render_at(const std::string& scene, const UnitConfig& config) {
  return scene_error(scene, config, std::nullopt, FrameOptions{}.max_depth);
}

}  // namespace shadesim
