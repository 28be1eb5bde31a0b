#include "sim/harness/rtl_config.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "model/command_stream.h"
#include "model/unit_config_file.h"

namespace shadesim {

std::vector<RtlConfig> load_named_builds(const std::string& path) {
  std::ifstream is(path);
  if (!is) throw std::invalid_argument(path + ": cannot open the named RTL builds");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(is);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(path + ": " + e.what());
  }
  if (!j.is_object()) throw std::invalid_argument(path + ": expected an object of named builds");
  std::vector<RtlConfig> builds;
  for (const auto& [name, b] : j.items()) {
    if (name.rfind('_', 0) == 0) continue;  // "_comment"
    const std::string where = path + ": " + name;
    if (!b.is_object() || !b.contains("unit")) {
      throw std::invalid_argument(where + ": expected {\"unit\": {...}, \"backends\": [...]}");
    }
    RtlConfig c;
    c.name = name;
    try {
      c.unit = overlay_unit_config(b.at("unit").dump(), UnitConfig{}, where + ".unit");
    } catch (const UnitConfigFileError& e) {
      throw std::invalid_argument(e.what());
    }
    for (auto it = b.begin(); it != b.end(); ++it) {
      if (it.key() != "unit" && it.key() != "backends" && it.key() != "fault_hooks") {
        throw std::invalid_argument(where + "." + it.key() +
                                    ": unknown key (expected unit, backends, fault_hooks)");
      }
    }
    if (b.contains("fault_hooks")) {
      if (!b.at("fault_hooks").is_boolean()) {
        throw std::invalid_argument(where + ".fault_hooks: expected true or false, got " +
                                    b.at("fault_hooks").dump());
      }
      c.faults.hooks = b.at("fault_hooks").get<bool>();
    }
    if (b.contains("backends")) {
      for (const auto& be : b.at("backends")) {
        if (!be.is_string() || (be != "cpp" && be != "systemc")) {
          throw std::invalid_argument(where + ".backends: expected \"cpp\" or \"systemc\", got " +
                                      be.dump());
        }
        c.backends.push_back(be.get<std::string>());
      }
    }
    builds.push_back(c);
  }
  return builds;
}

RtlConfig named_build(const std::string& path, const std::string& name) {
  std::string names;
  for (const RtlConfig& c : load_named_builds(path)) {
    if (c.name == name) return c;
    names += (names.empty() ? "" : ", ") + c.name;
  }
  throw std::invalid_argument("'" + name + "' is not a named RTL build in " + path +
                              "; expected one of " + names + ", or a UnitConfig FILE.json");
}

std::string fault_text(const InjectedFaults& f) { return f.hooks ? " fault-hooks" : ""; }

}  // namespace shadesim
