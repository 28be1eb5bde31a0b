// What the command drivers put on cmd_data_i while cmd_valid_i is low: random words instead of
// the next beat held early, so an RTL that looks at the data without valid shows it.
// A pure function of the stimulus seed and the cycle, so a run repeats.
#pragma once

#include <array>
#include <cstdint>

#include "sim/harness/stimulus.h"

namespace shadesim {

inline std::array<uint64_t, 8> idle_noise(const Stimulus& stim, uint64_t cycle) {
  std::array<uint64_t, 8> words{};
  for (size_t k = 0; k < words.size(); ++k) {
    words[k] =
        splitmix64((stim.seed ^ 0x5EEDC0DE1D1E0000ull) * 0xD1342543DE82EF95ull + 8 * cycle + k);
  }
  return words;
}

}  // namespace shadesim
