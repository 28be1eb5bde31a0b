// shadesim layout (--config FILE.json | SCENE): its options; the engine is sim/engines/layout.h.
#include "sim/engines/layout.h"

#include <CLI/CLI.hpp>
#include <memory>
#include <stdexcept>

#include "sim/cli/commands.h"
#include "sim/cli/config_option.h"
#include "sim/cli/output_paths.h"

namespace shadesim {

void register_layout(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<LayoutJobOptions>();
  CLI::App* sub = app.add_subcommand(
      "layout",
      "The unit placed and routed in osu018 0.18 um with Debian's qflow 1.3, from shadesim\n"
      "area's mapped, fanout-buffered netlist (docs/layout.md):\n"
      "  area      die and core at the stated initial density (cells / core rows)\n"
      "  routing   wire length per metal layer and vias (qrouter)\n"
      "  timing    OpenSTA with the routed parasitics (rc2dly's SPEF, fixed up for OpenSTA),\n"
      "            area's constraints; every net's annotation counted; Fmax, critical path\n"
      "            with its wires' delay\n"
      "  checks    magic DRC errors and netgen LVS\n"
      "  files     GDS (routing and the cells' LEF abstracts), DEF, SPEF, a PNG picture\n"
      "Cached per netlist, scripts, options and tool versions in --cache (area's cache).\n"
      "Exit 1 when DRC finds errors, LVS is not clean or a net has no parasitics.");
  sub->add_option("--config", o->config_path,
                  "the unit: own (the default: SCENE's own unit), default, a named build or a "
                  "UnitConfig FILE.json")
      ->check(unit_choice_validator());
  sub->add_option("scene", o->scene, "scene JSON file: lay out the unit --config names for it")
      ->check(CLI::ExistingFile);
  sub->add_option("--cache", o->cache_dir, "cache folder (shared with shadesim area)")
      ->capture_default_str();
  sub->add_option("--json", o->json_path, "also write every figure as JSON")->check(output_file());
  sub->add_option("--density", o->density,
                  "qflow's initial_density: the cells' share of the core rows (the rest FILL)")
      ->check(CLI::Range(0.1, 0.95))
      ->capture_default_str();
  sub->add_option("--clock-mhz", o->clock_mhz, "the post-route analysis clock")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->callback([o, &exit_code]() {
    if (o->config_path.empty() && o->scene.empty()) {
      throw std::invalid_argument(
          "layout: give a SCENE (its own unit), or --config NAME|FILE.json (see shadesim layout "
          "--help)");
    }
    exit_code = run_layout(*o);
  });
}

}  // namespace shadesim
