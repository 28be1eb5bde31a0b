// Numbers in tables and messages: fixed-point text with a given number of decimals.
#pragma once

#include <fmt/format.h>

#include <string>

namespace shadesim {

inline std::string fixed_text(double v, int decimals) {
  return fmt::format("{:.{}f}", v, decimals);
}

}  // namespace shadesim
