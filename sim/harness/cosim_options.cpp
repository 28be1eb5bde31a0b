// The co-simulation executable's command line, read with CLI11 (sim/harness/cosim_options.h).
#include "sim/harness/cosim_options.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "sim/harness/fault_site.h"
#include "sim/harness/number_checks.h"

namespace shadesim::cosim_exe {
namespace {

// The kinds --expect-mismatch accepts (a deliberate fault may show as any of them).
constexpr Mismatch::Kind kExpectableKinds[] = {Mismatch::Kind::kPixel, Mismatch::Kind::kCycle,
                                               Mismatch::Kind::kReady, Mismatch::Kind::kExtraPixel,
                                               Mismatch::Kind::kHang,  Mismatch::Kind::kTimeout};

// --json names a file, except after --list, which prints JSON to stdout.
std::string json_option_error(const Options& o) {
  if (o.list && o.list_json && !o.json_path.empty()) {
    return "--list --json prints to stdout; it takes no file name";
  }
  if (!o.list && o.list_json && o.json_path.empty()) {
    return "--json needs a file name (only --list --json prints to stdout)";
  }
  return "";
}

}  // namespace

CommandLine parse_command_line(int argc, char** argv, const CosimExecutable& exe) {
  CLI::App app{"Co-simulate the Verilated shade_unit (" + exe.backend +
               " backend) against the bit-accurate model and the cycle model"};
  CommandLine line;
  Options& o = line.options;
  app.add_option("--unit", o.unit_path, "the unit (UnitConfig JSON) this build simulates");
  app.add_option("--config", o.config, "the build's name, for reports")->capture_default_str();
  app.add_flag("--list", o.list,
               "print the parameters this executable was Verilated with (--json: as JSON)");
  app.add_option("--scenario", o.scenario,
                 "mixed, long, short, slow, maxbp, switch, tiny, edge, or all");
  app.add_option("--stream", o.stream_path, "replay a saved command stream (text form)");
  app.add_option("--seed", o.seed, "seed of the stream and of the stimulus (printed on every run)");
  app.add_option("--rows", o.rows, "override: scanlines per generated stream (for benchmarks)")
      ->check(CLI::Range(1, 32768));
  app.add_option("--runs", o.runs, "consecutive seeds per scenario")->check(positive_number());
  app.add_option("--gap-pct", o.gap_pct, "override: chance of idle cycles before a command word")
      ->check(CLI::Range(0, 100));
  app.add_option("--max-gap", o.max_gap, "override: longest idle gap")
      ->check(CLI::Range(1, 100000));
  app.add_option("--stall-pct", o.stall_pct, "override: chance of pix_ready low per cycle")
      ->check(CLI::Range(0, 99));
  app.add_option("--expect-mismatch", o.expect,
                 "KIND:Y[:X] - succeed only if the first mismatch is KIND "
                 "(pixel|cycle|ready|extra-pixel|hang|timeout) "
                 "at scanline y=Y (and column X; 'first': the x0 of the stream's first span "
                 "on row Y)");
  std::string sites;
  for (const FaultSiteInfo& s : fault_sites())
    sites += std::string("\n    ") + s.name + ": " + s.what;
  app.add_option("--fault", o.fault,
                 "SITE@Y - inject one deliberate fault on row Y (a build with fault hooks, e.g. "
                 "grey_s428w); SITE is one of:" +
                     sites);
  app.add_option("--replay-prefix", o.replay_prefix,
                 "the shadesim command line replay lines start with (shadesim cosim and regress "
                 "pass it: backend, cache, netlist)");
  app.add_option("--save-dir", o.save_dir, "where a failing run's command stream is saved");
  auto* json_opt =
      app.add_option("--json", o.json_path, "write each run's result as JSON to this file")
          ->expected(0, 1);
  app.add_option(
      "--waves", o.waves_path,
      "on a mismatch, re-run with tracing and write an FST of the cycles around it (traced build)");
  app.add_option(
         "--min-spec-pct", o.min_spec_pct,
         "fail a run where the specular term changes fewer than this percentage of the pixels")
      ->check(CLI::Range(0.0, 100.0));
  app.add_option(
      "--watchdog", o.watchdog,
      "cycles without pix_valid_o, while pixels are still expected, that count as a hang "
      "(default 0: the cycle model's longest pixel-less stretch on this stream + 1000)");
  app.add_option(
      "--coverage", o.coverage_path,
      "write the run's line/toggle/user coverage to FILE.dat, pass or fail (covered build)");
  app.add_option("--trace-run", o.trace_run_path,
                 "after the run passes, run it again with every cycle it clocked dumped into this "
                 "FST file (traced build, one job; for switching activity)");
  app.add_option("--waves-before", o.waves_before, "cycles before the mismatch in the waveform")
      ->capture_default_str();
  app.add_option("--waves-after", o.waves_after, "cycles after the mismatch in the waveform")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    line.exit_status = rc == 0 ? 0 : 2;
    return line;
  }
  o.list_json = json_opt->count() > 0;
  if (const std::string why = json_option_error(o); !why.empty()) {
    std::cerr << exe.command << ": error: " << why << '\n';
    line.exit_status = 2;
  }
  return line;
}

Expectation parse_expectation(const std::string& text) {
  Expectation e;
  if (text.empty()) return e;
  e.text = text;
  const auto colon = text.find(':');
  const auto second = colon == std::string::npos ? colon : text.find(':', colon + 1);
  try {
    if (colon == std::string::npos) throw std::invalid_argument(text);
    e.kind = text.substr(0, colon);
    const std::string row = text.substr(colon + 1, second - colon - 1);
    size_t used = 0;
    e.y = std::stoi(row, &used);
    if (used != row.size()) throw std::invalid_argument(text);
    if (second != std::string::npos) {
      const std::string column = text.substr(second + 1);
      if (column == "first") {
        e.first_of_row = true;
      } else {
        e.x = std::stoi(column, &used);
        if (used != column.size()) throw std::invalid_argument(text);
      }
    }
  } catch (const std::logic_error&) {
    throw InputError("--expect-mismatch '" + text +
                     "': expected KIND:Y or KIND:Y:X (X a column or 'first'), e.g. pixel:17 or "
                     "pixel:17:first");
  }
  std::string kinds;
  for (Mismatch::Kind k : kExpectableKinds) {
    if (to_string(k) == e.kind) return e;
    kinds += (kinds.empty() ? "" : ", ") + to_string(k);
  }
  throw InputError("--expect-mismatch kind '" + e.kind + "': expected one of " + kinds);
}

FaultInjection parse_fault_option(const std::string& text, const RtlConfig& build) {
  if (text.empty()) return {};
  FaultInjection f;
  try {
    f = parse_fault(text);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--fault: ") + e.what());
  }
  if (!build.faults.hooks) {
    throw InputError("--fault " + text +
                     ": this build has no fault hooks (a named build with "
                     "\"fault_hooks\": true in sim/harness/builds.json has them, e.g. grey_s428w)");
  }
  if (const std::string why = fault_unsupported(f, build.unit); !why.empty()) {
    throw InputError("--fault " + text + ": " + why);
  }
  return f;
}

}  // namespace shadesim::cosim_exe
