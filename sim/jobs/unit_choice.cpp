#include "sim/jobs/unit_choice.h"

#include <filesystem>

#include "host/frame.h"
#include "host/scene_config.h"
#include "sim/eda/rtl_build.h"

namespace shadesim {

namespace fs = std::filesystem;

CLI::Validator unit_choice_validator() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text == kOwnUnit || text == kDefaultUnit) return {};
        if (fs::path(text).extension() == ".json") {
          return fs::is_regular_file(text) ? "" : "unit file " + text + " does not exist";
        }
        for (const RtlConfig& b : load_named_builds(named_builds_path())) {
          if (b.name == text) return {};
        }
        return "'" + text +
               "' is not own, default, a named build (shadesim cosim --list) or a "
               "UnitConfig FILE.json";
      },
      "own|default|NAME|FILE.json");
}

RtlConfig own_unit(const std::string& scene) {
  RtlConfig c;
  c.name = std::string(kOwnUnit) + ":" + fs::path(scene).stem().string();
  c.unit = derive_config({scene}, DeriveOptions{}).config;
  return c;
}

RtlConfig resolve_unit(const std::string& text, const std::string& scene,
                       const std::string& option) {
  if (text == kOwnUnit) return own_unit(scene);
  if (text == kDefaultUnit) {
    RtlConfig c;
    c.name = kDefaultUnit;
    c.unit = prepare_frame(scene, FrameOptions{}).config;
    return c;
  }
  return resolve_rtl_config(text, option);
}

}  // namespace shadesim
