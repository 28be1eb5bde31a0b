// shadesim config's engine: the smallest unit that shades the scenes within the error budget, with
// each field's derivation (sim/engines/config.cpp). The command line that fills ConfigOptions:
// sim/cli/config.cpp.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "sim/eda/common/build_paths.h"

namespace shadesim {

struct ConfigOptions {
  std::vector<std::string> scenes;
  double budget_lsb = std::nan("");
  int out_bits = 8;
  int port_words = 0;          // 0: derived (derive/throughput_choice.h)
  int tri_queue = 0;           // 0: derived
  std::string ideal_unit;      // empty: W_16, then the fallbacks that meet the budget
  std::string span_setup;      // empty: derived
  std::string diffuse_colour;  // empty: derived
  int lanes = 1;               // pixel lanes of the unit; the structure is derived for them
  // NaN: not given, the default target (1.10 cycles per beat of the lanes; cycles_target in
  // derive/throughput_choice.h)
  double max_cycles_per_pixel = std::nan("");
  std::string json_path;
  // --clock-mhz: time the unit where it will be built and pipeline it to reach the clock
  // (sim/engines/clock_target.h); 0: no clock target; negative: the site's default_clock_mhz.
  double clock_mhz = -1;
  std::string clock_target = "osu018";  // or ice40
  std::string liberty;                  // another library than osu018
  std::string area_cache = binary_dir() + "/area-cache";
};

// Derives the unit, prints it and each scene's error on it, writes --json; returns the exit code
// (1 when the unit misses the budget or the cycles target on a scene).
int run_config(const ConfigOptions& o);

}  // namespace shadesim
