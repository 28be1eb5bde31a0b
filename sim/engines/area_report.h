// Area and timing of one shading unit configuration, measured by synthesising rtl/shade_unit.sv
// with Yosys (and placing and routing it with nextpnr-ice40 where it fits an iCE40 HX8K).
//
// The parameters come only from shade_unit_parameters() (model/rtl_parameters.h), passed to
// Yosys with yosys_chparam_args(). Three flows run on the same parameters:
//   flat      read rtl/files.f's sources in its order (a tree without the list, --rtl-dir: all
//             *.sv, packages first, then by name; ABC's result depends on the netlist's order,
//             by about 0.5 % in cells, so the order is fixed); chparam; synth -flatten; abc -g
//             AND,NAND,OR,NOR,XOR,XNOR,MUX; stat -tech cmos: the unit's generic cells, transistor
//             estimate, flip-flops. unit_netlist() writes this same netlist (write_verilog
//             -noattr) for simulation.
//   memory    synth -flatten -run :fine and a dump of the table memories (RAM bits, below).
//   breakdown the same with the datapath modules kept (keep_hierarchy): per-module cells.
//   ice40     synth_ice40 (flattened): SB_LUT4, SB_DFF*, SB_CARRY, SB_RAM40_4K counts.
//   pnr       nextpnr-ice40 --hx8k on the synth_ice40 netlist: Fmax of clk_i. Skipped (and said
//             so) when the LUT4 or DFF count alone exceeds the HX8K's 7,680 logic cells.
//
// Where each lives: the generic flow (flat, memory, breakdown) sim/eda/yosys/area.cpp and its
// figures and GE convention sim/eda/yosys/generic_area.h, the iCE40 flow and its Fmax shell
// sim/eda/ice40/area_ice40.h, the liberty flow sim/eda/sta/liberty_flow.h, Yosys's reports
// sim/eda/yosys/yosys_stat.h, the simulation netlist sim/eda/yosys/unit_netlist.h; the run that
// sets the flows side by side and its cache sim/engines/area_synthesis.cpp, the JSON
// sim/engines/area_report_json.cpp and the estimate sim/engines/area_estimate.cpp.
//
// Results are cached per configuration in AreaOptions::cache_dir, one JSON file per key; the
// key hashes the parameter list, the RTL sources' contents, the Yosys (and nextpnr) version
// and the script text, so any of them changing gives a fresh run. Entries are written to a
// temporary file and renamed into place: a concurrent run sees a whole entry or none.
//
// Cost: a cold run takes minutes (the report's `seconds` and `cpu_seconds`; README figures), far
// too slow for one run per point of a width sweep. So a sweep measures ONE configuration with
// unit_area() (its anchor: cached after the first run) and gets every other point from
// estimate_area() below, which scales the anchor's measured per-module cells by each module's
// size from its parameters. It is an estimate and must be labelled so wherever it is shown;
// `shadesim area` prints the estimate of each measured unit from the other cached anchors beside
// the measurement, i.e. the estimate's error against held-out Yosys runs.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/rtl_parameters.h"
#include "model/unit_config.h"
#include "sim/eda/common/missing_tool.h"
#include "sim/eda/ice40/area_ice40.h"
#include "sim/eda/sta/liberty_flow.h"
#include "sim/eda/yosys/generic_area.h"

namespace shadesim {

struct AreaOptions {
  std::string rtl_dir;          // folder with rtl/*.sv; empty: this source tree's rtl/
  std::string cache_dir;        // empty: no cache (always synthesise)
  bool place_and_route = true;  // run nextpnr-ice40 for Fmax when the design fits
  bool breakdown = true;        // also run the per-module (kept hierarchy) synthesis
  std::string yosys = "yosys";  // program names (looked up on PATH) or paths
  std::string nextpnr = "nextpnr-ice40";
  // The unit mapped onto a standard-cell library and timed with OpenSTA
  // (sim/eda/sta/liberty_flow.h); unset: not run. Cached apart from the rest (its own key), so a
  // new library costs only it.
  std::optional<LibertyOptions> liberty;
  std::ostream* progress = nullptr;  // one updating progress line while tools run; null: quiet
};

// Every flow of `shadesim area` on one unit: the generic flow's figures (the base), the iCE40
// flow's and, when asked for, the liberty flow's.
struct AreaReport : GenericArea {
  std::string key;  // cache key (hex)
  bool from_cache = false;
  std::string yosys_version, nextpnr_version;
  Ice40Area ice40;
  double seconds = 0;      // wall time of the run that produced the figures (not of a cache hit)
  double cpu_seconds = 0;  // CPU time of its tools (all syntheses and nextpnr together, and the
                           // liberty flow's when it ran beside them)
  std::optional<LibertyReport> liberty;  // with AreaOptions::liberty
};

// Synthesises `unit` (throws std::invalid_argument for an invalid config, MissingToolError,
// std::runtime_error naming the log when a tool fails).
AreaReport unit_area(const UnitConfig& unit, const AreaOptions& options);

// A fast area figure for a unit that has not been synthesised: an anchor (a measured report with
// the per-module breakdown and the same specular unit kind) scaled module by module:
//   cells(m) = anchor cells_each(m) * size_m(unit) / size_m(anchor) * instances_m(unit)
// with size_m a structural count from the parameters (span_setup: product bits that reach the
// series register; series_engine: series width; pixel_combine: multiplier and adder bits;
// specular_unit: table bits / divider or squarer array; glue: register bits), summed and scaled
// by the anchor's flat/kept-hierarchy ratio. The anchor is the one with the fewest parameters
// that differ; reports with warnings (series Yosys removed) are no anchors. LUT4s scale with
// the cells. Throws std::runtime_error when no anchor has the
// unit's specular kind (run unit_area on one such configuration first).
struct AreaEstimate {
  int64_t cells = 0;             // estimated flat generic cells
  int64_t gate_equivalents = 0;  // the anchor's GE scaled like its cells
  int64_t lut4 = 0;              // estimated iCE40 LUT4s
  std::string anchor_key;        // the measured report it was scaled from
  int differing_parameters = 0;
  std::string label() const;  // "estimate (scaled from Yosys run KEY, N parameters differ)"
};
AreaEstimate estimate_area(const UnitConfig& unit, const std::vector<AreaReport>& anchors);

// Every report in a cache folder (unreadable entries are skipped).
std::vector<AreaReport> load_area_reports(const std::string& cache_dir);

// The report as JSON (the `shadesim area --json` format and, without its "liberty" object, which
// is cached apart, the cache entry).
std::string area_report_to_json(const AreaReport& report);
AreaReport area_report_from_json(const std::string& text, const std::string& source);

}  // namespace shadesim
