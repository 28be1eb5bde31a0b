// shadesim report [INPUTS...]: its options; the engine is sim/report/report.h.
#include "sim/report/report.h"

#include <CLI/CLI.hpp>
#include <memory>

#include "sim/cli/commands.h"
#include "sim/cli/output_paths.h"

namespace shadesim {

void register_report(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App* sub = app.add_subcommand(
      "report",
      "Write one self-contained HTML page (OUT/index.html; images embedded, nothing fetched) from "
      "the\n"
      "JSON the other commands write: per scene the model, reference and error images (render\n"
      "--json), the specular Pareto plot (spec-error --json) and the width Pareto (explore "
      "--json)\n"
      "drawn by scripts/plot, the cycles-per-pixel breakdown (cycles --json), each unit's area,\n"
      "clock, energy and layout picture (area --json, layout --json) beside its error and "
      "cycles,\n"
      "the regression table with each failure's replay command (regress --json), and the tool\n"
      "versions. Each JSON is recognised by its keys. A section without input says so. Exits 1\n"
      "when a named input is missing or malformed, a plot or a --run step failed (the page is\n"
      "written anyway).");
  sub->add_option(
      "inputs", o->inputs,
      "report JSON files, or folders holding them (read with the folders one level down);\n"
      "default: out (where scripts/render, scripts/run and --run write)");
  sub->add_option("-o,--out", o->out_dir, "folder of the page (index.html) and its plots")
      ->capture_default_str()
      ->check(output_folder());
  sub->add_option(
         "--run", o->run,
         "first produce the inputs on the shipped scenes (run from the project folder), into "
         "out/:\n"
         "all, or a comma list of render, cycles, area (every scenes/*.json; area synthesises\n"
         "each own unit: 38 minutes for the five the first time), spec-error, explore "
         "(scenes/sphere.json),\n"
         "regress (needs Verilator; minutes the first time), layout (scenes/sphere.json only; "
         "about\n"
         "a minute cold; not in all)")
      ->excludes("inputs");
  sub->callback([o, &exit_code]() { exit_code = run_report(*o); });
}

}  // namespace shadesim
