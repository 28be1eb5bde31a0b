// Readers of what qflow's tools write for shadesim layout (sim/engines/layout.h): the routed DEF
// (qrouter), the cells' LEF sizes, magic's DRC count, netgen's LVS verdict. Pure text in, values
// out: the unit tests feed them small hand-written files.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace shadesim {

// A placed component of the DEF: its cell and lower-left corner in microns.
struct DefComponent {
  std::string name, cell;
  double x_um = 0, y_um = 0;
  char orient = 'N';  // the first letter of N, S, FN, FS ... (F: flipped)
  bool flipped = false;
};

// One straight routed segment (a point-only NEW ... VIA row gives none).
struct DefSegment {
  std::string layer;
  double x0_um = 0, y0_um = 0, x1_um = 0, y1_um = 0;
};

struct DefSummary {
  double units_per_micron = 0;
  double die_x0_um = 0, die_y0_um = 0, die_x1_um = 0, die_y1_um = 0;
  double core_x0_um = 0, core_y0_um = 0, core_x1_um = 0, core_y1_um = 0;  // the ROWs' extent
  int64_t components = 0, fill_cells = 0, pins = 0, nets = 0;
  double wire_length_um = 0;  // every routed segment of NETS (not SPECIALNETS: power)
  int64_t vias = 0;           // via names on NETS' routes
  std::map<std::string, double> wire_length_by_layer_um;
  std::vector<DefComponent> placed;
  std::vector<DefSegment> segments;  // NETS' segments, for the picture

  double die_area_um2() const { return (die_x1_um - die_x0_um) * (die_y1_um - die_y0_um); }
  double core_area_um2() const { return (core_x1_um - core_x0_um) * (core_y1_um - core_y0_um); }
};

// MACRO name -> SIZE w BY h (microns) of a LEF.
struct LefSize {
  double width_um = 0, height_um = 0;
};
std::map<std::string, LefSize> parse_lef_sizes(const std::string& text);

// Reads a DEF 5.x as qrouter writes it. The core is the extent of the placed cells (qflow writes
// no ROWs), each `sizes` wide and high (a cell missing from `sizes` counts as a point).
// Components of `fill_cell` (osu018: FILL) count as fill. Throws std::runtime_error naming
// `source` when UNITS or DIEAREA is missing.
DefSummary parse_def(const std::string& text, const std::string& source,
                     const std::map<std::string, LefSize>& sizes,
                     const std::string& fill_cell = "FILL");

// magic's DRC count from qflow's drc.log ("drc = N", or "No DRC errors found."); -1 if neither.
int64_t parse_magic_drc_count(const std::string& log);

// netgen's verdict from qflow's lvs.log or comp.out: clean when it says "Circuits match
// uniquely." and count_lvs.py's "Total errors = 0" (when present) agrees.
struct LvsResult {
  bool found = false;  // a verdict line was there at all
  bool clean = false;
  int64_t total_errors = -1;  // count_lvs.py's figure; -1 when absent
  std::string verdict;        // the line netgen wrote ("Circuits match uniquely.")
};
LvsResult parse_netgen_lvs(const std::string& log);

}  // namespace shadesim
