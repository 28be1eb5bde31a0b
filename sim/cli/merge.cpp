// shadesim merge DIR...: its options; the engine is sim/regress/merge.h.
#include "sim/regress/merge.h"

#include <CLI/CLI.hpp>
#include <memory>

#include "sim/cli/commands.h"
#include "sim/cli/output_paths.h"

namespace shadesim {

void register_merge(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* sub = app.add_subcommand(
      "merge",
      "Merge the results that `shadesim regress` runs wrote into one or more output folders "
      "(shards,\n"
      "job lines of --emit-jobs, resumed runs) into the summary table, JSON and JUnit one regress\n"
      "writes. Exits 1 when a run the folders' plans name has no result (named, with whether it\n"
      "started), when a run is in two folders, when a result file cannot be read (named), and on "
      "any\n"
      "mismatch, hang, timeout or error; 0 only when the whole regression is there and passed.");
  sub->add_option("dirs", o->dirs, "regress output folders (each with plans/ and runs/)")
      ->required();
  sub->add_option("--json", o->json_path,
                  "write every run's figures as JSON (the format of regress --json)")
      ->check(output_file());
  sub->add_option("--junit", o->junit_path, "write JUnit XML for CI")->check(output_file());
  sub->callback([o, &exit_code]() { exit_code = run_merge(*o); });
}

}  // namespace shadesim
