// A unit configuration in a file: the UnitConfig JSON the command stream's header carries
// (config_to_json), hand-written or written by `shadesim config --json`. The reader is the
// header's own (model/command_stream.cpp); a file may omit fields and must not misspell them.
#pragma once

#include <stdexcept>
#include <string>

#include "model/unit_config.h"

namespace shadesim {

// A bad config file. what() names the file, then the line and column of a JSON syntax error (of
// the last character the parser read: the end of the offending token) or
// the field's JSON path (e.g. "specular.wpow.max_m") and what was expected.
class UnitConfigFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads a UnitConfig JSON file over `base`: fields the file omits keep base's values, unknown
// keys are errors (typos) except "derivation" (the reasons `shadesim config --json` writes,
// ignored), and the result passes UnitConfig::validate(). Throws
// UnitConfigFileError.
UnitConfig load_unit_config(const std::string& path, const UnitConfig& base = {});

// The same for a file's text held in memory; `source` names it in errors.
UnitConfig parse_unit_config(const std::string& text, const std::string& source,
                             const UnitConfig& base = {});

// A UnitConfig JSON object over `base` (e.g. one entry of sim/harness/builds.json): the same
// reader as a file's.
UnitConfig overlay_unit_config(const std::string& json_object, const UnitConfig& base,
                               const std::string& source);

}  // namespace shadesim
