// shadesim config SCENE...: its options; the engine is sim/jobs/config.h.
#include "sim/jobs/config.h"

#include <CLI/CLI.hpp>
#include <memory>

#include "sim/cli/commands.h"
#include "sim/cli/number_checks.h"
#include "sim/cli/output_paths.h"

namespace shadesim {

void register_config(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ConfigOptions>();
  CLI::App* sub = app.add_subcommand(
      "config",
      "Derive the smallest unit that shades the scene(s) within the error budget, print every "
      "field\n"
      "with how it was derived (with the measured numbers), and the error the bit-accurate model\n"
      "reaches on each scene with it. --json writes a UnitConfig file for --config.\n"
      "Rules:\n"
      "  channels     1 if every scene is grey, else 3\n"
      "  lights       the most directional lights of any scene\n"
      "  specular     none (no specular unit, no specular series) when no material has a\n"
      "               specular term (specular colour x light colour 0 in every channel); else\n"
      "               the unit the materials name (all must name one); `ideal` is not hardware\n"
      "               (its RTL slot outputs 0), so it becomes W_16 B=16 pipelined, or where\n"
      "               that misses the budget on the scenes (measured), the first that meets it\n"
      "               of W_16 with zeta fitted, W_32 (plain, fitted) and interpolating LUTs; a\n"
      "               named lut, schlick or wpow whose defaults miss gets the first of its kind's\n"
      "               fields that meets it (LUT entries, entry bits, interpolation, shared or\n"
      "               per-exponent; Schlick's fitted n' and divider widths; W_m's squarings,\n"
      "               base bits, fitted zeta). Budget first: a unit within the budget is taken\n"
      "               unless another within it costs no more than max(target, the first's\n"
      "               cycles + 1 %); where none meets the budget the closest is kept and its\n"
      "               limit named. The reason lists each unit tried with its error and cycles\n"
      "  xy_bits      enough unsigned bits for the largest image width and height (at least 4)\n"
      "  offset_bits  enough signed bits for the largest |dx|, |dy| of a span's first pixel from\n"
      "               its triangle's origin, so no triangle is re-origined\n"
      "  series       integer bits: the fewest (>= 2) holding every series value at every pixel\n"
      "               (measured on a trial unit that loses nothing); fraction bits F: the proven\n"
      "               drift bound over the longest span L, 2^-F (1 + L(L-1)/2) (half with "
      "rounding),\n"
      "               times the gain G of the series into one output channel, <= budget/4 LSB\n"
      "  coef         integer bits: wrapping, the series' (exact modulo 2^iwl: span setup "
      "multiplies\n"
      "               coefficients only by integers); fraction bits: coefficient rounding "
      "2^-(F+1)\n"
      "               times the largest 1+|dx|+|dy|+dx^2+|dx dy|+dy^2 of a pixel from its "
      "triangle's\n"
      "               origin, times G, <= budget/4 LSB\n"
      "  coef_term_iwl  coefficient packing: T0 keeps coef's integer bits (it wraps); T1..T5 the\n"
      "               fewest saturating integer bits holding every measured |T_t| + 1 LSB\n"
      "  out_bits     as requested (--out-bits)\n"
      "  lanes        as requested (--lanes): pixels of one span a clock\n"
      "  port_words, tri_queue, span_setup, start_depth, material_buffers, and a Schlick or\n"
      "               W_m unit's timing: the cheapest structure that runs every scene within\n"
      "               1.10 cycles per beat by the cycle model, no gaps (a beat: up to `lanes`\n"
      "               pixels of one span; one lane, 1.10 cycles per pixel; with 4 lanes\n"
      "               bench/scenes/sphere_1024.json's 230,466 beats for 759,144 pixels make\n"
      "               0.334, not 1.10 / 4 = 0.275, below its 0.304 floor), or within\n"
      "               --max-cycles-per-pixel where given.\n"
      "               Cheapest first: host span setup (the host sends each span's start values:\n"
      "               no span setup, no coefficient banks, tri_queue 1) before unit setup,\n"
      "               iterative before pipelined, fewer port words (1, 2, 4, 8), a shallower\n"
      "               start bank (1, 2) or triangle queue (1..8), 1 material buffer before 2.\n"
      "               Where none meets it: the fastest, and each scene over the target named\n"
      "               with the resource that limits it (--port-words, --tri-queue,\n"
      "               --span-setup hold a knob)\n"
      "  combine_stages, square_stages  the first rung of the pipelining ladder that meets\n"
      "               the clock (250 MHz in osu018 unless --clock-mhz says otherwise): none,\n"
      "               combine_stages 1, 2, then a W_m unit's square_stages 2; else the fastest\n"
      "               (each timed; see --clock-mhz). With --clock-mhz 0: none (0 and 1)\n"
      "  diffuse_colour  multiply with 3 channels (one N.L series per light, times kd_c L_c per\n"
      "               pixel and channel), series with 1 (--diffuse-colour to choose)\n"
      "  spec_colour  integer bits: every ks_c L_c (and kd_c L_c multiplied) unsaturated;\n"
      "               fraction bits: rounding 2^-(F+1) per word (and N.L truncated to F bits x\n"
      "               kd_c L_c multiplied) summed over the lights <= 3/16 budget; >= 12 (default)\n"
      "  specular out fraction bits: truncation 2^-F x the summed ks_c L_c <= budget/16; >= 16\n"
      "  series also holds every colour product (intensity or N.L times a colour word)\n"
      "  G = sum over lights of (1, or max kd_c L_c multiplied, + max specular colour x the\n"
      "  unit's slope on its series), the\n"
      "  slope from t^n's <= n on [0, 1] through setup's pre-scaling. The Taylor error keeps the\n"
      "  whole budget in setup; the fixed-point error adds at most 3/4 of it.\n"
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
