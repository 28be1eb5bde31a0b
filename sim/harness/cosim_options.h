// The co-simulation executable's options (sim/harness/cosim_main.cpp states its contract): the
// command line, read with CLI11 in cosim_options.cpp and nowhere else, and the option values the
// run reads once it knows its build. --expect-mismatch and --fault are parsed when the run starts
// (sim/harness/cosim_run.cpp), not with the command line: --fault is checked against the build
// the unit maps to, and a bad unit is reported before a bad value of either.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>

#include "sim/harness/cosim.h"
#include "sim/harness/cosim_executable.h"

namespace shadesim::cosim_exe {

// Bad input: exit status 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The command line's values (defaults where not given), checked by the run.
struct Options {
  std::string config = "custom";  // the build's name, for reports
  std::string unit_path;
  std::string scenario = "mixed";
  std::string stream_path;
  uint64_t seed = 1;
  int runs = 1;
  int rows = 0;  // 0: the scenario's own
  int gap_pct = -1, max_gap = -1, stall_pct = -1;
  std::string expect;  // KIND:Y[:X]
  std::string fault;   // SITE@Y (sim/harness/fault_site.h)
  std::string save_dir = ".";
  std::string json_path;
  std::string waves_path;
  std::string replay_prefix;  // how replay lines start; empty: the executable's own command
  uint64_t waves_before = 200, waves_after = 16;
  double min_spec_pct = 0;
  uint64_t watchdog =
      0;  // cycles without pix_valid_o that count as a hang; 0: from the cycle model
  std::string coverage_path;  // covered builds: FILE.dat (several jobs: FILE_<i>.dat)
  // Traced builds, one job: after it passes, the run again with every cycle dumped into this FST
  // file (the switching activity of sim/eda/power/activity.h).
  std::string trace_run_path;
  bool list = false;
  bool list_json = false;  // --list --json: the list as JSON, on stdout
};

// What the command line asks for. With exit_status set the executable stops with it: --help
// (0) or a bad command line (2), its message already printed.
struct CommandLine {
  Options options;
  std::optional<int> exit_status;
};

CommandLine parse_command_line(int argc, char** argv, const CosimExecutable& exe);

// --expect-mismatch KIND:Y[:X]: the run succeeds only if its first mismatch is KIND on row Y,
// and at column X when given. X "first" is the row's first pixel as the stream orders them: the
// x0 of the stream's first SPAN on row Y, so a fault on every pixel of a row is checked to show
// on the first one, without asking the model under test where that is.
struct Expectation {
  std::string kind;  // empty: none expected
  int y = -1;
  std::optional<int> x;  // none: any column
  bool first_of_row = false;
  std::string text;  // as given

  bool active() const { return !kind.empty(); }
  bool met_by(const Mismatch& m, const CommandStream& stream) const {
    if (to_string(m.kind) != kind || m.y != y) return false;
    if (first_of_row) return m.x == first_span_x(stream, y);
    return !x || m.x == *x;
  }

  static int first_span_x(const CommandStream& stream, int row) {
    for (const Command& c : stream.commands) {
      if (const auto* span = std::get_if<SpanCmd>(&c); span != nullptr && span->y == row) {
        return span->x0;
      }
    }
    return -1;  // the stream has no span on the row: no mismatch can be its first pixel
  }
};

// Throws InputError for a text that is not KIND:Y[:X] with KIND a mismatch kind.
Expectation parse_expectation(const std::string& text);

// --fault SITE@Y: only a build with fault hooks injects it, and only where the unit can show it.
FaultInjection parse_fault_option(const std::string& text, const RtlConfig& build);

}  // namespace shadesim::cosim_exe
