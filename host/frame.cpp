#include "host/frame.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <stdexcept>

namespace shadesim {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int xy_bits_for_image(int width, int height) {
  const int64_t size = std::max(width, height);
  int b = 0;
  while ((int64_t{1} << b) < size) ++b;
  return b;
}

PreparedFrame prepare_frame(const std::string& scene_path, const FrameOptions& options) {
  PreparedFrame f;
  auto t0 = std::chrono::steady_clock::now();
  f.scene = load_scene(scene_path);
  f.timings.load_s = seconds_since(t0);

  UnitConfig base = options.base;
  if (options.fixed_unit) {
    base.validate();
  } else if (options.specular_override) {
    base.specular.kind = *options.specular_override;
  } else {
    // One specular unit per build: the scene's materials must agree on it.
    base.specular.kind = f.scene.materials.front().unit;
    for (const auto& m : f.scene.materials) {
      if (m.unit != base.specular.kind) {
        throw std::invalid_argument(scene_path + ": materials '" + f.scene.materials.front().name +
                                    "' and '" + m.name + "' ask for different specular units (" +
                                    to_string(base.specular.kind) + ", " + to_string(m.unit) +
                                    "); one unit serves a frame - pick one with --specular");
      }
    }
  }
  f.config = options.fixed_unit ? base : config_for_scene(f.scene, base);
  check_scene_fits(f.scene, f.config);
  if (xy_bits_for_image(f.scene.width, f.scene.height) > f.config.xy_bits) {
    throw std::invalid_argument(scene_path + ": image " + std::to_string(f.scene.width) + "x" +
                                std::to_string(f.scene.height) + " does not fit xy_bits=" +
                                std::to_string(f.config.xy_bits) + ": it needs xy_bits >= " +
                                std::to_string(xy_bits_for_image(f.scene.width, f.scene.height)));
  }

  t0 = std::chrono::steady_clock::now();
  const auto projected = project_scene(f.scene, &f.project);
  f.timings.project_s = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  SetupOptions setup_options;
  setup_options.budget_lsb = options.budget_lsb;
  setup_options.max_depth = options.max_depth;
  setup_options.output_bits = f.config.out_bits;
  f.setup = subdivide_and_setup(projected, f.scene, setup_options);
  f.timings.setup_s = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  f.visibility = resolve_visibility(f.setup.triangles, f.scene.width, f.scene.height);
  f.timings.visibility_s = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  f.encoded = encode_frame(f.scene, f.config, f.setup, f.visibility);
  f.timings.encode_s = seconds_since(t0);
  return f;
}

}  // namespace shadesim
