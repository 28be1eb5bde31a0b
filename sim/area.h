// Area and timing of one shading unit configuration, measured by synthesising rtl/shade_unit.sv
// with Yosys (and placing and routing it with nextpnr-ice40 where it fits an iCE40 HX8K).
//
// The parameters come only from shade_unit_parameters() (model/rtl_parameters.h), passed to
// Yosys with yosys_chparam_args(). Three flows run on the same parameters:
//   flat      read all rtl/*.sv (packages, *_pkg.sv, first: the units' parameter types name
//             shade_pkg; then sorted by name: ABC's result depends on the netlist's order, by
//             about 0.5 % in cells, so the order is fixed); chparam; synth -flatten; abc -g
//             AND,NAND,OR,NOR,XOR,XNOR,MUX; stat -tech cmos: the unit's generic cells, transistor
//             estimate, flip-flops.
//   breakdown the same with the datapath modules kept (keep_hierarchy): per-module cells.
//   ice40     synth_ice40 (flattened): SB_LUT4, SB_DFF*, SB_CARRY, SB_RAM40_4K counts.
//   pnr       nextpnr-ice40 --hx8k on the synth_ice40 netlist: Fmax of clk_i. Skipped (and said
//             so) when the LUT4 or DFF count alone exceeds the HX8K's 7,680 logic cells.
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
#include <string>
#include <vector>

#include "model/rtl_parameters.h"
#include "model/unit_config.h"

namespace shadesim {

// A tool the flow needs is not installed (names the tool and the Debian package).
class MissingToolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct AreaOptions {
  std::string rtl_dir;          // folder with rtl/*.sv; empty: this source tree's rtl/
  std::string cache_dir;        // empty: no cache (always synthesise)
  bool place_and_route = true;  // run nextpnr-ice40 for Fmax when the design fits
  bool breakdown = true;        // also run the per-module (kept hierarchy) synthesis
  std::string yosys = "yosys";  // program names (looked up on PATH) or paths
  std::string nextpnr = "nextpnr-ice40";
  std::ostream* progress = nullptr;  // one updating progress line while tools run; null: quiet
};

// One module of the hierarchical generic synthesis.
struct ModuleArea {
  std::string module;            // RTL module name (span_setup, series_engine, ..., shade_unit)
  int instances = 0;             // instances in the design
  int64_t cells_each = 0;        // generic cells of one instance, its submodules included
  int64_t transistors_each = 0;  // stat -tech cmos estimate of one instance
  int64_t flip_flops_each = 0;
  int64_t cells() const { return cells_each * instances; }
  int64_t transistors() const { return transistors_each * instances; }
};

struct Ice40Area {
  int64_t lut4 = 0, dff = 0, carry = 0, ram4k = 0;
  static constexpr int64_t kHx8kLogicCells = 7680;
  static constexpr int64_t kHx8kRam4k = 32;
  bool fits_hx8k = false;          // false: see fit_note
  std::string fit_note;            // plain words: fits, or by how much it does not
  std::optional<double> fmax_mhz;  // nextpnr-ice40's post-route Fmax of clk_i
  std::string pnr_note;            // why there is no Fmax (no fit, --no-pnr, nextpnr failed)
};

struct AreaReport {
  std::vector<VerilogParameter> parameters;  // as passed to chparam
  std::string key;                           // cache key (hex)
  bool from_cache = false;
  std::string yosys_version, nextpnr_version;
  // Generic synthesis of the flattened unit: the headline figures.
  int64_t cells = 0;
  int64_t transistors = 0;
  bool transistors_partial = false;  // Yosys's CMOS cost table has no flip-flops: not counted
  int64_t flip_flops = 0;
  // Where the area goes (empty without AreaOptions::breakdown): the same flow with span_setup,
  // series_engine, specular_unit and pixel_combine kept as modules. shade_unit's row is its own
  // glue only (decoder, coefficient and material registers, span pipeline control, metadata
  // lines, output register). Rows sum to breakdown_cells, which is >= cells: across a kept
  // boundary Yosys cannot remove logic whose result the neighbour never reads.
  std::vector<ModuleArea> modules;
  int64_t breakdown_cells = 0;
  Ice40Area ice40;
  double seconds = 0;      // wall time of the run that produced the figures (not of a cache hit)
  double cpu_seconds = 0;  // CPU time of its tools (all syntheses and nextpnr together)
  std::vector<std::string> warnings;  // e.g. series that Yosys removed: figures understated
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
  int64_t cells = 0;       // estimated flat generic cells
  int64_t lut4 = 0;        // estimated iCE40 LUT4s
  std::string anchor_key;  // the measured report it was scaled from
  int differing_parameters = 0;
  std::string label() const;  // "estimate (scaled from Yosys run KEY, N parameters differ)"
};
AreaEstimate estimate_area(const UnitConfig& unit, const std::vector<AreaReport>& anchors);

// Every report in a cache folder (unreadable entries are skipped).
std::vector<AreaReport> load_area_reports(const std::string& cache_dir);

// The report as JSON (the `shadesim area --json` format and the cache entry).
std::string area_report_to_json(const AreaReport& report);
AreaReport area_report_from_json(const std::string& text, const std::string& source);

}  // namespace shadesim
