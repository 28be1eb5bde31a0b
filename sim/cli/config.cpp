// shadesim config SCENE...: its options; the engine is sim/engines/config.h.
#include "sim/engines/config.h"

#include <CLI/CLI.hpp>
#include <memory>
#include <sstream>
#include <string>

#include "derive/reasons.h"
#include "sim/cli/commands.h"
#include "sim/cli/output_paths.h"
#include "sim/harness/number_checks.h"

namespace shadesim {
namespace {

// The derivation's rules as --help lists them: each rule's fields, then its text wrapped to the
// help's width, in derivation_rules' order (derive/reasons.h: each rule is defined beside the
// code that applies it).
std::string config_rules_text() {
  constexpr size_t kIndent = 15, kWidth = 96;
  std::string out;
  for (const DerivationRule& rule : derivation_rules()) {
    std::string line = "  " + std::string(rule.fields);
    line += std::string(line.size() + 2 > kIndent ? 2 : kIndent - line.size(), ' ');
    bool first = true;
    std::istringstream words(rule.text);
    for (std::string word; words >> word;) {
      if (!first && line.size() + 1 + word.size() > kWidth) {
        out += line + '\n';
        line = std::string(kIndent, ' ');
        first = true;
      }
      line += (first ? "" : " ") + word;
      first = false;
    }
    out += line + '\n';
  }
  return out;
}

}  // namespace

void register_config(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ConfigOptions>();
  CLI::App* sub = app.add_subcommand(
      "config",
      "Derive the smallest unit that shades the scene(s) within the error budget, print every "
      "field\n"
      "with how it was derived (with the measured numbers), and the error the bit-accurate model\n"
      "reaches on each scene with it. --json writes a UnitConfig file for --config.\n"
      "Rules:\n" +
          config_rules_text() +
          "Exits 1 when the unit misses the budget on a scene (measured), saying which part by\n"
          "shading the scene again: the specular unit's function (exact pow meets it), a format\n"
          "(formats that lose nothing meet it), else the Taylor setup or N.L gate; or the cycles "
          "target,\n"
          "naming the resource that limits it (port words per triangle or span, table reload, the\n"
          "specular unit's initiation interval, a frame's fixed overhead).");
  sub->add_option("scenes", o->scenes, "scene JSON files")->required()->check(CLI::ExistingFile);
  sub->add_option(
         "--budget", o->budget_lsb,
         "error budget in output LSBs (default: the smallest error_budget_lsb of the scenes)")
      ->check(positive_number());
  sub->add_option("--out-bits", o->out_bits, "output bits per channel")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  sub->add_option("--port-words", o->port_words,
                  "command port width of the unit (64-bit words per handshake; throughput only;\n"
                  "default: derived, see above)")
      ->check(CLI::IsMember({1, 2, 4, 8}));
  sub->add_option("--tri-queue", o->tri_queue,
                  "triangle queue depth of the unit (throughput only; 1 with host span setup;\n"
                  "default: derived, see above)")
      ->check(CLI::Range(1, 8));
  sub->add_option("--span-setup", o->span_setup,
                  "span setup in the unit or on the host (default: derived, see above)")
      ->check(CLI::IsMember({"unit", "host"}));
  sub->add_option(
         "--diffuse-colour", o->diffuse_colour,
         "diffuse colour rolled into the series or multiplied per pixel (default: derived)")
      ->check(CLI::IsMember({"series", "multiply"}));
  sub->add_option("--lanes", o->lanes,
                  "pixel lanes of the unit: pixels of one span a clock; the throughput structure\n"
                  "is derived to feed them (pixels do not depend on them)")
      ->check(one_of({1, 2, 4}))
      ->capture_default_str();
  sub->add_option(
         "--max-cycles-per-pixel", o->max_cycles_per_pixel,
         "the cycles per pixel every scene must stay within (cycle model, no gaps): the\n"
         "throughput structure is the cheapest that meets it; config exits 1 where none does.\n"
         "Default: 1.10 cycles per beat of the lanes, each scene's 1.10 x beats / pixels (1.10\n"
         "with one lane; not 1.10 / lanes, which spans shorter than the lanes or of no multiple\n"
         "of them put out of reach)")
      ->check(positive_number());
  sub->add_option(
      "--ideal-unit", o->ideal_unit,
      "hardware unit for scenes that name ideal, and no other: wpow (W_16 B=16 pipelined),\n"
      "lut or schlick (their default widths), or ideal to keep the yardstick (no RTL); default:\n"
      "W_16, else the first of W_32 and two interpolating LUTs that meets the budget");
  sub->add_option(
         "--clock-mhz", o->clock_mhz,
         "the clock the unit must close: 250 MHz by default (50 with --clock-target ice40);\n"
         "0: none, and then no synthesis runs. The derived unit is timed where\n"
         "--clock-target says; where it misses, it climbs the pipelining\n"
         "ladder, each rung timed: a register stage in the pixel combine (combine_stages 1),\n"
         "a second that splits its colour products (2), then, on a pipelined W_m unit, each\n"
         "squaring split over two cycles (square_stages 2). config keeps the first rung that\n"
         "meets the clock (each adds registers), else the fastest, names the path that limits\n"
         "it and exits 1. Runs shadesim area's flows (cached in --area-cache: minutes on a\n"
         "new unit, instant after)")
      ->check(non_negative_number());
  sub->add_option("--clock-target", o->clock_target,
                  "where the clock is timed: osu018 (Yosys onto the library, OpenSTA; --liberty\n"
                  "for another) or ice40 (an HX8K through nextpnr-ice40)")
      ->check(CLI::IsMember({"osu018", "ice40"}))
      ->capture_default_str();
  sub->add_option("--liberty", o->liberty,
                  "another standard-cell library for --clock-target osu018's flow")
      ->check(CLI::ExistingFile);
  sub->add_option("--area-cache", o->area_cache, "shadesim area's cache for the clock's flows")
      ->capture_default_str();
  sub->add_option(
         "--json", o->json_path,
         "write the UnitConfig JSON (loadable by --config) with a \"derivation\" block: reasons, "
         "measurements, errors")
      ->check(output_file());
  sub->callback([o, &exit_code]() { exit_code = run_config(*o); });
}

}  // namespace shadesim
