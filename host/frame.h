// The host pipeline for one frame: scene file -> projection -> triangle setup (with
// subdivision) -> visibility -> command stream. Shared by `render`, `regress` and `cycles`.
#pragma once

#include <optional>
#include <string>

#include "host/encode.h"
#include "host/raster.h"
#include "host/scene.h"
#include "host/triangle_setup.h"
#include "model/unit_config.h"

namespace shadesim {

struct FrameOptions {
  UnitConfig base;                                    // widths; structure comes from the scene
  std::optional<double> budget_lsb;                   // unset: the scene's error_budget_lsb
  int max_depth = 12;                                 // subdivision depth limit
  std::optional<SpecularUnitKind> specular_override;  // unset: the scene's (first) material unit
  // true: shade on exactly `base`, structure and specular unit included (a fixed RTL build); the
  // scene must fit it. false: take channels and lights from the scene.
  bool fixed_unit = false;
};

struct FrameTimings {
  double load_s = 0, project_s = 0, setup_s = 0, visibility_s = 0, encode_s = 0;
};

struct PreparedFrame {
  Scene scene;
  UnitConfig config;
  ProjectStats project;
  SetupResult setup;
  Visibility visibility;
  EncodedFrame encoded;
  FrameTimings timings;
};

// The fewest xy_bits whose unit holds a width x height image (every coordinate 0..size-1, so
// size <= 2^xy_bits); prepare_frame refuses a unit with fewer. Not clamped to UnitConfig's range.
int xy_bits_for_image(int width, int height);

// Throws SceneError for bad scene/mesh input and std::invalid_argument for impossible options.
PreparedFrame prepare_frame(const std::string& scene_path, const FrameOptions& options);

// The unit prepare_frame shades `scene` on: `options.base` as it is (fixed_unit), or with the
// scene's structure and specular unit. Throws std::invalid_argument naming `scene_path` when the
// unit cannot shade the scene or its materials ask for different specular units.
UnitConfig frame_unit(const Scene& scene, const std::string& scene_path,
                      const FrameOptions& options);

// The steps of a frame that no unit width changes: transform and clip, triangle setup with
// subdivision, visibility. Fills project, setup, visibility and their timings.
void prepare_geometry(const Scene& scene, const SetupOptions& setup_options, ProjectStats& project,
                      SetupResult& setup, Visibility& visibility, FrameTimings& timings);

}  // namespace shadesim
