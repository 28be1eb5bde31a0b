// shadesim cycles SCENE: its options; the engine is sim/engines/cycles.h.
#include "sim/engines/cycles.h"

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "sim/cli/commands.h"
#include "sim/cli/config_option.h"
#include "sim/cli/output_paths.h"
#include "sim/cli/stimulus_options.h"
#include "sim/cli/width_options.h"
#include "sim/harness/number_checks.h"

namespace shadesim {

void register_cycles(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CyclesOptions>();
  CLI::App* sub = app.add_subcommand(
      "cycles",
      "Estimate cycles per pixel for a scene from the cycle model alone (the RTL's control, clock "
      "by\n"
      "clock, without its datapath: exact to the cycle, far faster than co-simulation), with a\n"
      "breakdown of where the cycles go: pixels, span setup, unit stalls, table reloads, material\n"
      "drains, command words and gaps, back-pressure. With no gaps and no back-pressure (the "
      "default)\n"
      "every figure, the breakdown included, comes from a closed-form recurrence over commands "
      "and\n"
      "spans (model/cycle_estimate.h), equal to the clocked model's (--clocked runs both and "
      "checks).\n"
      "Per triangle: its decoder cycles are the cycles on which the decoder takes its words (the\n"
      "TRIANGLE header, its coefficient words, the SPAN headers up to the next TRIANGLE; one item "
      "a\n"
      "cycle, waiting not counted); its engine cycles are its pixels' beats x the specular slot's\n"
      "interval. It is setup-bound if its decoder cycles exceed its engine cycles, else "
      "fill-bound.");
  sub->add_option("scene", o->scene, "scene JSON file")->required()->check(CLI::ExistingFile);
  sub->add_option("--specular", o->specular,
                  "specular unit: ideal|lut|schlick|wpow (default: the scene's)");
  sub->add_option("--channels", o->channels,
                  "build with this many channels (default: what the scene needs)")
      ->check(CLI::IsMember({1, 3}));
  sub->add_option("--lights", o->lights,
                  "build with series for this many lights (default: the scene's)")
      ->check(CLI::Range(1, 8));
  sub->add_option("--port-words", o->port_words,
                  "command port width: 64-bit words per handshake (default: the unit's;\n"
                  "given, it overrides the unit's)")
      ->check(CLI::IsMember({1, 2, 4, 8}));
  sub->add_option("--tri-queue", o->tri_queue,
                  "triangle queue depth: coefficient banks; > 1 adds a span queue (default: the\n"
                  "unit's; given, it overrides the unit's)")
      ->check(CLI::Range(1, 8));
  sub->add_option(
         "--lanes", o->lanes,
         "pixel lanes: pixels of one span per clock (k-step forward differences, lane j at\n"
         "x0 + j; default: the unit's; given, it overrides the unit's)")
      ->check(CLI::IsMember({1, 2, 4}));
  sub->add_option(
         "--material-buffers", o->material_buffers,
         "material buffers: 2 loads a MATERIAL, and a per-material TABLE (a per-exponent LUT's\n"
         "reload), into the bank no span in flight reads, so neither drains the datapath;\n"
         "default: the unit's; given, it overrides the unit's")
      ->check(CLI::IsMember({1, 2}));
  sub->add_option("--span-setup", o->span_setup,
                  "span setup in the unit (coefficients on the port) or on the host (start\n"
                  "values on every SPAN, tri_queue 1); default: the unit's")
      ->check(CLI::IsMember({"unit", "host"}));
  sub->add_option("--diffuse-colour", o->diffuse_colour,
                  "diffuse colour rolled into the series (one per light and channel) or\n"
                  "multiplied in the unit (one N.L series per light); default: the unit's")
      ->check(CLI::IsMember({"series", "multiply"}));
  sub->add_option("--seed", o->seed, "stimulus seed")->capture_default_str();
  add_stimulus_options(sub, o->gap_pct, o->max_gap, o->stall_pct);
  sub->add_flag("--regress-stimulus", o->regress_stimulus,
                "the regression's gaps and back-pressure (" +
                    std::to_string(kRegressStimulus.gap_pct) + "% gaps, max " +
                    std::to_string(kRegressStimulus.max_gap) + ", " +
                    std::to_string(kRegressStimulus.stall_pct) +
                    "% back-pressure): with the run's --seed, the cycles `regress` reports")
      ->excludes("--gap-pct")
      ->excludes("--max-gap")
      ->excludes("--stall-pct");
  sub->add_option("--json", o->json_path, "write the figures as JSON")->check(output_file());
  sub->add_flag(
      "--clocked", o->clocked,
      "also run the clocked cycle model when there are no gaps or back-pressure, and fail if the\n"
      "closed form disagrees with it (with gaps or back-pressure it is the only one that runs)");
  sub->add_option(
         "--max-cycles-per-pixel", o->max_cycles_per_pixel,
         "warn when the unit takes more cycles per pixel than this with no gaps and no\n"
         "back-pressure (the unit's own figure; with gaps or back-pressure that figure is\n"
         "judged, not the run's), naming the resource that limits it. Default: config's, 1.10\n"
         "cycles per beat of the unit's lanes (1.10 x beats / pixels; 1.10 with one lane)")
      ->check(positive_number());
  sub->add_option("--clock-mhz", o->clock_mhz,
                  "the unit's clock in MHz (e.g. the Fmax `shadesim area` prints): the report\n"
                  "adds pixels per second, the clock over the cycles per pixel")
      ->check(positive_number());
  sub->add_option("--worst", o->worst, "setup-bound triangles to list, worst first")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  add_width_options(*sub, o->widths);
  add_config_option(*sub, o->config, {"--specular", "--channels", "--lights"});
  sub->callback([o, sub, &exit_code]() {
    o->config = unit_choice_in_effect(*sub, o->config, {"--specular", "--channels", "--lights"});
    if (o->regress_stimulus) {
      o->gap_pct = kRegressStimulus.gap_pct;
      o->max_gap = kRegressStimulus.max_gap;
      o->stall_pct = kRegressStimulus.stall_pct;
    }
    exit_code = run_cycles(*o);
  });
}

}  // namespace shadesim
