// A Liberty (.lib) library as shadesim area's liberty flow needs it: the library's name, and per
// cell its area, pins (direction, function, clock, capacitances) and whether it holds state (an
// ff / latch group). Timing and power tables are skipped: OpenSTA reads those itself.
//
// Cell functions are evaluated (Liberty's syntax: ! and ' for NOT, & * and a space for AND, | +
// for OR, ^ for XOR, parentheses, 0 and 1), so the cells the flow needs are found by what they
// compute, not by their names: a buffer is a one-input cell whose output equals its input, a
// NAND2 a two-input cell whose output is NOT (A AND B).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace shadesim {

struct LibertyPin {
  std::string name;
  std::string direction;  // input | output | inout | internal
  std::string function;   // an output's function text ("" for inputs)
  bool clock = false;     // `clock : true`: a flip-flop's or latch's clock pin
  double capacitance = 0, max_capacitance = 0;  // library units (osu018: pF)
};

struct LibertyCell {
  std::string name;
  double area = 0;
  bool dont_use = false;                // `dont_use : true`: never picked by the flow
  bool sequential = false;              // has an ff / latch (or their _bank) group
  bool latch = false;                   // the state group is a latch
  std::vector<std::string> state_vars;  // the state group's names (IQ, IQN): P0002, ...
  // The state group's attributes: next_state, clocked_on, clear, preset (ff); data_in, enable
  // (latch).
  std::map<std::string, std::string> state;
  std::vector<LibertyPin> pins;
  const LibertyPin* pin(const std::string& name) const;  // null when it has none
  std::vector<const LibertyPin*> inputs() const;
  std::vector<const LibertyPin*> outputs() const;
};

struct LibertyLibrary {
  std::string path;
  std::string name;  // library (NAME)
  std::map<std::string, LibertyCell> cells;
  // The cell; throws std::runtime_error naming the library file when it has none.
  const LibertyCell& cell(const std::string& name) const;
};

// Reads `path`; throws std::runtime_error naming the file (and line) when it cannot be read or
// parsed, or holds no cell.
LibertyLibrary read_liberty(const std::string& path);

// A function's value for the given input values; throws std::invalid_argument naming the
// expression on a syntax error or an input it does not know.
bool eval_liberty_function(const std::string& function, const std::map<std::string, bool>& inputs);

// The buffer a fanout tree is built of: of the cells with one input whose one output equals it,
// the one with the largest max_capacitance per input capacitance (the most load driven per load
// presented, so a tree needs the fewest levels; osu018: BUFX4 at 139, BUFX2 104, CLKBUF1-3 52);
// ties go to the smaller area. Throws std::runtime_error naming the library when it has none.
const LibertyCell& strongest_buffer(const LibertyLibrary& lib);

// The smallest-area two-input cell computing NOT (A AND B): the unit of NAND2 equivalents
// (osu018: NAND2X1, 24 um^2). Throws std::runtime_error naming the library when it has none.
const LibertyCell& nand2_cell(const LibertyLibrary& lib);

// The smallest-area flip-flop with a plain D input and no set or reset (osu018: DFFPOSX1), for
// measuring clock-to-Q + setup; nullptr when the library has none.
struct PlainFlipFlop {
  const LibertyCell* cell = nullptr;
  std::string d, clock, q;  // pin names
};
PlainFlipFlop plain_flip_flop(const LibertyLibrary& lib);
// The same, or std::runtime_error naming the library and `needed_for` (what the caller measures
// on it) when it has none.
PlainFlipFlop required_plain_flip_flop(const LibertyLibrary& lib, const std::string& needed_for);

}  // namespace shadesim
