#include "host/scene_error.h"

#include "host/frame.h"
#include "host/reference.h"
#include "model/cycle_estimate.h"
#include "model/shade_unit.h"

namespace shadesim {
namespace {

// The scene's frame on exactly `config`.
PreparedFrame frame_on(const std::string& scene_path, const UnitConfig& config,
                       std::optional<double> budget_lsb, int max_depth) {
  FrameOptions fo;
  fo.base = config;
  fo.fixed_unit = true;
  fo.budget_lsb = budget_lsb;
  fo.max_depth = max_depth;
  return prepare_frame(scene_path, fo);
}

}  // namespace

ErrorStats scene_error(const std::string& scene_path, const UnitConfig& config,
                       std::optional<double> budget_lsb, int max_depth) {
  const PreparedFrame f = frame_on(scene_path, config, budget_lsb, max_depth);
  const auto pixels = ShadeUnit(f.config).run(f.encoded.stream);
  const ReferenceImage ref =
      render_reference(f.setup.triangles, f.visibility, f.scene, f.config.channels);
  return compare_to_reference(pixels, ref.values, f.visibility.owner, f.scene.width, f.scene.height,
                              f.config.channels, f.config.out_bits)
      .stats;
}

SceneCycles scene_cycles(const std::string& scene_path, const UnitConfig& config,
                         std::optional<double> budget_lsb, int max_depth) {
  const PreparedFrame f = frame_on(scene_path, config, budget_lsb, max_depth);
  const CycleEstimateRun run =
      CycleEstimate(CycleConfig::of(f.config)).run(f.encoded.stream.encode());
  return {run.cycles, run.pixels};
}

double scene_cycles_per_pixel(const std::string& scene_path, const UnitConfig& config,
                              std::optional<double> budget_lsb, int max_depth) {
  return scene_cycles(scene_path, config, budget_lsb, max_depth).per_pixel();
}

}  // namespace shadesim
