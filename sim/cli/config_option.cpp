#include "sim/cli/config_option.h"

#include <filesystem>

#include "sim/eda/verilator/rtl_build.h"

namespace shadesim {

CLI::Validator unit_choice_validator() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text == kOwnUnit || text == kDefaultUnit) return {};
        if (std::filesystem::path(text).extension() == ".json") {
          return std::filesystem::is_regular_file(text) ? ""
                                                        : "unit file " + text + " does not exist";
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

}  // namespace shadesim
