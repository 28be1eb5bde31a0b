// Reading what Yosys reports: `stat -json` (cells by type, the CMOS transistor estimate), a
// `dump` of the table memories and `ltp -noff`'s longest path. The generic and iCE40 flows of
// shadesim area read their figures with these (never from Yosys's text stat).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace shadesim {

// One module's figures from a Yosys `stat -json -tech cmos` report (a `tee -o` of it): cells,
// transistors, flip-flops (every $_*DFF* cell) and logic transistors (transistors less
// kYosysCmosPlainDffTransistors per $_DFF_P_ / $_DFF_N_). `module` "" takes the only or top
// module. Throws std::runtime_error naming the file.
struct CmosStat {
  int64_t cells = 0, transistors = 0, flip_flops = 0, logic_transistors = 0;
  bool transistors_partial = false;
};
CmosStat read_cmos_stat(const std::string& stat_file, const std::string& module = "");
// What Yosys 0.23's `stat -tech cmos` charges for $_DFF_P_ and $_DFF_N_ (nothing for others).
constexpr int kYosysCmosPlainDffTransistors = 16;

// Table memory bits in a Yosys `dump` of $mem / $mem_v2 cells: the sum of SIZE x WIDTH over
// the cells named kTableMemoryName (last hierarchical component); the unit's register arrays
// (coef_q, ambient_q, ...) are $mem cells there too and are not counted.
constexpr const char* kTableMemoryName = "mem_q";  // rtl/exponent_lut.sv's table
int64_t read_memory_bits(const std::string& dump_file);

// Logic depth: the cells on the longest path between registers (or ports) of the flat generic
// netlist, from Yosys `ltp -noff` after abc: every 2-input gate, MUX and inverter is one level.
// A technology-free timing figure for every configuration, beside the library and iCE40 timing;
// it is not a delay (a MUX and a NAND count the same).
struct LogicDepth {
  static constexpr const char* kMethod =
      "Yosys ltp -noff on the flat netlist after abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX: cells on "
      "the longest register-to-register (or port) path, each gate, MUX and inverter one level";
  int64_t gates = -1;  // -1 until a report is read
  std::string from, to;
};
// The depth in a `tee -o` of `ltp -noff`; throws std::runtime_error naming the file.
LogicDepth read_logic_depth(const std::string& ltp_file);

// ---- the report's structure, for the flows that read more than one module ------------------

// One module's figures, or the design's, in Yosys's `stat -json`.
struct StatSection {
  int64_t cells = 0;
  int64_t transistors = 0;
  bool transistors_partial = false;  // "N+": some cells (flip-flops) have no CMOS cost
  std::map<std::string, int64_t> by_type;
};

// A `stat -json` report: "modules" {name: {"num_cells", "num_cells_by_type" {type: n},
// "estimated_num_transistors" "N" or "N+" (only with -tech cmos)}} and "design", the top module
// with everything below it (as the text's "design hierarchy"). Names are spelled as the text
// spells them: "\shade_unit" is "shade_unit", "$paramod..." stays.
// Yosys 0.23 writes invalid JSON in two cases, neither of which shadesim's scripts meet: when no
// top module is known (no -top, and no module with the `top` attribute that synth -top and
// synth_ice40 -top set), "modules" ends in a comma and "design" is missing; and when a module
// below the top instantiates a module of its own (the breakdown's kept modules instantiate none
// of each other), the text's nested hierarchy lines land between "modules" and "design".
struct StatReport {
  std::map<std::string, StatSection> modules;
  std::optional<StatSection> design;
};
// `cmos`: the report is of `stat -tech cmos`, which must carry each transistor estimate. Throws
// naming the file (and, for a section's missing or mistyped field, the section).
StatReport read_stat_json(const std::filesystem::path& p, bool cmos);

// "$paramod$0f50...\span_setup" -> "span_setup"; "\shade_unit" -> "shade_unit"; a module with
// one short parameter keeps it in its name: "$paramod\setup_ctrl\XY_BITS=s32'..." -> "setup_ctrl".
std::string base_module_name(const std::string& yosys_name);
// The report's shade_unit module (whatever its $paramod spelling); throws naming the file.
const std::string& stat_top_name(const StatReport& stat, const std::filesystem::path& p);
// Every Yosys internal flip-flop ($_*DFF*) and iCE40 SB_DFF* of a section.
int64_t flip_flops_of(const StatSection& s);
// The transistors `stat -tech cmos` charged for the flip-flops of `s` (only the plain
// $_DFF_P_ / $_DFF_N_ have a cost in its table).
int64_t flip_flop_transistors_of(const StatSection& s);

}  // namespace shadesim
