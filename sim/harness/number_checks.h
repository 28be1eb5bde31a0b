// Range checks for numeric options whose message names the bound in words: CLI11's
// PositiveNumber and NonNegativeNumber print their range as 0 to DBL_MAX in full (a 309-digit
// number). CLI11 adds the option's name: "--budget: must be greater than 0, got 0".
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>
#include <vector>

namespace shadesim {

namespace detail {
inline CLI::Validator number_at_least(bool allow_zero) {
  return CLI::Validator(
      [allow_zero](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || std::isnan(v)) {
          return "expected a number, got '" + text + "'";
        }
        if (std::isinf(v)) return "expected a finite number, got '" + text + "'";
        if (allow_zero ? v < 0 : v <= 0) {
          return std::string(allow_zero ? "must be 0 or more" : "must be greater than 0") +
                 ", got " + text;
        }
        return "";
      },
      allow_zero ? "NONNEGATIVE" : "POSITIVE");
}
}  // namespace detail

// > 0 and finite.
inline CLI::Validator positive_number() { return detail::number_at_least(false); }
// >= 0 and finite.
inline CLI::Validator non_negative_number() { return detail::number_at_least(true); }

// One of `allowed`: "3 not in {1,2,4}" as CLI::IsMember says it, and for text that is no whole
// number "x not in {1,2,4}" too (IsMember on an int option says only "x").
inline CLI::Validator one_of(const std::vector<int>& allowed) {
  std::string set;
  for (const int a : allowed) set += (set.empty() ? "" : ",") + std::to_string(a);
  set = "{" + set + "}";
  return CLI::Validator(
      [allowed, set](std::string& text) -> std::string {
        int v = 0;
        if (CLI::detail::lexical_cast(text, v)) {
          for (const int a : allowed) {
            if (v == a) return "";
          }
        }
        return text + " not in " + set;
      },
      set);
}

}  // namespace shadesim
