#include "sim/engines/unit_choice.h"

#include <filesystem>

#include "derive/derive_config.h"
#include "host/frame.h"
#include "sim/eda/verilator/rtl_build.h"
#include "sim/engines/derivation_cache.h"

namespace shadesim {

namespace fs = std::filesystem;

RtlConfig own_unit(const std::string& scene, std::string* origin) {
  RtlConfig c;
  c.name = std::string(kOwnUnit) + ":" + fs::path(scene).stem().string();
  const CachedDerivation d =
      cached_derive_config({scene}, DeriveOptions{}, default_unit_cache_dir());
  c.unit = d.derived.config;
  if (origin) *origin = d.origin();
  return c;
}

RtlConfig resolve_unit(const std::string& text, const std::string& scene, const std::string& option,
                       std::string* origin) {
  if (text == kOwnUnit) return own_unit(scene, origin);
  if (text == kDefaultUnit) {
    RtlConfig c;
    c.name = kDefaultUnit;
    c.unit = prepare_frame(scene, FrameOptions{}).config;
    return c;
  }
  return resolve_rtl_config(text, option);
}

}  // namespace shadesim
