// The one meaning of --config in every command that shades a scene (render, cycles, regress,
// explore, area): the unit is
//   own      the scene's own unit, as `shadesim config SCENE` derives it (the default);
//   default  UnitConfig's default widths, with the scene's channels, lights and specular unit
//            (what the width options change: giving one selects it);
//   NAME     a named build (sim/harness/builds.json, `shadesim cosim --list`);
//   FILE     a UnitConfig JSON file (as `shadesim config --json` writes it).
// The --config option itself (its check, what it excludes): sim/cli/config_option.h.
#pragma once

#include <stdexcept>
#include <string>

#include "host/frame.h"
#include "sim/engines/unit_widths.h"
#include "sim/harness/rtl_config.h"

namespace shadesim {

inline constexpr const char* kOwnUnit = "own";
inline constexpr const char* kDefaultUnit = "default";

// The unit `text` names for `scene`, with its label ("own:sphere", "default", the build name, the
// file). Throws std::invalid_argument naming `option` for an unknown name or a bad file. For
// own, `origin` (when given) gets how the unit came (own_unit).
RtlConfig resolve_unit(const std::string& text, const std::string& scene,
                       const std::string& option = "--config", std::string* origin = nullptr);

// The scene's own unit: the smallest unit that shades it within its error budget, with real
// specular hardware, or none when the scene has no specular term (derive/derive_config.h). Derived
// once per content and reused (sim/engines/derivation_cache.h); `origin` (when given) gets which,
// for the unit line: "cached derivation, PATH" or "derived, cached as PATH".
RtlConfig own_unit(const std::string& scene, std::string* origin = nullptr);

// What a unit line says of the --config in effect: "--config own: cached derivation, PATH",
// "--config default", "--config lut_d".
inline std::string unit_choice_note(const std::string& choice, const std::string& origin) {
  return "--config " + choice + (origin.empty() ? "" : ": " + origin);
}

// Sets `fo`'s unit from the --config in effect; returns what its unit line says of it
// (unit_choice_note).
inline std::string use_unit_choice(const std::string& choice, const std::string& scene,
                                   const WidthOptions& widths, FrameOptions& fo) {
  if (choice == kDefaultUnit) {
    fo.base = widths.to_config();
    return unit_choice_note(choice, "");
  }
  std::string origin;
  const RtlConfig unit = resolve_unit(choice, scene, "--config", &origin);
  fo.base = unit.unit;
  fo.fixed_unit = true;
  return unit_choice_note(choice, origin);
}

// prepare_frame, with the --config unit named in a scene-does-not-fit error.
inline PreparedFrame prepare_frame_on(const std::string& scene, const FrameOptions& fo,
                                      const std::string& choice) {
  if (choice == kDefaultUnit) return prepare_frame(scene, fo);
  try {
    return prepare_frame(scene, fo);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(e.what()) + " (the unit of --config " + choice + ")");
  }
}

// frame_unit, with the --config unit named in a scene-does-not-fit error.
inline UnitConfig frame_unit_on(const Scene& scene, const std::string& scene_path,
                                const FrameOptions& fo, const std::string& choice) {
  if (choice == kDefaultUnit) return frame_unit(scene, scene_path, fo);
  try {
    return frame_unit(scene, scene_path, fo);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(e.what()) + " (the unit of --config " + choice + ")");
  }
}

}  // namespace shadesim
