// shadesim explore SCENE...: its options; the engine is sim/engines/explore.h.
#include "sim/engines/explore.h"

#include <CLI/CLI.hpp>
#include <memory>

#include "sim/cli/commands.h"
#include "sim/cli/config_option.h"
#include "sim/cli/output_paths.h"
#include "sim/eda/sta/liberty_flow.h"
#include "sim/harness/number_checks.h"

namespace shadesim {

void register_explore(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ExploreJobOptions>();
  auto clock_target = std::make_shared<std::string>("osu018");
  CLI::App* sub = app.add_subcommand(
      "explore",
      "Sweep the unit's widths with the bit-accurate model and find the cheapest that meet an\n"
      "error budget. Every point: error against the double reference (max and mean LSB per\n"
      "channel, PSNR, % of pixels more than 1 LSB off), cycles per pixel (cycle model) and area\n"
      "(generic cells: shadesim area's estimate, a Yosys-measured unit of the same specular kind\n"
      "scaled module by module; with none in --area-cache the start is synthesised once, "
      "minutes).\n"
      "Host setup (projection, Taylor setup, visibility, reference) is done once per scene and\n"
      "output width; a point only re-quantizes the stream and re-runs the model.\n"
      "\n"
      "Search:\n"
      "  1. per stage: each knob swept alone, the others at the start widths - coefficient\n"
      "     integer/fraction bits; series fraction/integer bits, trn/rnd, wrap/sat; the specular\n"
      "     unit's widths and output fraction bits; specular colour fraction bits; output bits\n"
      "     (swept for the table, never narrowed: they are what you asked for). A knob's minimum\n"
      "     is its cheapest value (area, then narrowest) meeting the budget, else its start.\n"
      "     The structure is swept beside them for the table and the front, never chosen (the\n"
      "     search keeps the start's; --widths-only skips it): span setup site (unit|host), the\n"
      "     host's start depth (1|2), the diffuse colour (series|multiply; with colour) and the\n"
      "     pipelining (c0|c1|c2: combine_stages; c2 sq2: square_stages 2, a pipelined W_m).\n"
      "  2. joint: combine the minima; while that breaks the budget, try every knob one step\n"
      "     wider (choices back to the start's) and take the cheapest step that meets the\n"
      "     budget, else the one buying the most error (max real LSB + mean LSB) per area added.\n"
      "  3. Pareto front of every evaluated point: (max LSB, mean LSB) against area and\n"
      "     throughput (points at the requested output bits; error is in LSBs of a point's own\n"
      "     output, so other output widths are shown but not compared). Throughput: Mpixel/s\n"
      "     where both points are measured, else cycles per pixel between points of one\n"
      "     pipelining (a pipeline register buys clock, which only the measurement shows).\n"
      "Then the chosen point's error is split by source: (1) the unit's shading function vs\n"
      "exact pow, (2) Taylor truncation, (3) fixed-point quantization; widths fix only (3).\n"
      "Then (unless --estimate-only) every point on the front, and the chosen one, is measured\n"
      "by shadesim area (cached): Yosys's cells, nextpnr-ice40's Fmax on an HX8K (not with\n"
      "--no-pnr) and the unit mapped onto osu018 0.18 um and timed by OpenSTA, Fmax = 1000 /\n"
      "(4 ns - worst slack) (not with --no-liberty); Mpixel/s = Fmax / cycles per pixel.\n"
      "Exit status 0 when a point meets the budget, 1 when none does, 2 on bad input;\n"
      "--clock-mhz does not change it.");
  sub->add_option("scenes", o->scenes, "scene JSON file(s); one unit must serve them all")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--budget", o->budget_lsb, "error budget: max LSB off, every pixel and channel")
      ->check(non_negative_number())
      ->capture_default_str();
  sub->add_option("--setup-budget", o->setup_budget_lsb,
                  "Taylor error budget per triangle in output LSBs (default: the scene's, else 1)")
      ->check(positive_number());
  sub->add_option("--max-depth", o->max_depth, "subdivision depth limit per triangle")
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
  sub->add_option(
         "--config", o->config_path,
         "start from this unit: own (the default: the scenes' own configuration, as shadesim "
         "config\nderives it), default (the default widths, the first scene's structure), a "
         "named build or a\nUnitConfig FILE.json")
      ->check(unit_choice_validator());
  sub->add_option("--out-bits", o->out_bits, "output bits per channel for the derived start")
      ->check(CLI::Range(1, 16))
      ->capture_default_str()
      ->excludes("--config");
  sub->add_option("--specular", o->specular,
                  "specular unit: ideal|lut|schlick|wpow, replacing the start's (its widths stay)");
  sub->add_option("-j,--jobs", o->jobs, "threads evaluating points")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  sub->add_option(
         "--json", o->json_path,
         "write every point, the search and the error split as JSON (scripts/plot draws it)")
      ->check(output_file());
  sub->add_option("--csv", o->csv_path,
                  "write every point as CSV (a measured point with its library um^2, Fmax, "
                  "Mpixel/s\nand meets_clock, as in --json)")
      ->check(output_file());
  sub->add_option("-o,--out", o->out_dir,
                  "folder for the config files: start.json, chosen.json, pareto_<point>.json\n"
                  "(default out/explore/<first scene>)")
      ->check(output_folder());
  sub->add_option(
         "--area-cache", o->area_cache,
         "shadesim area's cache: the measured units the area estimate scales from (the start\n"
         "is synthesised into it once when no unit with its specular kind is there)")
      ->capture_default_str();
  sub->add_flag("--widths-only", o->widths_only,
                "sweep the widths alone, keeping the start's span setup, start depth, diffuse "
                "colour and\npipelining (fewer points on the front, so fewer syntheses)");
  sub->add_flag(
      "--verify", o->verify,
      "co-simulate the chosen point on every scene in RTL, both backends (shadesim regress with\n"
      "--config; its RTL is Verilated on demand) and mark it verified: 0 pixel, 0 cycle "
      "mismatches");
  sub->add_option(
      "--emit-jobs", o->emit_jobs,
      "write the regress runs --verify would do into FILE, one shell command per line (for GNU\n"
      "parallel or a batch system; README \"Regression on many machines\") instead of running "
      "them");
  CLI::Option* estimate_only = sub->add_flag(
      "--estimate-only", o->estimate_only,
      "do not synthesise the Pareto points: the front is drawn on estimated areas and "
      "labelled so\n(by default every point on it, and the chosen one, is measured by "
      "shadesim area: minutes\neach the first time, cached after)");
  sub->add_flag("--no-pnr", o->no_pnr,
                "measure the front without nextpnr-ice40 (no iCE40 Fmax, no iCE40 Mpixel/s; much "
                "quicker)");
  CLI::Option* liberty =
      sub->add_option("--liberty", o->liberty,
                      "map the front's points onto this Liberty (.lib) library instead of osu018\n"
                      "(" +
                          std::string(kDefaultLiberty) + ")")
          ->check(CLI::ExistingFile);
  sub->add_flag("--no-liberty", o->no_liberty,
                "measure the front without the standard-cell mapping and OpenSTA (no um^2, no "
                "library Fmax,\nno library Mpixel/s)")
      ->excludes(liberty);
  CLI::Option* clock =
      sub->add_option(
             "--clock-mhz", o->clock_mhz,
             "a clock to hold the measured front against: each point is marked whether its Fmax "
             "on\n"
             "--clock-target meets it, and the output ends with one line: the cheapest measured\n"
             "point within the budget that meets it, else the fastest and the critical path that\n"
             "limits it. Reported, not enforced: the exit status does not depend on it")
          ->check(positive_number())
          ->excludes(estimate_only);
  sub->add_option(
         "--clock-target", *clock_target,
         "where --clock-mhz is timed: osu018 (the front's library Fmax, OpenSTA; --liberty "
         "for\nanother library) or ice40 (nextpnr-ice40's Fmax on an HX8K)")
      ->check(CLI::IsMember({"osu018", "ice40"}))
      ->capture_default_str()
      ->needs(clock);
  sub->add_flag("-q,--quiet", o->quiet, "print nothing (use with --json / --csv)");
  sub->callback([o, clock_target, &exit_code]() {
    o->clock_site = parse_clock_site(*clock_target, "--clock-target");
    // Each site's Fmax comes from a flow the front can be measured without.
    if (o->clock_mhz > 0 && o->clock_site == ClockSite::kIce40 && o->no_pnr)
      throw CLI::ValidationError("--clock-target ice40",
                                 "needs nextpnr-ice40's Fmax: it excludes --no-pnr");
    if (o->clock_mhz > 0 && o->clock_site == ClockSite::kLiberty && o->no_liberty)
      throw CLI::ValidationError("--clock-mhz",
                                 "is timed on the library (--clock-target osu018): it excludes "
                                 "--no-liberty");
    exit_code = run_explore(*o);
  });
}

}  // namespace shadesim
