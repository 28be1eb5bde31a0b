// What `shadesim render` measures at one unit configuration, end to end from the scene file: a
// fresh host setup (prepare_frame, not the derivation's PreparedScene), the bit-accurate model,
// the double reference, the comparison. Tests use it as the independent check of a
// configuration that another component (derive_config, explore) chose.
#pragma once

#include <optional>
#include <string>

#include "host/frame.h"
#include "host/metrics.h"
#include "host/reference.h"
#include "host/scene_error.h"
#include "model/cycle_estimate.h"
#include "model/shade_unit.h"

namespace shadesim {

inline PreparedFrame frame_at(const std::string& scene, const UnitConfig& config,
                              std::optional<double> budget_lsb = std::nullopt,
                              int max_depth = FrameOptions{}.max_depth) {
  FrameOptions fo;
  fo.base = config;
  fo.fixed_unit = true;
  fo.budget_lsb = budget_lsb;
  fo.max_depth = max_depth;
  return prepare_frame(scene, fo);
}

// The scene on exactly `config` against the reference (by default the scene's own budget,
// depth 12).
inline ErrorStats render_at(const std::string& scene, const UnitConfig& config,
                            std::optional<double> budget_lsb = std::nullopt,
                            int max_depth = FrameOptions{}.max_depth) {
  const PreparedFrame f = frame_at(scene, config, budget_lsb, max_depth);
  const auto pixels = ShadeUnit(f.config).run(f.encoded.stream);
  const ReferenceImage ref =
      render_reference(f.setup.triangles, f.visibility, f.scene, f.config.channels);
  return compare_to_reference(pixels, ref.values, f.visibility.owner, f.scene.width, f.scene.height,
                              f.config.channels, f.config.out_bits)
      .stats;
}

// The scene's cycles on exactly `config` (the closed-form cycle model), from a fresh frame.
inline SceneCycles cycles_at(const std::string& scene, const UnitConfig& config,
                             std::optional<double> budget_lsb = std::nullopt,
                             int max_depth = FrameOptions{}.max_depth) {
  const PreparedFrame f = frame_at(scene, config, budget_lsb, max_depth);
  const CycleEstimateRun run =
      CycleEstimate(CycleConfig::of(f.config)).run(f.encoded.stream.encode());
  return {run.cycles, run.pixels};
}

}  // namespace shadesim
