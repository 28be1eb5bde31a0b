// shadesim cosim / rtl-build / rtl-params: their options; the engines are sim/engines/cosim.h.
#include "sim/engines/cosim.h"

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sim/cli/commands.h"
#include "sim/cli/output_paths.h"
#include "sim/eda/verilator/rtl_build.h"
#include "sim/harness/number_checks.h"

namespace shadesim {
namespace {

// The co-simulation's own outputs (forwarded options) are checked before any build starts.
void check_forwarded_outputs(const std::vector<std::string>& rest) {
  for (size_t i = 0; i < rest.size(); ++i) {
    for (const auto& [option, folder] : {std::pair<std::string, bool>{"--json", false},
                                         std::pair<std::string, bool>{"--save-dir", true}}) {
      if (rest[i] == option && i + 1 < rest.size()) {
        check_output_path(rest[i + 1], folder, option);
      } else if (rest[i].rfind(option + "=", 0) == 0) {
        check_output_path(rest[i].substr(option.size() + 1), folder, option);
      }
    }
  }
}

void register_cosim_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CosimOptions>();
  CLI::App* sub = app.add_subcommand(
      "cosim",
      "Co-simulate one unit configuration: the Verilated RTL against the bit-accurate model "
      "(every\n"
      "pixel) and the cycle model (every scanline's cycle). The RTL is Verilated on demand into "
      "the\n"
      "build cache the first time a configuration is needed, and reused after that. Options not\n"
      "listed here go to the co-simulation itself: --scenario mixed|long|short|slow|maxbp|switch|\n"
      "tiny|edge|all, --seed, --runs, --gap-pct, --max-gap, --stall-pct, --expect-mismatch "
      "KIND:Y,\n"
      "--fault SITE@Y (a build with fault hooks: inject one deliberate fault),\n"
      "--save-dir, --json FILE, --min-spec-pct, --rows (run with any unit and --help to see "
      "them).");
  sub->add_option("--backend", o->backend, "cpp (Verilator C++) or systemc (Verilator in SystemC)")
      ->capture_default_str();
  sub->add_option("--config", o->config, "a named build (see --list) or a UnitConfig FILE.json");
  sub->add_option("--stream", o->stream,
                  "replay a saved command stream (text form; its header names the unit)");
  sub->add_option("--waves", o->waves,
                  "on a mismatch, write an FST of the cycles around it (cpp backend)")
      ->check(output_file());
  sub->add_option("--cache", o->cache, "build cache folder (default: <build>/rtl-cache)");
  sub->add_option(
         "--coverage", o->coverage,
         "run the covered build (line, toggle, user cover points) and write its Verilator\n"
         "coverage to FILE.dat, pass or fail (several runs: FILE_<i>.dat)")
      ->check(output_file());
  sub->add_option("--opt", o->optimization,
                  "compile a new build quick (-O0: builds fastest) or fast (-O2: simulates "
                  "fastest); a cached fast build is used either way. Default: quick for the "
                  "random scenarios (short), by the stream's length for --stream (quick under " +
                      std::to_string(kQuickBuildCycles) + " cycles, " +
                      std::to_string(kQuickCoveredBuildCycles) + " with --coverage)")
      ->check(CLI::IsMember({"quick", "fast"}));
  sub->add_flag("--netlist", o->netlist,
                "simulate the unit's gate-level netlist from Yosys (what `shadesim area` "
                "measures) in place of the RTL; no fault hooks, no coverage");
  sub->add_option("--netlist-cache", o->netlist_cache,
                  "with --netlist: folder of the cached netlists (default: <build>/netlist-cache)");
  sub->add_flag("--list", o->list, "list the named builds (sim/harness/builds.json)");
  sub->add_flag("--list-json", o->list_json, "with --list: as JSON");
  sub->allow_extras();
  sub->callback([o, sub, &exit_code]() {
    o->passthrough = sub->remaining();
    check_forwarded_outputs(o->passthrough);
    exit_code = run_cosim(*o);
  });
}

void register_rtl_build(CLI::App& app, int& exit_code) {
  auto b = std::make_shared<RtlBuildCommandOptions>();
  CLI::App* build = app.add_subcommand(
      "rtl-build",
      "Verilate and compile co-simulation executables into the build cache ahead of time (the\n"
      "commands that need one build it on demand anyway). Prints each executable's path.");
  build->add_option("--config", b->configs, "named builds or UnitConfig FILE.json files")
      ->delimiter(',');
  build->add_flag("--all", b->all,
                  "every named build in sim/harness/builds.json, on its own backends");
  build
      ->add_option("--backends", b->backends, "cpp, systemc, cpp_trace (default: each build's own)")
      ->delimiter(',');
  build->add_option("--cache", b->cache, "build cache folder (default: <build>/rtl-cache)");
  build->add_option("-j,--jobs", b->jobs, "builds at once (default: hardware threads)")
      ->check(non_negative_number());
  build->add_flag("--coverage", b->coverage, "the covered builds (what regress --coverage runs)");
  build->add_flag("--fault-hooks", b->fault_hooks,
                  "the fault-hook variants of the builds that have them (what runs with --fault "
                  "use; other runs use each build without its hooks)");
  build->add_flag("--runtime", b->runtime,
                  "compile the Verilator runtime of every flavour into the cache (once; the first "
                  "build of a new configuration then compiles only its own model)");
  build
      ->add_option("--opt", b->optimization,
                   "quick (-O0: builds fastest) or fast (-O2: simulates fastest)")
      ->capture_default_str()
      ->check(CLI::IsMember({"quick", "fast"}));
  build->add_flag("--print-key", b->print_key, "print each build's cache key and build nothing");
  build->add_flag("--print-source-dir", b->print_source_dir, "print the checkout the builds read");
  build->add_flag("--print-rtl-sources", b->print_rtl_sources,
                  "print shade_unit's sources, leaves first");
  build->callback([b, &exit_code]() { exit_code = run_rtl_build(*b); });
}

void register_rtl_params(CLI::App& app, int& exit_code) {
  auto p = std::make_shared<RtlParamsOptions>();
  CLI::App* params = app.add_subcommand(
      "rtl-params",
      "Print shade_unit's Verilog parameters for a configuration (model/rtl_parameters.h, the one\n"
      "mapping), one argument per line: verilator (-GNAME=V), iverilog (-Ptb_shade_unit.NAME=V)\n"
      "or yosys (chparam's -set NAME V list).");
  params->add_option("--config", p->config, "a named build or a UnitConfig FILE.json")->required();
  params->add_option("--tool", p->tool, "verilator, iverilog or yosys")->capture_default_str();
  params->callback([p, &exit_code]() { exit_code = run_rtl_params(*p); });
}

}  // namespace

void register_cosim(CLI::App& app, int& exit_code) {
  register_cosim_command(app, exit_code);
  register_rtl_build(app, exit_code);
  register_rtl_params(app, exit_code);
}

}  // namespace shadesim
