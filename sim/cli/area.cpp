// shadesim area (--config FILE.json | SCENE): its options; the engine is sim/engines/area.h.
#include "sim/engines/area.h"

#include <CLI/CLI.hpp>
#include <memory>
#include <stdexcept>
#include <string>

#include "sim/cli/commands.h"
#include "sim/cli/config_option.h"
#include "sim/cli/output_paths.h"
#include "sim/eda/sta/liberty_flow.h"

namespace shadesim {

void register_area(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<AreaCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "area",
      "Area and timing of one unit configuration, synthesised from rtl/*.sv with Yosys:\n"
      "  cells        generic cells of the flattened unit after synth -flatten and\n"
      "               abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX (2-input gates, MUXes, flip-flops)\n"
      "  transistors  Yosys's CMOS estimate of those cells (stat -tech cmos; flip-flops have no\n"
      "               CMOS cost in Yosys and are not included)\n"
      "  flip-flops   the flip-flops among them (with those the table RAM was mapped to)\n"
      "  GE           NAND2 gate equivalents: (transistors less Yosys's flip-flop cost) / 4 + 6\n"
      "               per flip-flop, the table RAM's flip-flops left out "
      "(sim/eda/yosys/generic_area.h)\n"
      "  RAM bits     table memories (exponent LUT entries), apart: an SRAM macro, not logic\n"
      "  per module   cells, transistors, FFs, GE and RAM bits per instance of span_setup, "
      "series_engine, specular_unit, "
      "pixel_combine\n"
      "               and shade_unit's own glue (decoder, registers, control), from the same flow\n"
      "               with those modules kept: read the shares (the kept total exceeds the flat "
      "one)\n"
      "  library      the unit mapped onto a standard-cell library (default: osu018 0.18 um,\n"
      "               --liberty FILE for another) by Yosys dfflibmap + abc -liberty, fanout-\n"
      "               buffered (at most 8 cell inputs a net), and timed by OpenSTA: area (um^2,\n"
      "               NAND2 equivalents), cells, flip-flops, Fmax = 1000 / (4 ns - worst slack)\n"
      "               under stated constraints (clock uncertainty, the ports' drive and load;\n"
      "               sim/eda/sta/sta_constraints.h)\n"
      "               and its critical path; with a SCENE, Mpixel/s = Fmax / cycles per pixel\n"
      "               (a table memory mapped as a register file, timed; "
      "sim/eda/sta/liberty_flow.h)\n"
      "  iCE40        SB_LUT4 / SB_DFF* / SB_CARRY / SB_RAM40_4K counts from synth_ice40, whether\n"
      "               that fits an HX8K (7,680 logic cells), and where it does, Fmax of clk_i "
      "from\n"
      "               nextpnr-ice40 place and route\n"
      "  estimate     the fast estimate (what explore shows for unsynthesised width points): this\n"
      "               unit scaled from the nearest OTHER measured unit in the cache, and its "
      "error\n"
      "               against this measurement\n"
      "Results are cached per configuration (key: parameters, RTL sources, tool versions, "
      "scripts).\n"
      "A cold run takes minutes (several Yosys runs side by side); a cache hit is instant.");
  sub->add_option("--config", o->config_path,
                  "the unit: own (the default: SCENE's own unit, as `shadesim config "
                  "--clock-mhz 0` derives it: unpipelined), default\n(the default widths, SCENE's "
                  "structure), a named build "
                  "(shadesim cosim --list) or a UnitConfig\nFILE.json")
      ->check(unit_choice_validator());
  sub->add_option("scene", o->scene, "scene JSON file: measure the unit --config names for it")
      ->check(CLI::ExistingFile);
  sub->add_option("--cache", o->cache_dir, "cache folder for results")->capture_default_str();
  sub->add_option("--json", o->json_path, "also write the report as JSON")->check(output_file());
  sub->add_option("--rtl-dir", o->rtl_dir,
                  "synthesise the rtl/*.sv of DIR instead of this tree's (an A/B against another "
                  "commit's RTL: git worktree add /tmp/old COMMIT; --rtl-dir /tmp/old/rtl)")
      ->check(CLI::ExistingDirectory);
  sub->add_flag("--no-pnr", o->no_pnr,
                "skip nextpnr-ice40 place and route (no Fmax; much quicker)");
  CLI::Option* liberty =
      sub->add_option("--liberty", o->liberty,
                      "map onto this Liberty (.lib) library instead of osu018 (" +
                          std::string(kDefaultLiberty) + ")")
          ->check(CLI::ExistingFile);
  sub->add_flag("--no-liberty", o->no_liberty,
                "skip the standard-cell mapping and OpenSTA (no um^2, no library Fmax)")
      ->excludes(liberty);
  sub->add_flag("--no-power", o->no_power,
                "skip the energy per pixel (with a scene, the library netlist's power under the\n"
                "scene's own switching activity: a traced co-simulation, then OpenSTA\n"
                "report_power; docs/power.md)");
  sub->callback([o, &exit_code]() {
    if (o->config_path.empty() && o->scene.empty()) {
      throw std::invalid_argument(
          "area: give a SCENE (its own unit), or --config NAME|FILE.json (see shadesim area "
          "--help)");
    }
    exit_code = run_area(*o);
  });
}

}  // namespace shadesim
