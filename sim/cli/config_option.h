// --config for the commands that shade on a unit (render, cycles): own, default, a named build
// or a UnitConfig file (sim/engines/unit_choice.h says what each means). Own, a build or a file fix
// the unit, so the options that would change it are excluded; a scene that needs more than the unit
// gives is an error naming the field.
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/cli/width_options.h"
#include "sim/engines/unit_choice.h"

namespace shadesim {

// Accepts own, default, a named build or an existing .json file; the error lists the forms.
CLI::Validator unit_choice_validator();

// Call after add_width_options and after adding the options named in `also_excluded`.
inline void add_config_option(CLI::App& sub, std::string& text,
                              const std::vector<std::string>& also_excluded) {
  CLI::Option* config = sub.add_option(
      "--config", text,
      "the unit: own (the scene's own unit, as `shadesim config --clock-mhz 0` derives it,\n"
      "unpipelined: the default when no width or structure option is given), default (the width "
      "defaults listed here, with the\n"
      "scene's channels, lights and specular unit: what the width options change), a named build\n"
      "(shadesim cosim --list) or a UnitConfig FILE.json (omitted fields take the defaults).\n"
      "Own, a build or a file is exactly the unit: width options are refused beside it.");
  config->check(unit_choice_validator());
  for (CLI::Option* o : sub.get_options()) {
    if (o != config && (o->get_group() == kWidthGroup || o->get_group() == kUnitWidthGroup))
      config->excludes(o);
  }
  for (const auto& name : also_excluded) config->excludes(sub.get_option(name));
}

// The --config in effect: as given, else `default` when a width option or one of `structure`
// (options that choose the unit's structure or specular unit) was given, else `own`.
inline std::string unit_choice_in_effect(const CLI::App& sub, const std::string& given,
                                         const std::vector<std::string>& structure) {
  if (!given.empty()) return given;
  for (const CLI::Option* o : sub.get_options()) {
    const bool width = o->get_group() == kWidthGroup || o->get_group() == kUnitWidthGroup;
    if (width && o->count() > 0) return kDefaultUnit;
  }
  for (const auto& name : structure) {
    if (sub.get_option(name)->count() > 0) return kDefaultUnit;
  }
  return kOwnUnit;
}

}  // namespace shadesim
