// Integers as people read them in reports: 12345678 -> "12,345,678", -1234 -> "-1,234".
#pragma once

#include <cstdint>
#include <string>
#include <type_traits>

namespace shadesim {

template <typename Int>
std::string grouped(Int value) {
  static_assert(std::is_integral_v<Int>, "grouped() groups the digits of an integer");
  const bool negative = value < 0;
  std::string digits;
  if constexpr (std::is_signed_v<Int>) {
    // The magnitude in 64 unsigned bits, so the most negative value has one too (and a narrow
    // type's arithmetic is not promoted back to a signed int).
    const uint64_t bits = static_cast<uint64_t>(static_cast<int64_t>(value));
    digits = std::to_string(negative ? uint64_t{0} - bits : bits);
  } else {
    digits = std::to_string(static_cast<uint64_t>(value));
  }
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3)
    digits.insert(static_cast<size_t>(i), ",");
  return negative ? "-" + digits : digits;
}

}  // namespace shadesim
