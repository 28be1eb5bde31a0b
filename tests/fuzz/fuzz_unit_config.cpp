// libFuzzer target: the UnitConfig file reader (model/unit_config_file.h), on the file's text in
// memory (parse_unit_config: what load_unit_config runs after reading the file, without a file
// write per input). Every input must give a configuration that passes validate() and survives a
// JSON round trip, or throw UnitConfigFileError with a message.
#include <cstddef>
#include <cstdint>
#include <string>

#include "model/command_stream.h"
#include "model/unit_config_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const shadesim::UnitConfig config = shadesim::parse_unit_config(text, "unit.json");
    config.validate();
    // The header of a saved stream carries config_to_json: what was accepted must read back
    // as the same configuration.
    const std::string json = shadesim::config_to_json(config);
    const shadesim::UnitConfig again = shadesim::config_from_json(json, "<round trip>");
    if (shadesim::config_to_json(again) != json) {
      shadesim::fuzz::fail("config_to_json / config_from_json round trip changed the config");
    }
  } catch (const shadesim::UnitConfigFileError& e) {
    shadesim::fuzz::require_message(e);
  }
  return 0;
}
