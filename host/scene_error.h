// The error a unit reaches on a scene: the prepared scene re-encoded and shaded on exactly that
// unit through the bit-accurate model, against the double-precision reference, with render's
// metrics. `config` measures its derived unit with it; the derivation tries specular units with it.
#pragma once

#include <cstdint>

#include "host/metrics.h"
#include "host/prepared_scene.h"
#include "model/command_stream.h"
#include "model/unit_config.h"

namespace shadesim {

ErrorStats scene_error(const PreparedScene& frame, const UnitConfig& config);

// A frame's cycles on one unit (the closed-form cycle model: no gaps, no back-pressure), with its
// pixel beats (each up to `lanes` pixels of one span; not the port's beats): the default cycles
// target is per pixel beat.
struct SceneCycles {
  uint64_t cycles = 0, pixels = 0, pixel_beats = 0;
  double per_pixel() const {
    return pixels ? static_cast<double>(cycles) / static_cast<double>(pixels) : 0.0;
  }
};
SceneCycles scene_cycles(const PreparedScene& frame, const UnitConfig& config);

// A stream's pixel beats on `lanes` lanes: ceil(length / lanes) summed over its SPANs (the
// breakdown's `pixel` row with no stall). The throughput structure changes none of them.
uint64_t pixel_beats(const CommandStream& stream, int lanes);

}  // namespace shadesim
