// Integers as people read them in reports: 12345678 -> "12,345,678", -1234 -> "-1,234".
#pragma once

#include <string>
#include <type_traits>

namespace shadesim {

template <typename Int>
std::string grouped(Int value) {
  static_assert(std::is_integral_v<Int>, "grouped() groups the digits of an integer");
  const bool negative = value < 0;
  std::string digits;
  if constexpr (std::is_signed_v<Int>) {
    // The magnitude as unsigned, so the most negative value has one too.
    using U = std::make_unsigned_t<Int>;
    digits = std::to_string(negative ? U(0) - static_cast<U>(value) : static_cast<U>(value));
  } else {
    digits = std::to_string(value);
  }
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3)
    digits.insert(static_cast<size_t>(i), ",");
  return negative ? "-" + digits : digits;
}

}  // namespace shadesim
