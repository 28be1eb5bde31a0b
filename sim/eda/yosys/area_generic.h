// shadesim area's generic flow (sim/eda/yosys/area.cpp), for the files that run and cache it: the
// Yosys scripts (flat, table memories, kept-hierarchy breakdown, the simulation netlist's write:
// .ys files beside this header) and reading their figures into a GenericArea. The figures'
// conventions (GE, RAM bits) are in sim/eda/yosys/generic_area.h.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "sim/eda/yosys/generic_area.h"

namespace shadesim::generic_flow {

// The commands of the Yosys scripts beside this header (tool_script); each file's header says
// what it does. @WORK@ stands for the run's work folder (flow_tools::yosys_script).
std::string flat_script();           // flat.ys: synth -flatten; abc -g ...; stat; ltp
std::string memory_script();         // memory.ys: synth to `fine`; dump of the $mem cells
std::string breakdown_script();      // breakdown.ys: the datapath and control modules kept
std::string netlist_write_script();  // netlist_write.ys: regress --netlist's netlist

// The syntheses' figures in `work` into r: cells, flip-flops, GE and RAM bits, logic depth and
// (with `breakdown`) the per-module rows; then check_series.
void read_syntheses(const std::filesystem::path& work, bool breakdown, GenericArea& r);

// Sets r.warnings: series Yosys removed (figures understated), a RAM bit count that differs
// from the parameters'.
void check_series(GenericArea& r);

// Diffuse series of a unit's parameters: one per light and channel, or one per light with
// DIFFUSE_MULTIPLY.
int64_t diffuse_series_of(const std::map<std::string, int64_t>& parameters);

}  // namespace shadesim::generic_flow
