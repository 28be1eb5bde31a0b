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
// Where each lives: the generic flow (flat, memory, breakdown; GE) sim/eda/yosys/area.cpp, the
// iCE40 flow and its Fmax shell sim/eda/ice40/area_ice40.h, the run and its cache
// sim/eda/yosys/synthesis_cache.cpp, the shared shell glue sim/eda/common/flow_tools.h, Yosys's
// reports sim/eda/yosys/yosys_stat.h, the JSON sim/eda/yosys/area_report_json.cpp, the simulation
// netlist sim/eda/yosys/area_netlist.cpp and the estimate sim/eda/yosys/area_estimate.cpp.
//
// Gate equivalents (GE), the one convention every figure here uses: NAND2 gates =
//   logic transistors / 4  +  6 per flip-flop  (rounded to the nearest gate),
// with "logic transistors" = `stat -tech cmos`'s estimate less what it charges for flip-flops.
// Yosys 0.23's CMOS table (its cost.h) charges 16 transistors for a plain $_DFF_P_ /
// $_DFF_N_ and nothing for every other flip-flop type ($_DFFE_*, $_SDFF*, $_DFF_PN0_, ...; the
// "+" of "N+ transistors"), so those 16 are taken off and every flip-flop counts 6 GE, whatever
// its type (checked by area_test on tiny modules: NAND 4, AND 6, XOR 12, MUX 12, NOT 2
// transistors, a 4-bit register 4 x 16). A NAND2 is 4 transistors.
//
// Table memories (the exponent LUT's entries, rtl/exponent_lut.sv mem_q) are RAM, not logic: an
// ASIC would use an SRAM macro, an iCE40 its block RAM. synth maps them to flip-flops (and
// their write decoders and read multiplexers) in its `fine` half; the memory flow stops before
// it, dumps the $mem / $mem_v2 cells and sums SIZE x WIDTH of the tables (cells named mem_q,
// kTableMemoryName; register arrays are $mem cells there too): `ram_bits`. (A run of its own:
// splitting the flat flow's synth there changes ABC's result by a few cells.) Those bits'
// flip-flops are left out of the flip-flop term of GE (their decoders and read multiplexers stay in
// the logic term: GE is an upper bound of the logic beside a macro). The count is cross-checked
// against the parameters (lut: 2^A x B per bank, MATERIAL_BUFFERS banks, one table per
// specular_unit instance); a difference is a warning. The per-module rows take their RAM bits
// from that parameter count (the table sits in specular_unit).
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
#include "sim/eda/yosys/yosys_stat.h"

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

// One module of the hierarchical generic synthesis.
struct ModuleArea {
  std::string module;            // RTL module name (span_setup, series_engine, ..., shade_unit)
  int instances = 0;             // instances in the design
  int64_t cells_each = 0;        // generic cells of one instance, its submodules included
  int64_t transistors_each = 0;  // stat -tech cmos estimate of one instance
  int64_t flip_flops_each = 0;
  // transistors_each less Yosys's cost of its flip-flops (see Gate equivalents above); -1: not
  // known (a cache entry written before GE were measured).
  int64_t logic_transistors_each = -1;
  int64_t ram_bits_each = 0;  // table memory bits inside one instance (not in GE)
  int64_t cells() const { return cells_each * instances; }
  int64_t transistors() const { return transistors_each * instances; }
  bool has_gate_equivalents() const { return logic_transistors_each >= 0; }
  int64_t gate_equivalents_each() const;
  int64_t gate_equivalents() const { return gate_equivalents_each() * instances; }
};

// NAND2 gate equivalents (the convention above): llround(logic_transistors / 4) +
// 6 * (flip_flops - ram_bits).
constexpr int kTransistorsPerGate = 4;
constexpr int kGatesPerFlipFlop = 6;
int64_t gate_equivalents(int64_t logic_transistors, int64_t flip_flops, int64_t ram_bits);

struct AreaReport {
  std::vector<VerilogParameter> parameters;  // as passed to chparam
  std::string key;                           // cache key (hex)
  bool from_cache = false;
  std::string yosys_version, nextpnr_version;
  // Generic synthesis of the flattened unit: the headline figures.
  int64_t cells = 0;
  int64_t transistors = 0;
  bool transistors_partial = false;  // Yosys's CMOS cost table has no flip-flops: not counted
  int64_t flip_flops = 0;            // every flip-flop, the RAM's included
  // GE inputs (see Gate equivalents above); logic_transistors -1: a cache entry from before
  // GE were measured (no GE shown, no GE estimate from it).
  int64_t logic_transistors = -1;
  int64_t ram_bits = 0;           // table memory bits (Yosys: $mem cells' SIZE x WIDTH)
  int64_t ram_bits_expected = 0;  // the same from the parameters (the cross-check)
  bool has_gate_equivalents() const { return logic_transistors >= 0; }
  int64_t gate_equivalents() const;  // NAND2 GE of the logic, RAM apart
  // Where the area goes (empty without AreaOptions::breakdown): the same flow with span_setup,
  // series_engine, specular_unit and pixel_combine kept as modules. shade_unit's row is its own
  // glue only (decoder, coefficient and material registers, span pipeline control, metadata
  // lines, output register). Rows sum to breakdown_cells, which is >= cells: across a kept
  // boundary Yosys cannot remove logic whose result the neighbour never reads.
  std::vector<ModuleArea> modules;
  int64_t breakdown_cells = 0;
  Ice40Area ice40;
  LogicDepth logic_depth;  // of the flat netlist (above)
  double seconds = 0;      // wall time of the run that produced the figures (not of a cache hit)
  double cpu_seconds = 0;  // CPU time of its tools (all syntheses and nextpnr together, and the
                           // liberty flow's when it ran beside them)
  std::optional<LibertyReport> liberty;  // with AreaOptions::liberty
  std::vector<std::string> warnings;     // e.g. series that Yosys removed: figures understated
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
  int64_t cells = 0;              // estimated flat generic cells
  int64_t gate_equivalents = -1;  // the anchor's GE scaled like its cells; -1: anchor has none
  int64_t lut4 = 0;               // estimated iCE40 LUT4s
  std::string anchor_key;         // the measured report it was scaled from
  int differing_parameters = 0;
  std::string label() const;  // "estimate (scaled from Yosys run KEY, N parameters differ)"
};
AreaEstimate estimate_area(const UnitConfig& unit, const std::vector<AreaReport>& anchors);

// Table memory bits of a unit from its parameters (the cross-check of AreaReport::ram_bits):
// per specular_unit instance, lut: 2^A x B x MATERIAL_BUFFERS; other kinds 0.
int64_t ram_bits_per_specular_unit(const std::vector<VerilogParameter>& parameters);
int64_t ram_bits_of_parameters(const std::vector<VerilogParameter>& parameters);

// The gate-level netlist of `unit` that the flat flow measures, for simulation in place of the
// RTL (regress --netlist): the flat script above, then `write_verilog -noattr`. Parameters are
// baked in (chparam); no fault hooks (sim/harness/faults/ is never synthesised). Cached in
// `cache_dir` as netlist-<key>.v, the key hashing the parameters, the RTL sources' contents, the
// Yosys version and the script (like the area cache), with its stat beside it (netlist-<key>.json).
// The top's ports are checked against the ports the co-simulation glue drives (names and widths
// from the parameters).
struct NetlistOptions {
  std::string rtl_dir;    // empty: SHADESIM_RTL_DIR, else this source tree's rtl/
  std::string cache_dir;  // required
  std::string yosys = "yosys";
  std::ostream* progress = nullptr;
};
struct UnitNetlist {
  std::string path;  // the Verilog netlist
  std::string key;
  bool from_cache = false;
  int64_t cells = 0, flip_flops = 0, gate_equivalents = 0, ram_bits = 0;
  double seconds = 0;  // Yosys's wall time when it was made
};
UnitNetlist unit_netlist(const UnitConfig& unit, const NetlistOptions& options);
// The default netlist cache: <build>/netlist-cache.
std::string default_netlist_cache_dir();

// Every report in a cache folder (unreadable entries are skipped).
std::vector<AreaReport> load_area_reports(const std::string& cache_dir);

// The report as JSON (the `shadesim area --json` format and, without its "liberty" object, which
// is cached apart, the cache entry).
std::string area_report_to_json(const AreaReport& report);
AreaReport area_report_from_json(const std::string& text, const std::string& source);

}  // namespace shadesim
