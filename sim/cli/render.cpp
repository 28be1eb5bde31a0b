// shadesim render SCENE: its options; the engine is sim/engines/render.h.
#include "sim/engines/render.h"

#include <CLI/CLI.hpp>
#include <memory>

#include "sim/cli/commands.h"
#include "sim/cli/config_option.h"
#include "sim/cli/output_paths.h"
#include "sim/cli/width_options.h"
#include "sim/harness/number_checks.h"

namespace shadesim {

void register_render(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand(
      "render",
      "Shade a scene through the bit-accurate model and the double-precision reference; write\n"
      "model.png, reference.png, error.png (heat map) and compare.png, and print the error\n"
      "(max/mean LSB, PSNR) beside the cost (triangles split, stream words, model speed).");
  sub->add_option("scene", opts->scene, "scene JSON file (see scenes/)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("-o,--out", opts->out_dir, "output directory (default out/<scene name>)")
      ->check(output_folder());
  sub->add_option("--json", opts->json_path, "write the figures as JSON to this file")
      ->check(output_file());
  sub->add_option("--save-stream", opts->stream_path,
                  "save the command stream (text form) for replay")
      ->check(output_file());
  sub->add_option("--budget", opts->budget_lsb,
                  "Taylor error budget per triangle in output LSBs (default: the scene's, else 1)")
      ->check(positive_number());
  sub->add_option("--max-depth", opts->max_depth, "subdivision depth limit per triangle")
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
  sub->add_option("--specular", opts->specular,
                  "override the specular unit: ideal|lut|schlick|wpow");
  sub->add_option("--heat-scale", opts->heat_scale_lsb, "error heat map full scale in LSBs")
      ->check(positive_number())
      ->capture_default_str();
  sub->add_flag("-q,--quiet", opts->quiet, "print nothing (use with --json)");
  sub->add_flag("--all-units", opts->all_units,
                "render with every specular unit (ideal, lut, schlick, wpow) and write units.png:\n"
                "the highlights side by side with the reference, and one error line per unit")
      ->excludes("--specular");
  add_width_options(*sub, opts->widths);
  add_config_option(*sub, opts->config, {"--specular", "--all-units"});
  sub->callback([opts, sub, &exit_code]() {
    opts->config = unit_choice_in_effect(*sub, opts->config, {"--specular", "--all-units"});
    exit_code = opts->all_units ? run_all_units(*opts) : run_render(*opts);
  });
}

}  // namespace shadesim
