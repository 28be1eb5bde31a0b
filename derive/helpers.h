// Small helpers the derive/ sources share. Included by derive/*.cpp only: their names are short.
#pragma once

#include <cstdint>
#include <sstream>
#include <string>

#include "host/vec3.h"
#include "model/digit_grouping.h"

namespace shadesim {

inline double channel(const Vec3& v, int c) { return c == 0 ? v.x : (c == 1 ? v.y : v.z); }

inline std::string fmt(double x, int precision = 4) {
  std::ostringstream os;
  os.precision(precision);
  os << x;
  return os.str();
}

inline std::string fixed(double x, int precision = 3) {
  std::ostringstream os;
  os << std::fixed;
  os.precision(precision);
  os << x;
  return os.str();
}

// 1.1 -> "1.10", 1.125 -> "1.125": the target as the options spell it, at least two decimals.
inline std::string target_text(double target) {
  std::string s = fixed(target, 6);
  while (s.size() > s.find('.') + 3 && s.back() == '0') s.pop_back();
  return s;
}

}  // namespace shadesim
