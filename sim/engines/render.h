// shadesim render's engine: a scene through the bit-accurate model beside the float reference,
// with the error and the cost (sim/engines/render.cpp). The command line that fills RenderOptions:
// sim/cli/render.cpp.
#pragma once

#include <cmath>
#include <string>

#include "sim/engines/unit_widths.h"

namespace shadesim {

struct RenderOptions {
  std::string scene;
  std::string out_dir;
  std::string json_path;
  std::string stream_path;
  // --config as in effect (sim/engines/unit_choice.h): own, default, a build, a file.
  std::string config;
  WidthOptions widths;
  double budget_lsb = std::nan("");
  int max_depth = 12;
  std::string specular;
  double heat_scale_lsb = 4.0;
  bool quiet = false;
  bool all_units = false;
};

// Shades the scene, prints the figures, writes the images, --json and --save-stream; returns the
// exit code.
int run_render(const RenderOptions& o);

// --all-units: every specular unit on the scene, units.png and units_error.png side by side, one
// line of error per unit; returns the exit code.
int run_all_units(const RenderOptions& o);

}  // namespace shadesim
