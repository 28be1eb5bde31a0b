// shadesim regress: its options, and their checks; the engine is sim/regress/regress.h.
#include "sim/regress/regress.h"

#include <CLI/CLI.hpp>
#include <memory>
#include <stdexcept>
#include <string>

#include "sim/cli/commands.h"
#include "sim/cli/config_option.h"
#include "sim/cli/output_paths.h"
#include "sim/cli/stimulus_options.h"
#include "sim/eda/verilator/rtl_build.h"
#include "sim/harness/number_checks.h"
#include "sim/harness/random_stream.h"

namespace shadesim {
namespace {

// The random scenarios' names, comma-separated (for --random's help and its error).
std::string scenario_list() {
  std::string s;
  for (const auto& w : scenario_names()) s += (s.empty() ? "" : ", ") + w;
  return s;
}

// What a regression runs: scenes, units, backends, seeds and stimulus.
void add_run_options(CLI::App* sub, RegressOptions& o) {
  sub->add_option("scenes", o.scenes, "scene files (default: scenes/*.json)")
      ->check(CLI::ExistingFile);
  sub->add_option("--random", o.random,
                  "SCENARIO (repeatable): also co-simulate this random scenario of `shadesim cosim "
                  "--scenario`\n(" +
                      scenario_list() +
                      ") on each named or file configuration, after the scene runs: its seeded "
                      "stream\nunder the regression's stimulus, a run of its own "
                      "(random-SCENARIO__<config>__<backend>__seed<S>)")
      ->allow_extra_args(false);
  sub->add_flag("--random-only", o.random_only, "with --random: run no scenes");
  sub->add_option("--configs", o.configs, "named builds to run every scene on (see --list)")
      ->delimiter(',')
      ->allow_extra_args(false);
  sub->add_option("--config", o.config_files,
                  "the unit to run every scene on (repeatable): own (the default: each scene's "
                  "own unit), default\n(the default widths), a named build or a UnitConfig "
                  "FILE.json")
      ->check(unit_choice_validator())
      ->allow_extra_args(false);
  sub->add_option("--backends", o.backends, "cpp, systemc or both (comma-separated)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->capture_default_str();
  sub->add_option("--seed", o.seed,
                  "seed of the first scene x configuration; each next one gets the next seed "
                  "(printed on every run)")
      ->capture_default_str();
  sub->add_option("-j,--jobs", o.jobs,
                  "parallel builds and co-simulations (default: hardware threads)")
      ->check(non_negative_number());
  add_stimulus_options(sub, o.gap_pct, o.max_gap, o.stall_pct);
}

// Where its results go, and how its builds are made.
void add_output_options(CLI::App* sub, RegressOptions& o) {
  sub->add_option("-o,--out", o.out_dir,
                  "where plans and each run's folder (stream, logs, result) go")
      ->capture_default_str()
      ->check(output_folder());
  sub->add_option("--junit", o.junit_path, "write JUnit XML for CI")->check(output_file());
  sub->add_option("--json", o.json_path, "write every run's figures as JSON")->check(output_file());
  sub->add_option("--cache", o.cache, "RTL build cache folder (default: <build>/rtl-cache)");
  sub->add_option("--opt", o.optimization,
                  "compile new RTL builds quick (-O0: builds fastest) or fast (-O2: simulates "
                  "fastest); default: quick for runs under " +
                      std::to_string(kQuickBuildCycles) + " cycles (" +
                      std::to_string(kQuickCoveredBuildCycles) +
                      " with --coverage; a cached fast build is used either way)")
      ->check(CLI::IsMember({"quick", "fast"}));
}

// Many machines: shards, job lines, resuming, and the limits a run is held to.
void add_scale_out_options(CLI::App* sub, RegressOptions& o) {
  sub->add_option("--shard", o.shard,
                  "I/N: run only the I-th of N equal shards of the job list (runs I, I+N, I+2N, "
                  "...; 1 <= I <= N)");
  sub->add_option(
      "--emit-jobs", o.emit_jobs,
      "write one self-contained shell command per run into FILE (for GNU parallel, a batch\n"
      "system) instead of running; each writes into --out");
  sub->add_option(
      "--resume", o.resume,
      "DIR: a regress output folder; run the runs its plans name that have no result there yet\n"
      "(and those that ended in an error), with the settings they were planned with");
  sub->add_option("--timeout", o.timeout,
                  "seconds a run may take before it is killed and reported as a timeout (0: none)")
      ->check(non_negative_number())
      ->capture_default_str();
  sub->add_option(
      "--watchdog", o.watchdog,
      "cycles without pix_valid_o, while pixels are still expected, that count as a hang\n"
      "(default 0: the cycle model's longest pixel-less stretch of each stream + 1000)");
}

// Faults, waves, the netlist in place of the RTL, coverage.
void add_check_options(CLI::App* sub, RegressOptions& o) {
  sub->add_option("--fault", o.fault,
                  "SITE@Y: every run injects this deliberate fault (configurations with fault\n"
                  "hooks only; `shadesim cosim --help` lists the sites), to see the regression "
                  "catch it");
  sub->add_flag("--waves", o.waves,
                "on a mismatch, re-run the C++ backend with FST tracing of the window around it");
  sub->add_flag("--netlist", o.netlist,
                "simulate the gate-level netlist Yosys makes of each configuration (the flat\n"
                "netlist `shadesim area` measures, written by write_verilog) in place of the RTL;\n"
                "cached per configuration (--netlist-cache), no fault hooks, no --coverage");
  sub->add_option("--netlist-cache", o.netlist_cache,
                  "with --netlist: folder of the cached netlists (default: <build>/netlist-cache)");
  sub->add_flag("--list", o.list, "list the named builds and exit");
  sub->add_flag(
      "--coverage", o.coverage,
      "run covered builds (Verilator line, toggle and user cover points) and merge their\n"
      "coverage into OUT/coverage/: per-file line and toggle table, uncovered rtl/ lines, lcov\n"
      "coverage.info, annotated sources; exclusions are the RTL's coverage_off pragmas");
  sub->add_option("--coverage-min", o.coverage_min,
                  "PCT: with --coverage (implied), exit 1 when rtl/ line coverage is below PCT")
      ->check(CLI::Range(0.0, 100.0));
}

// --coverage-min implies --coverage; a netlist has neither coverage nor fault hooks.
void check_options(RegressOptions& o) {
  if (o.coverage_min >= 0) o.coverage = true;
  for (const auto& name : o.random) {
    try {
      scenario_by_name(name);
    } catch (const std::invalid_argument&) {
      throw std::invalid_argument("--random '" + name + "': unknown scenario; expected one of " +
                                  scenario_list());
    }
  }
  if (o.random_only && o.random.empty())
    throw std::invalid_argument("--random-only: name a scenario with --random SCENARIO");
  if (o.random_only && !o.scenes.empty())
    throw std::invalid_argument("--random-only runs no scenes; drop the scene files");
  if (o.netlist && o.coverage)
    throw std::invalid_argument(
        "--netlist: a gate-level netlist has no RTL coverage; drop "
        "--coverage");
  if (o.netlist && !o.fault.empty())
    throw std::invalid_argument("--netlist: a netlist has no fault hooks; drop --fault");
}

}  // namespace

void register_regress(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RegressOptions>();
  CLI::App* sub = app.add_subcommand(
      "regress",
      "RTL regression, the main job: every scene x configuration x backend (Verilator C++ and\n"
      "Verilator-in-SystemC). By default each scene runs on its own configuration - the smallest\n"
      "unit that shades it (channels and lights as it needs; a scene naming the `ideal` unit, "
      "which\n"
      "has no hardware, gets the W_16 unit; `shadesim config --help` states each rule). --configs "
      "runs\n"
      "named builds (sim/harness/builds.json,\n"
      "see --list), --config any UnitConfig FILE.json. The RTL of each configuration is Verilated "
      "on\n"
      "demand into the build cache. Each run compares every pixel bit for bit with the "
      "bit-accurate\n"
      "model and every scanline's completion cycle with the cycle model, under seeded input gaps "
      "and\n"
      "output back-pressure. Exits 1 on any mismatch, hang, timeout or error (naming it, with a "
      "replay\n"
      "command) and when no run was executed.\n"
      "\n"
      "Many machines: each run writes OUT/runs/<scene>__<config>__<backend>__seed<S>/run.json the\n"
      "moment it ends. --shard I/N runs every N-th run of the job list (Slurm: --shard\n"
      "$SLURM_ARRAY_TASK_ID/N), --emit-jobs FILE writes one command per run for GNU parallel,\n"
      "--resume OUT runs what OUT's plan has no result for, and `shadesim merge OUT...` reports "
      "the\n"
      "whole regression.");
  add_run_options(sub, *o);
  add_output_options(sub, *o);
  add_scale_out_options(sub, *o);
  add_check_options(sub, *o);
  sub->callback([o, &exit_code]() {
    check_options(*o);
    exit_code = run_regress(*o);
  });
}

}  // namespace shadesim
