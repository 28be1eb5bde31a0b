// The conditions every OpenSTA run of a unit is timed under, in one place: shadesim
// area's liberty flow, config's clock ladder (sim/engines/clock_target.cpp) and explore's clock
// column read them here, and so can a layout or a clock predictor. docs/area.md argues the
// values.
//
//   clock      an ideal clock (no tree pre-route) with a setup uncertainty for skew and jitter;
//   inputs     an input delay of the library's plain flip-flop's clock-to-Q (a register of the
//              surrounding block launches them) and a driving cell, the library's smallest
//              buffer (osu018: BUFX2), so their slew and load are timed;
//   outputs    an output delay of that flip-flop's setup (a register of the surrounding block
//              captures them) and a load of `load_pins` of its D pins;
//   guard band "meets a clock" asks for Fmax at least clock / (1 - guard_band): the slack at the
//              target period must exceed that fraction of it pre-route, for the wires, the
//              clock tree and the corner a synthesis estimate leaves out.
//
// The Tcl is a file beside this header (sim/eda/sta/constraints.tcl) whose @NAME@ fields
// constraints_tcl() fills in.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "sim/eda/sta/liberty.h"

namespace shadesim {

// The policy: what the values are made of, for any library.
struct StaConstraints {
  double clock_uncertainty_ns = 0.2;
  double guard_band = 0.05;  // fraction of the period "meets" must clear
  int load_pins = 4;         // D pins of the plain flip-flop on every output port
};

// The policy applied to one library: the figures the Tcl is filled in with and the report
// states.
struct ResolvedConstraints {
  StaConstraints policy;
  std::string driving_cell, driving_pin;  // the smallest buffer and its output
  std::string load_cell, load_pin;        // the plain flip-flop and its D
  double output_load_pf = 0;              // load_pins x the D pin's capacitance
  double input_delay_ns = 0;              // the plain flip-flop's clock-to-Q
  double output_delay_ns = 0;             // its setup time
};

// Resolves `policy` on `lib`, with the plain flip-flop's clock-to-Q and setup as OpenSTA measured
// them. Throws std::runtime_error naming the library when it has no buffer or plain flip-flop.
ResolvedConstraints resolve_constraints(const StaConstraints& policy, const LibertyLibrary& lib,
                                        double clock_to_q_ns, double setup_ns);

// The clock a unit's Fmax must reach to meet `mhz` with the guard band: mhz / (1 - guard_band).
double required_fmax_mhz(double mhz, const StaConstraints& policy = {});

// constraints.tcl filled in for a clock of `period_ns` on port `clock`.
std::string constraints_tcl(const ResolvedConstraints& c, double period_ns,
                            const std::string& clock = "clk_i");
// The template itself (its text is part of the liberty flow's cache key).
std::string constraints_template();

// One line for the report: "BUFX2 drives the inputs (after 0.24 ns), 4 DFFPOSX1 D load ...".
std::string describe_constraints(const ResolvedConstraints& c);

// The `constraints` object of shadesim area's JSON, and back (std::runtime_error naming
// `source` on a missing field).
nlohmann::json constraints_to_json(const ResolvedConstraints& c);
ResolvedConstraints constraints_from_json(const nlohmann::json& j, const std::string& source);

}  // namespace shadesim
