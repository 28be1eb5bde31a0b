// Switching activity of a scene, read from an FST trace of the Verilated RTL: the toggles and
// time at 1 of every bit of shade_unit's hierarchy. The traced co-simulation that writes the FST
// (the scene's command stream on the C++ backend, no input gaps, no back-pressure, every cycle
// dumped by `--trace-run`, sim/harness/cosim_run.cpp) is run by the engine,
// sim/engines/scene_activity.h.
//
// Why a trace and not toggle coverage: the covered builds (`--coverage-toggle`) count exactly the
// toggles of a bit (power_test checks it on a hand-counted fixture), but Verilator 5.006 gives
// no toggle point to a signal declared inside a generate block (slot_meta's g_delay.line_q,
// wpow_unit's g_pipelined.b_q, start_bank's g_word[w].q: two thirds of specular's flip-flops),
// sums the instances of a module in a generate loop into one point (`g_series[*]`), and has no
// time at 1. The trace has every signal of every instance, with its values.
//
// What is counted: the trace holds two samples per cycle, the settled inputs of the cycle and
// the state after its rising edge (the harness's dumps, kWaveUnitsPerCycle apart). A bit's toggles
// are the changes between consecutive samples from cycle 0 (after reset) to the last drain
// cycle; its duty is the fraction of [first sample, last sample + half a cycle] it was 1.
// `cycles` is the number of cycles traced (from clk_i's toggles: one rise per cycle), checked
// against the harness's stimulus replayed (port_stimulus). Verilator traces no signal wider
// than 256 bits or array of more than 32 elements (--trace-max-width, --trace-max-array): such
// bits are missing from the maps, not zero. While cmd_valid_i is low the harness drives seeded
// noise on cmd_data_i (sim/harness/idle_noise.h): with no gaps that happens only after
// the last command beat, and those toggles are in the counts (`idle_noise_toggles` says how many).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "model/command_stream.h"
#include "model/unit_config.h"

namespace shadesim {

// Per bit, keyed by the flattened hierarchical name Yosys's `synth -flatten` gives the same bit:
// instance path and signal joined by '.', then the indices, e.g. "u_decoder.pos_q[1]",
// "u_material_bank.spec_colour_q[0][1]", "u_series.g_series[1].g_one_lane.u_engine.d_q[3]", or
// "cmd_data_i[3]" at the top.
using ToggleMap = std::map<std::string, uint64_t>;
using DutyMap = std::map<std::string, double>;

struct SceneActivity {
  std::string scene;        // the scene file, as given
  std::string unit;         // UnitConfig::to_string() of the unit simulated
  uint64_t cycles = 0;      // cycles traced: the frame and the drain after it
  uint64_t run_cycles = 0;  // the frame: to the idle unit, as `shadesim cycles` counts it
  uint64_t pixels = 0;
  // Every signal bit of the hierarchy (registers among them); the top's own signals, its ports
  // (clk_i included) among them, under their plain names.
  ToggleMap signals;
  DutyMap duty;                     // the same bits: fraction of the time at 1
  uint64_t idle_noise_toggles = 0;  // of the cmd_data_i toggles: the harness's noise
  std::vector<std::string> notes;   // how it was measured, in words

  // Toggles per clock cycle of a bit (0 when cycles is 0).
  double rate(uint64_t toggles) const {
    return cycles ? static_cast<double>(toggles) / static_cast<double>(cycles) : 0.0;
  }
};

// Toggles and duty of every bit of an FST file's scopes under TOP.<top> (Verilator's trace of
// `top`), named as ToggleMap says; duty over [start, end + tail]. Throws std::runtime_error when
// the file cannot be read or has no such scope.
struct FstActivity {
  ToggleMap toggles;
  DutyMap duty;
  uint64_t start_time = 0, end_time = 0;
};
FstActivity read_fst_activity(const std::string& fst_path, const std::string& top,
                              uint64_t tail = 0);

// A traced run's activity (the harness's dump protocol: a sample at each cycle's settled inputs
// with clk_i low, one after its rising edge, kWaveUnitsPerCycle apart): `cycles` from clk_i's
// toggles, duty up to half a cycle after the last sample. Throws std::runtime_error when clk_i
// never toggled.
SceneActivity activity_from_trace(const std::string& fst_path, const std::string& top,
                                  uint64_t pixels, const std::string& clock = "clk_i");

// The input ports as the harness drives them for `stream` on `unit` with no gaps or
// back-pressure, replayed without the RTL: the lockstep block (sim/harness/cosim.h) around a
// stand-in for the RTL (the cycle model, which the co-simulation checks the RTL against on every
// cycle). Toggles counted as the trace counts them (the first cycle's values the baseline);
// `idle_noise` is the part of cmd_data_i's toggles the noise on cycles with cmd_valid_i low
// makes (the count minus the count with the last beat held instead).
struct PortStimulus {
  ToggleMap ports;          // cmd_valid_i, cmd_data_i[k], pix_ready_i, rst_ni
  uint64_t run_cycles = 0;  // cycles clocked, drain included
  uint64_t idle_noise = 0;
};
PortStimulus port_stimulus(const UnitConfig& unit, const CommandStream& stream);

// JSON for the area job's cache: every field above.
std::string activity_to_json(const SceneActivity& a);
SceneActivity activity_from_json(const std::string& text);

}  // namespace shadesim
