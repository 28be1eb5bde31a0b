// The N.L gate near the terminator. The unit opens light l's specular term where its
// fixed-point N.L series is > 0. Where the exact N.L is within the series' error of 0, series
// truncation and coefficient rounding can put that sign the other way. The whole specular term
// then appears or vanishes: ks t^n, 33 LSB at n = 1 on a bright highlight. No budget share of
// the width rules covers that step, so it is measured: the frame is shaded on the unit and on a
// copy with the most fraction bits UnitConfig allows, and a pixel whose gates differ and whose
// codes differ by more than the budget is a flip over the budget.
#pragma once

#include <cstddef>

#include "host/frame.h"
#include "host/prepared_scene.h"
#include "model/unit_config.h"

namespace shadesim {

struct GateFlips {
  size_t pixels = 0;  // pixels whose gate flipped with an output more than the budget off
  int max_lsb = 0;    // the largest such output difference (codes)
  // Fraction bits added to both series and coef that leave no such pixel (0: none needed;
  // -1: none short of UnitConfig's widest formats), and the unit with them.
  int fix_bits = 0;
  UnitConfig fixed;
};

// Widen `unit`'s series and coef formats by `bits` fraction bits each (integer bits, rounding
// and overflow unchanged), at most to UnitConfig's limits.
UnitConfig with_more_fraction_bits(const UnitConfig& unit, int bits);

// A frame's setup and visibility shaded on `unit` (re-encoded for it) against the widest copy.
GateFlips measure_gate_flips(const Scene& scene, const SetupResult& setup,
                             const Visibility& visibility, const UnitConfig& unit,
                             int budget_codes);
inline GateFlips measure_gate_flips(const PreparedFrame& frame, const UnitConfig& unit,
                                    int budget_codes) {
  return measure_gate_flips(frame.scene, frame.setup, frame.visibility, unit, budget_codes);
}
// The same on a prepared scene; the shading of `unit` also gives its error against the frame's
// reference, which scene_error then finds measured (PreparedScene::error_on). With threads 2
// (0: the hardware's) the unit and its yardstick are shaded side by side, holding two streams.
GateFlips measure_gate_flips(const PreparedScene& frame, const UnitConfig& unit, int budget_codes,
                             int threads = 1);

}  // namespace shadesim
