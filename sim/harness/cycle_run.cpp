#include "sim/harness/cycle_run.h"

namespace shadesim {

CycleRun run_cycle_model(const std::vector<uint64_t>& words, const Stimulus& stim,
                         CycleConfig timing) {
  CycleModel m(timing);
  CommandDriver driver(words, stim, timing.port_words);
  CycleRun r;
  r.words = words.size();
  r.beats = (words.size() + static_cast<size_t>(timing.port_words) - 1) /
            static_cast<size_t>(timing.port_words);
  uint64_t cycle = 0;
  CycleBreakdown& b = r.breakdown;
  while (!driver.done() || !m.idle()) {
    const CycleModel::Edge e = m.clock(driver.valid(), driver.beat(), stim.pix_ready(cycle));
    driver.clock(e.cmd_fire);
    switch (e.category) {
      case CycleModel::Category::kPixel:
        ++b.pixel;
        break;
      case CycleModel::Category::kBackPressure:
        ++b.back_pressure;
        break;
      case CycleModel::Category::kUnitStall:
        ++b.unit_stall;
        break;
      case CycleModel::Category::kCommandGap:
        ++b.command_gap;
        break;
      case CycleModel::Category::kMaterial:
        ++b.material;
        break;
      case CycleModel::Category::kTable:
        ++b.table;
        break;
      case CycleModel::Category::kCommandWords:
        ++b.command_words;
        break;
      case CycleModel::Category::kSetupLoad:
        ++b.setup_load;
        break;
    }
    if (e.pix_fire) {
      r.pixels += static_cast<uint64_t>(e.pix_count);
      if (e.pix_eor) r.scanlines.push_back({e.pix_y, cycle, e.pix_x + e.pix_count - 1});
    }
    ++cycle;
  }
  r.cycles = cycle;
  return r;
}

}  // namespace shadesim
