#include "sim/jobs/unit_choice.h"

#include <filesystem>

#include "host/frame.h"
#include "host/scene_config.h"
#include "sim/eda/rtl_build.h"

namespace shadesim {

namespace fs = std::filesystem;

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
