// Random command streams for co-simulation: random triangles (coefficients mostly in the range
// real shading produces, sometimes wild enough to overflow), spans from 1 pixel to the full
// screen width, back-to-back spans, material switches with TABLE loads. Uses model/ only.
// Configurations with a hardware specular unit get non-zero specular colours, random unit
// parameters and (LUT) a full table first, then partial TABLE reloads; the ideal unit's streams
// keep spec_colour = 0 (the RTL slot outputs 0 for it).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/command_stream.h"
#include "sim/harness/stimulus.h"

namespace shadesim {

struct StreamShape {
  int rows = 32;  // scanlines in the frame
  int max_spans_per_row = 4;
  int min_len = 1, max_len = 200;
  bool full_rows = false;       // one span covering the whole row
  double p_new_triangle = 0.6;  // per span
  double p_material = 0.08;     // per span (a TABLE load precedes it with p_table)
  double p_table = 0.5;
  double p_wild = 0.05;  // per triangle: coefficients/origins that overflow the series
  int frames = 1;        // frames of `rows` scanlines, each closed by END_FRAME
  // The corners of the value space (scenario "edge"): spans at the right and bottom screen
  // edges and across the full width 2^xy_bits, negative ambient (totals below 0) and large
  // diffuse terms (totals above 1), series that leave the series format (saturating in :sat
  // builds), every LUT / W_m shift and squaring count, fractional exponents.
  bool edge = false;
};

// A named workload: stream shape plus the default stimulus (gaps, back-pressure).
struct Scenario {
  std::string name;
  StreamShape shape;
  Stimulus stim;
};

// "mixed", "long", "short", "slow", "maxbp", "switch", "tiny" (~10,000 triangles), "edge"
// (StreamShape::edge over three frames, END_FRAME followed by more commands). Throws
// std::invalid_argument naming the accepted names.
Scenario scenario_by_name(const std::string& name);
std::vector<std::string> scenario_names();

CommandStream random_stream(const UnitConfig& config, const StreamShape& shape, uint64_t seed);

}  // namespace shadesim
