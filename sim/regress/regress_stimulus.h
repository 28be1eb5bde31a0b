// The stimulus a regression runs under (sim/harness/stimulus.h: idle gaps on the command port,
// back-pressure on the pixel port). Its command-line options: sim/cli/stimulus_options.h.
#pragma once

namespace shadesim {

// The regression's stimulus: `regress` runs under it by default, and `cycles --regress-stimulus`
// counts the cycles of the same runs (with the same --seed).
struct StimulusPercentages {
  int gap_pct, max_gap, stall_pct;
};
inline constexpr StimulusPercentages kRegressStimulus{20, 8, 20};

}  // namespace shadesim
