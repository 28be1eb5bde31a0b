// Where and why nlohmann::json rejected a text, for the readers' error messages (scene files,
// UnitConfig files). One home for the rule, so every reader names the same place.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace shadesim {

struct JsonTextError {
  std::string place;   // ":LINE:COLUMN" (1-based), or empty when the text does not locate it
  std::string reason;  // nlohmann's message without its "[json.exception...]" prefix
};

// A parse_error names the byte where parsing stopped (past the end for early EOF). A number
// beyond double range ("1e999") is out_of_range.406 instead and carries no position: its quoted
// token is looked up in the text.
JsonTextError describe_json_error(const std::string& text, const nlohmann::json::exception& e);

}  // namespace shadesim
