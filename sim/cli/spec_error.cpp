// shadesim spec-error: its options; the engine is sim/engines/spec_error.h.
#include "sim/engines/spec_error.h"

#include <CLI/CLI.hpp>
#include <memory>

#include "model/specular_units.h"
#include "sim/cli/commands.h"
#include "sim/cli/output_paths.h"

namespace shadesim {

void register_spec_error(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "spec-error",
      "Speed against error of the specular units (LUT, Schlick divider, W_m): bit-accurate units "
      "against exact t^n, with their costs, plus the reproduced paper figures");
  auto opt = std::make_shared<SpecErrorOptions>();
  cmd->add_option("--exponents", opt->exponents,
                  "exponents n: numbers, ranges a-b, a-b:step, comma-separated (default 1-1000)");
  cmd->add_option("--units", opt->units,
                  "all, or a comma list of " + specular_unit_names(true) + " (default all)");
  cmd->add_option("--points", opt->points,
                  "sample points per zone (epicentre, blooming, [0,1]) per exponent (default 256)");
  cmd->add_option("--json", opt->json, "write the results as JSON")->check(output_file());
  cmd->add_option("--csv", opt->csv, "write one row per unit and exponent as CSV")
      ->check(output_file());
  cmd->add_option(
         "--plot", opt->plot,
         "write a PNG of error against cost with the Pareto front (scripts/plot, matplotlib,\n"
         "from the --json report; without --json the report goes to PLOT.json)")
      ->check(output_file());
  cmd->add_flag("--no-papers", opt->no_papers, "skip the Bishop and Romanyuk reproductions");
  cmd->callback([opt, &exit_code]() { exit_code = run_spec_error(*opt); });
}

}  // namespace shadesim
