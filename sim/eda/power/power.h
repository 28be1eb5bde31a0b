// Power and energy per pixel of a unit mapped onto a standard-cell library, from the scene's own
// switching activity (sim/eda/power/activity.h), with OpenSTA 2019 (`sta`, Debian's opensta
// 0~20191111gitc018cb2) on the mapped netlist. docs/power.md says what is measured and left out.
//
// How the scene's activity reaches the netlist:
//   flip-flops   each instance of a sequential library cell (an `ff`/`latch` group) whose output
//                net (Q, or QN) carries, by its name or an `assign` alias, a flattened RTL name
//                of the activity map gets that bit's toggles per clock cycle. OpenSTA 2019's
//                propagation (its Power.cc) recomputes a flip-flop's Q from its internal
//                state pin and, on a pass that finds a D without activity, sets every state pin
//                from its D; it reaches logic behind a flip-flop only through a non-clock arc (a
//                DFFSR's R->Q) or that D->Q pass, so a plain DFFPOSX1's fanout would otherwise
//                keep the 0.1 default. Its Tcl `set_power_activity -pins` cannot be used either
//                (the proc calls an undefined get_pins_error and keeps only input pins). So
//                OpenSTA reads a copy of the netlist (power_netlist.v) with one extra input port
//                per flip-flop assigned to its output net - a propagation root carrying the
//                flip-flop's activity into its fanout; ports add no capacitance - and the script
//                sets that activity (sta::set_power_pin_activity, the command under the Tcl) on
//                the state pin, the output pins and the port. Every input pin of a sequential
//                cell is preset to activity 0 so that no D->Q pass runs; the propagation then
//                sets each D from its driver as before.
//   unmatched    flip-flops with no RTL name in the map, or whose register the synthesis
//                re-encoded (a bit index the RTL does not have, or a name in
//                PowerOptions::excluded_registers, e.g. fsm_recoded_registers() of Yosys's log),
//                get the default activity; counted and listed (PowerReport::unannotated).
//   inputs       each input port bit gets its own toggles per cycle (clk_i is the clock: OpenSTA
//                charges 2 transitions a period on the clock network).
//   duty         every annotated pin gets its bit's fraction of time at 1 from the trace (an
//                inverted output 1 - that); what has none, PowerOptions::duty.
//   constants    input pins tied to 1'b0 / 1'b1 get activity 0.
//   the rest     OpenSTA's propagation from those pins through the combinational cells, in
//                topological order, zero delay (no glitches): each output's activity and duty
//                from its Liberty function with the inputs taken as independent (AND: a1 d2 +
//                a2 d1; OR: a1 (1-d2) + a2 (1-d1); XOR: a1 d1 (1-d2) + a2 d2 (1-d1); NOT keeps
//                the activity) - Power.cc evalActivity.
// Activity is transitions per clock period (toggles per cycle): OpenSTA divides it by the period;
// switching power is 1/2 C V^2 per transition with C the sum of the load pins' capacitances (no
// wire load: osu018 has none), internal power the Liberty tables' energy per transition.
//
// Energy: the run's energy is total power x cycles / f (the activities are averages over those
// cycles), so per pixel: pJ/px = 1000 x P[mW] x cycles / (f[MHz] x pixels).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/eda/power/activity.h"

namespace shadesim {

// What a report_power row says, in mW.
struct PowerFigures {
  double internal_mw = 0, switching_mw = 0, leakage_mw = 0, total_mw = 0;
  double sequential_mw = 0, combinational_mw = 0;  // the rows' totals (clock pins in sequential)
};

struct PowerOptions {
  std::string sta = "sta";        // program name (on PATH) or path
  double default_activity = 0.1;  // toggles per cycle: unmatched flip-flops and input bits, and
                                  // the comparison run's global activity
  double duty = 0.5;              // the duty of what the activity has no time at 1 for
  std::string clock_port = "clk_i";
  // Registers (flattened RTL names without the bit index, e.g. "u_decoder.u_payload.pay_op_q")
  // whose flip-flops must not be annotated: the synthesis re-encoded them.
  std::vector<std::string> excluded_registers;
};

struct PowerReport {
  double clock_mhz = 0;
  uint64_t cycles = 0, pixels = 0;
  PowerFigures scene;             // the scene's activity
  PowerFigures default_activity;  // set_power_activity -global at PowerOptions::default_activity
  // Every data pin at activity 0 (set_power_activity -global -activity 0): the clock network's
  // power (its pins and cells at 2 transitions a period) and leakage, whatever the scene.
  PowerFigures clock_only;
  double pj_per_pixel = 0, default_pj_per_pixel = 0;
  int flip_flops = 0, flip_flops_annotated = 0;
  int input_bits = 0, input_bits_annotated = 0;  // the clock port not counted
  int constant_pins = 0;
  double default_activity_value = 0.1, duty = 0.5;  // PowerOptions' defaults, as used
  std::vector<std::string> unannotated;             // "instance (net): reason"
  std::vector<std::string> notes;                   // the method, in words

  // "N of M flip-flops annotated from the simulation, ..."
  std::string coverage_text() const;
};

// 1000 x P[mW] x cycles / (f[MHz] x pixels): the energy of one pixel in pJ.
double pj_per_pixel(double total_mw, uint64_t cycles, double clock_mhz, uint64_t pixels);

// Runs OpenSTA three times on `netlist_v` (module `top`, cells of `liberty`) at `clock_mhz` -
// with the scene's activity, with the global default, with every data pin at 0 - and reports
// them. Scripts and outputs are kept in `work_dir`: power_netlist.v, and for each run a Tcl script
// and OpenSTA's output (power, default, clock; .tcl and .out). Throws std::runtime_error
// with the tool's output when it fails, MissingToolError-like std::runtime_error when `sta` is
// not on PATH.
PowerReport netlist_power(const std::string& netlist_v, const std::string& liberty,
                          const std::string& top, const SceneActivity& activity, double clock_mhz,
                          const std::string& work_dir, const PowerOptions& options = {});

// The commands of netlist_power's OpenSTA scripts (sim/eda/power/*.tcl), for the cache keys of
// what it measures: a changed command is a new key.
std::string power_scripts_commands();

// Registers Yosys's fsm pass re-encoded, from its log ("Recoding FSM `$fsm$\NAME$N' ..."): NAME.
std::vector<std::string> fsm_recoded_registers(const std::string& yosys_log);

// The report_power rows of OpenSTA's output (W in the text, mW here). Throws std::runtime_error
// when there is no Total row.
PowerFigures parse_report_power(const std::string& sta_output);

std::string power_report_to_json(const PowerReport& r);
PowerReport power_report_from_json(const std::string& text);

}  // namespace shadesim
