// Wall time of a step, in seconds, for the timing lines commands print.
#pragma once

#include <chrono>

namespace shadesim {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace shadesim
