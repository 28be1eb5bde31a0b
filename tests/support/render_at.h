// What `shadesim render` measures at one unit configuration, end to end from the scene file: a
// fresh host setup, the bit-accurate model, the double reference, the comparison. Tests use it as
// the independent check of a configuration that another component (derive_config, explore) chose.
#pragma once

#include <string>

#include "host/frame.h"
#include "host/metrics.h"
#include "host/reference.h"
#include "model/shade_unit.h"

namespace shadesim {

inline ErrorStats render_at(const std::string& scene, const UnitConfig& config) {
  FrameOptions o;
  o.base = config;
  o.fixed_unit = true;
  const PreparedFrame f = prepare_frame(scene, o);
  const auto pixels = ShadeUnit(f.config).run(f.encoded.stream);
  const ReferenceImage ref =
      render_reference(f.setup.triangles, f.visibility, f.scene, f.config.channels);
  return compare_to_reference(pixels, ref.values, f.visibility.owner, f.scene.width, f.scene.height,
                              f.config.channels, f.config.out_bits)
      .stats;
}

}  // namespace shadesim
