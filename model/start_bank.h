// StartBank: with host span setup (UnitConfig::span_setup kHost) the unit's start values come
// from the SPAN payload; rtl/start_bank.sv holds them until the engines load them. The values
// are the series format's raw bits, so the model only reads them out per series.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/span_setup.h"
#include "model/start_packing.h"

namespace shadesim {

class StartBank {
 public:
  // Series i's (v, d, d2) from a SPAN's start values (StartLayout order).
  SeriesStart operator()(const std::vector<int64_t>& starts, int i) const {
    const size_t at = static_cast<size_t>(i) * StartLayout::kValuesPerSeries;
    return {starts[at], starts[at + 1], starts[at + 2]};
  }
};

}  // namespace shadesim
