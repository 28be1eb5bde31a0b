// The generic Yosys flow's figures of a unit and their conventions: cells, transistors, flip-flops,
// gate equivalents, table RAM bits and the per-module breakdown (sim/eda/yosys/area.cpp measures
// them; sim/engines/area_report.h sets them beside the other flows').
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
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/rtl_parameters.h"
#include "sim/eda/yosys/yosys_stat.h"

namespace shadesim {

// One module of the hierarchical generic synthesis.
struct ModuleArea {
  std::string module;            // RTL module name (span_setup, series_engine, ..., shade_unit)
  int instances = 0;             // instances in the design
  int64_t cells_each = 0;        // generic cells of one instance, its submodules included
  int64_t transistors_each = 0;  // stat -tech cmos estimate of one instance
  int64_t flip_flops_each = 0;
  // transistors_each less Yosys's cost of its flip-flops (see Gate equivalents above).
  int64_t logic_transistors_each = 0;
  int64_t ram_bits_each = 0;  // table memory bits inside one instance (not in GE)
  int64_t cells() const { return cells_each * instances; }
  int64_t transistors() const { return transistors_each * instances; }
  int64_t gate_equivalents_each() const;
  int64_t gate_equivalents() const { return gate_equivalents_each() * instances; }
};

// NAND2 gate equivalents (the convention above): llround(logic_transistors / 4) +
// 6 * (flip_flops - ram_bits).
constexpr int kTransistorsPerGate = 4;
constexpr int kGatesPerFlipFlop = 6;
int64_t gate_equivalents(int64_t logic_transistors, int64_t flip_flops, int64_t ram_bits);

// Table memory bits of a unit from its parameters (the cross-check of AreaReport::ram_bits):
// per specular_unit instance, lut: 2^A x B x MATERIAL_BUFFERS; other kinds 0.
int64_t ram_bits_per_specular_unit(const std::vector<VerilogParameter>& parameters);
int64_t ram_bits_of_parameters(const std::vector<VerilogParameter>& parameters);

// The generic flow's figures of one unit (Yosys synth -flatten; abc -g ...; stat -tech cmos),
// its per-module breakdown and its checks.
struct GenericArea {
  std::vector<VerilogParameter> parameters;  // as passed to chparam
  // Generic synthesis of the flattened unit: the headline figures.
  int64_t cells = 0;
  int64_t transistors = 0;
  bool transistors_partial = false;  // Yosys's CMOS cost table has no flip-flops: not counted
  int64_t flip_flops = 0;            // every flip-flop, the RAM's included
  // GE inputs (see Gate equivalents above).
  int64_t logic_transistors = 0;
  int64_t ram_bits = 0;              // table memory bits (Yosys: $mem cells' SIZE x WIDTH)
  int64_t ram_bits_expected = 0;     // the same from the parameters (the cross-check)
  int64_t gate_equivalents() const;  // NAND2 GE of the logic, RAM apart
  // Where the area goes (empty without the breakdown run): the same flow with span_setup,
  // series_engine, specular_unit and pixel_combine kept as modules. shade_unit's row is its own
  // glue only (decoder, coefficient and material registers, span pipeline control, metadata
  // lines, output register). Rows sum to breakdown_cells, which is >= cells: across a kept
  // boundary Yosys cannot remove logic whose result the neighbour never reads.
  std::vector<ModuleArea> modules;
  int64_t breakdown_cells = 0;
  LogicDepth logic_depth;             // of the flat netlist (above)
  std::vector<std::string> warnings;  // e.g. series that Yosys removed: figures understated
};

}  // namespace shadesim
