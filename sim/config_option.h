// --config FILE.json for the commands that shade on a unit (render, cycles): the unit is then
// exactly the file's (model/unit_config_file.h), so the options that would change it are
// excluded, and a scene that needs more than the file gives is an error naming the field.
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/frame.h"
#include "model/unit_config_file.h"
#include "sim/width_options.h"

namespace shadesim {

// Call after add_width_options and after adding the options named in `also_excluded`.
inline void add_config_option(CLI::App& sub, std::string& path,
                              const std::vector<std::string>& also_excluded) {
  CLI::Option* config =
      sub.add_option("--config", path,
                     "shade on exactly this unit: a UnitConfig JSON file (as `shadesim config "
                     "--json` writes or a\n"
                     "stream header carries; omitted fields take UnitConfig's defaults: the width "
                     "defaults listed\n"
                     "here, 1 channel, 1 light, specular ideal). Excludes the width options. "
                     "Without it the widths\n"
                     "come from the options and the structure and specular unit from the scene.");
  config->check(CLI::ExistingFile);
  for (CLI::Option* o : sub.get_options()) {
    if (o != config && (o->get_group() == kWidthGroup || o->get_group() == kUnitWidthGroup))
      config->excludes(o);
  }
  for (const auto& name : also_excluded) config->excludes(sub.get_option(name));
}

// FrameOptions for a --config file: the file's unit, fixed (structure and specular unit included).
inline void use_config_file(const std::string& path, FrameOptions& fo) {
  fo.base = load_unit_config(path);
  fo.fixed_unit = true;
}

// prepare_frame, with the --config file named in a scene-does-not-fit error.
inline PreparedFrame prepare_frame_on(const std::string& scene, const FrameOptions& fo,
                                      const std::string& config_path) {
  if (config_path.empty()) return prepare_frame(scene, fo);
  try {
    return prepare_frame(scene, fo);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(e.what()) + " (the unit of --config " + config_path +
                                ")");
  }
}

}  // namespace shadesim
