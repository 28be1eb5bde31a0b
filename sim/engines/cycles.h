// shadesim cycles's engine: cycles per pixel of a scene from the cycle model alone, with where
// they go (sim/engines/cycles.cpp). The command line that fills CyclesOptions: sim/cli/cycles.cpp.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "sim/engines/unit_widths.h"

namespace shadesim {

struct CyclesOptions {
  std::string scene;
  WidthOptions widths;
  std::string specular;
  int channels = 0;  // 0: what the scene needs
  int lights = 0;
  int port_words = 0;  // 0: not given (the unit's)
  int tri_queue = 0;
  int lanes = 0;
  int material_buffers = 0;
  std::string span_setup;      // empty: the unit's
  std::string diffuse_colour;  // empty: the unit's
  uint64_t seed = 1;
  int gap_pct = 0, max_gap = 1, stall_pct = 0;
  bool regress_stimulus = false;  // --regress-stimulus: regress's gaps and back-pressure
  std::string json_path;
  // --config as in effect (sim/engines/unit_choice.h): own, default, a build, a file.
  std::string config;
  bool clocked = false;  // also the clocked model when the closed form applies; must agree
  int worst = 5;         // setup-bound triangles listed
  // The target the no-gap figure is judged against: over it, a warning names the resource that
  // limits the unit (derive/cycles_limit.h, the words `config` uses). NaN: config's default,
  // 1.10 cycles per beat of the unit's lanes (cycles_target, derive/throughput_choice.h).
  double max_cycles_per_pixel = std::nan("");
  // > 0: the unit's clock in MHz; the report adds Mpixel/s = clock / cycles per pixel.
  double clock_mhz = 0;
};

// Prepares the frame on the unit, counts its cycles, prints them and writes --json; returns the
// exit code.
int run_cycles(const CyclesOptions& o);

}  // namespace shadesim
