// The one meaning of --config in every command that shades a scene (render, cycles, regress,
// explore, area): the unit is
//   own      the scene's own unit, as `shadesim config SCENE` derives it (the default);
//   default  UnitConfig's default widths, with the scene's channels, lights and specular unit
//            (what the width options change: giving one selects it);
//   NAME     a named build (sim/harness/builds.json, `shadesim cosim --list`);
//   FILE     a UnitConfig JSON file (as `shadesim config --json` writes it).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "sim/harness/rtl_config.h"

namespace shadesim {

inline constexpr const char* kOwnUnit = "own";
inline constexpr const char* kDefaultUnit = "default";

// Accepts own, default, a named build or an existing .json file; the error lists the forms.
CLI::Validator unit_choice_validator();

// The unit `text` names for `scene`, with its label ("own:sphere", "default", the build name, the
// file). Throws std::invalid_argument naming `option` for an unknown name or a bad file.
RtlConfig resolve_unit(const std::string& text, const std::string& scene,
                       const std::string& option = "--config");

// The scene's own unit: the smallest unit that shades it within its error budget, with real
// specular hardware, or none when the scene has no specular term (host/scene_config.h).
RtlConfig own_unit(const std::string& scene);

}  // namespace shadesim
