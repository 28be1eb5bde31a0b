#include "model/json_error.h"

#include <algorithm>
#include <cstddef>

namespace shadesim {
namespace {

std::string line_column(const std::string& text, size_t byte) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return ":" + std::to_string(line) + ":" + std::to_string(column);
}

}  // namespace

JsonTextError describe_json_error(const std::string& text, const nlohmann::json::exception& e) {
  JsonTextError out;
  std::string reason = e.what();
  if (const auto* parse = dynamic_cast<const nlohmann::json::parse_error*>(&e)) {
    // "[json.exception.parse_error.N] parse error at line L, column C: <reason>"
    const auto colon = reason.find(": ");
    out.reason = colon == std::string::npos ? reason : reason.substr(colon + 2);
    out.place = line_column(text, parse->byte > 0 ? parse->byte - 1 : 0);
    return out;
  }
  const auto bracket = reason.find("] ");
  out.reason = bracket == std::string::npos ? reason : reason.substr(bracket + 2);
  const auto open = out.reason.find('\''), close = out.reason.rfind('\'');
  if (open != std::string::npos && close > open + 1) {
    const size_t at = text.find(out.reason.substr(open + 1, close - open - 1));
    if (at != std::string::npos) out.place = line_column(text, at);
  }
  if (e.id == 406) out.reason += " (expected a number within double range)";
  return out;
}

}  // namespace shadesim
