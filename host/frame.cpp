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

UnitConfig frame_unit(const Scene& scene, const std::string& scene_path,
                      const FrameOptions& options) {
  UnitConfig base = options.base;
  if (options.fixed_unit) {
    base.validate();
  } else if (options.specular_override) {
    base.specular.kind = *options.specular_override;
  } else {
    // One specular unit per build: the scene's materials must agree on it.
    base.specular.kind = scene.materials.front().unit;
    for (const auto& m : scene.materials) {
      if (m.unit != base.specular.kind) {
        throw std::invalid_argument(scene_path + ": materials '" + scene.materials.front().name +
                                    "' and '" + m.name + "' ask for different specular units (" +
                                    to_string(base.specular.kind) + ", " + to_string(m.unit) +
                                    "); one unit serves a frame - pick one with --specular");
      }
    }
  }
  UnitConfig config = options.fixed_unit ? base : config_for_scene(scene, base);  // returned: moved
  check_scene_fits(scene, config);
  if (xy_bits_for_image(scene.width, scene.height) > config.xy_bits) {
    throw std::invalid_argument(
        scene_path + ": image " + std::to_string(scene.width) + "x" + std::to_string(scene.height) +
        " does not fit xy_bits=" + std::to_string(config.xy_bits) +
        ": it needs xy_bits >= " + std::to_string(xy_bits_for_image(scene.width, scene.height)));
  }
  return config;
}

void prepare_geometry(const Scene& scene, const SetupOptions& setup_options, ProjectStats& project,
                      SetupResult& setup, Visibility& visibility, FrameTimings& timings) {
  auto t0 = std::chrono::steady_clock::now();
  auto projected = project_scene(scene, &project);
  // Grown by doubling, it can hold twice its triangles: a 4K frame's setup would run beside
  // hundreds of MB of slack.
  projected.shrink_to_fit();
  timings.project_s = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  setup = subdivide_and_setup(projected, scene, setup_options);
  timings.setup_s = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  visibility = resolve_visibility(setup.triangles, scene.width, scene.height);
  timings.visibility_s = seconds_since(t0);
}

PreparedFrame prepare_frame(const std::string& scene_path, const FrameOptions& options) {
  PreparedFrame f;
  auto t0 = std::chrono::steady_clock::now();
  f.scene = load_scene(scene_path);
  f.timings.load_s = seconds_since(t0);
  f.config = frame_unit(f.scene, scene_path, options);

  SetupOptions setup_options;
  setup_options.budget_lsb = options.budget_lsb;
  setup_options.max_depth = options.max_depth;
  setup_options.output_bits = f.config.out_bits;
  prepare_geometry(f.scene, setup_options, f.project, f.setup, f.visibility, f.timings);

  t0 = std::chrono::steady_clock::now();
  f.encoded = encode_frame(f.scene, f.config, f.setup, f.visibility);
  f.timings.encode_s = seconds_since(t0);
  return f;
}

}  // namespace shadesim
