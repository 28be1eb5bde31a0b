// The cycle model's testbench: CycleModel (model/cycle_model.h) clocked over a whole stream, its
// command port fed by a CommandDriver with the stimulus's idle gaps and its pixel port stalled by
// the stimulus's back-pressure (sim/harness/stimulus.h), the same pattern the RTL's driver and
// sink apply. With Stimulus{} (no gaps, always ready) its results equal CycleEstimate's
// (model/cycle_estimate.h) exactly.
#pragma once

#include <cstdint>
#include <vector>

#include "model/cycle_model.h"
#include "sim/harness/stimulus.h"

namespace shadesim {

// Runs `words` to the end (every beat accepted, every pixel out) and counts where the cycles went.
CycleRun run_cycle_model(const std::vector<uint64_t>& words, const Stimulus& stim,
                         CycleConfig timing = CycleConfig{});

}  // namespace shadesim
